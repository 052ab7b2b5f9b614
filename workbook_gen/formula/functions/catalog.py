"""The function library describing itself: ``docs/functions.md``, generated from the registry.

One row per registered name: its family (the package that registers it) and module, how
many arguments it takes and of which kind, whether the column evaluator has a vectorised
form, whether it is volatile, where LibreOffice's dialect differs, and a test file that
calls it.  Made by
``python scripts/functions_doc.py``; ``tests/formula/functions/test_catalog.py`` checks that the
file is what the registry says.
"""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

from workbook_gen.formula.functions import REGISTRY
from workbook_gen.formula.functions.dialect import (LIBREOFFICE_DIFFERENCES, LIBREOFFICE_ERRORS,
                                                    NUMERIC_DEVIATIONS)
from workbook_gen.formula.functions.registry import FAMILIES

HEADER = """# Worksheet functions the audit recomputes

Generated from the registry (`workbook_gen/formula/functions/`) by
`python scripts/functions_doc.py`; `tests/formula/functions/test_catalog.py` checks it is current.
Kinds: `scalar` (one value; a larger reference is implicitly intersected), `range` (a
range or array taken whole), `ref` (the reference itself: ROW, OFFSET), `lazy` (evaluated
only if needed: IF, CHOOSE); the last kind repeats for further arguments. "vectorised":
the column evaluator computes a block of rows at once where the arguments allow; the
others go cell by cell. "LibreOffice": where its dialect (files LibreOffice saved) gives
another result. "test": a test file that calls the function in a formula.
"""


def _arity(f) -> str:
    if f.max_args is None:
        return f"{f.min_args}+"
    return str(f.min_args) if f.min_args == f.max_args else f"{f.min_args}-{f.max_args}"


def _libreoffice(name: str) -> str:
    notes = []
    for excel, lo in LIBREOFFICE_ERRORS.get(name, {}).items():
        notes.append(f"{excel.value} -> {lo.value}")
    if name in NUMERIC_DEVIATIONS:
        notes.append("numeric results")
    for d in LIBREOFFICE_DIFFERENCES:
        if re.match(rf"{re.escape(name)}\(", d.example):
            notes.append(d.situation)
    return "; ".join(dict.fromkeys(notes))


def _tests(root: Path) -> dict[str, str]:
    """name -> the first test file (sorted) whose text calls it as NAME( ."""
    found: dict[str, str] = {}
    call = re.compile(r"(?<![\w.])(?:_xlfn\.|_xlws\.)?([A-Z][A-Z0-9.]*)\(")
    tests = root / "tests"   # tests/<package>/test_<module>.py: named by that path
    paths = sorted(tests.rglob("*.py"), key=lambda p: (not p.name.startswith("test_"),
                                                       p.relative_to(tests).as_posix()))
    for path in paths:
        for name in set(call.findall(path.read_text(errors="replace"))):
            found.setdefault(name, path.relative_to(tests).as_posix())
    return found


def markdown(root: Path) -> str:
    tests = _tests(root)
    counts = Counter(f.family for f in REGISTRY.values())
    families = ", ".join(f"{family} {counts[family]}" for family in FAMILIES)
    lines = [HEADER, f"{len(REGISTRY)} functions. By family (each a package of "
             f"`workbook_gen/formula/functions/`, after Excel's categories): {families}.\n",
             "| function | family | module | arguments | kinds | vectorised | volatile "
             "| LibreOffice | test |",
             "|---|---|---|---|---|---|---|---|---|"]
    for name in sorted(REGISTRY):
        f = REGISTRY[name]
        module = f.module.partition(".")[2]  # the family's module that registers it
        lines.append(" | ".join([
            f"| `{name}`", f.family, module, _arity(f), ", ".join(f.kinds) or "-",
            "yes" if f.vector is not None else "", "yes" if f.volatile else "",
            _libreoffice(name).replace("|", "\\|"), tests.get(name, "none")]) + " |")
    untested = sorted(n for n in REGISTRY if n not in tests)
    lines += ["", f"Without a test that calls them in a formula ({len(untested)}): "
              + ", ".join(untested) + "."]
    return "\n".join(lines) + "\n"
