"""Every module's tests can be found from its path (issue 23 item 6).

The tests mirror the package tree:

* ``workbook_gen/<pkg>/<mod>.py``  -> ``tests/<pkg>/test_<mod>.py``
* ``workbook_gen/<mod>.py``        -> ``tests/test_<mod>.py`` (``tests/`` mirrors
  ``workbook_gen/``, so the top-level modules' tests sit at the top)
* ``workbook_gen/<pkg>/__init__.py`` holding logic -> ``tests/<pkg>/test_<pkg>.py``

A module may have more test files beside its own, named ``test_<mod>_<topic>.py`` in the
same folder. Tests of the project as a whole (the layering, the README's figures, this
tree, the fixture-workbook harness) sit at the top of ``tests/`` under the names in
``PROJECT_WIDE``; helpers shared by tests (``corpus_audits.py``, ``lo_sheet.py``,
``mp_reference.py``...) sit at the top too, without the ``test_`` prefix.

Only modules that hold no logic are exempt (``NO_LOGIC``, each with its reason, checked:
an exempt ``__init__`` defines no function or class). ``NOT_YET`` lists the modules whose
direct test is still to be written: it may only shrink.
"""

from __future__ import annotations

import ast
import fnmatch
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "workbook_gen"
TESTS = ROOT / "tests"

# modules without a test file of their own, and why none is needed
NO_LOGIC = {
    "version.py": "one constant, VERSION (tests/test_cli_startup.py reads it back via "
                  "--version, tests/workbook/test_sheets.py in the About sheet)",
    "mechanisms/_listing.py": "generated data: the digest and text of `workbook-gen list`, "
                              "checked against the templates by tests/test_cli_startup.py",
    "engines/__init__.py": "empty package marker",
    "auditor/__init__.py": "the face: re-exports audit and the report's classes",
    "batching/__init__.py": "the face: re-exports batch and its options",
    "evaluator/__init__.py": "the face: re-exports evaluate_cells and its result types",
    "expr/__init__.py": "the face: re-exports the tree's nodes and builders",
    "formula/__init__.py": "the face: re-exports parse, render and evaluate",
    "formula/functions/__init__.py": "the face: re-exports the registry",
    "tradeoff/__init__.py": "the face: re-exports measure, the report and the workbook",
    "workbook/__init__.py": "the face: re-exports write_workbook",
    "xlsx/__init__.py": "the face: re-exports the reader and its data classes",
    "formula/functions/*/__init__.py": "a function family's face: imports its modules, which "
                                       "register their functions (tested one module each)",
}

# modules whose direct test is still to be written: none since 2026-11-28 (it may only
# shrink; a new module comes with its test file)
NOT_YET: set[str] = set()

# test files at the top of tests/ that test the project as a whole, not one module
PROJECT_WIDE = {
    "test_test_tree.py": "this file: every module's tests can be found from its path",
    "test_fixture_workbooks.py": "every Excel-saved corpus workbook, cell by cell",
    "test_architecture.py": "docs/ARCHITECTURE.md's map against the package",
    "test_layers.py": "the import layers of the whole package, no cycles",
    "test_readme_figures.py": "the README's measured figures, from scripts/readme_figures.py",
    "test_docs_contract.py": "the user-facing contract in docs/ against the code",
}


def modules() -> list[str]:
    """Every module of workbook_gen, as its path relative to the package."""
    return sorted(p.relative_to(PACKAGE).as_posix() for p in PACKAGE.rglob("*.py"))


def expected_test(module: str) -> str:
    """The test file a module's path names (relative to tests/)."""
    path = Path(module)
    if path.name == "__init__.py":
        if path.parent == Path("."):
            return "test_workbook_gen.py"
        return (path.parent / f"test_{path.parent.name}.py").as_posix()
    return (path.parent / f"test_{path.stem}.py").as_posix()


def _defines(module: str) -> list[str]:
    """The functions and classes a module defines at its top."""
    tree = ast.parse((PACKAGE / module).read_text(encoding="utf-8"))
    return [n.name for n in tree.body
            if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))]


def exempt(module: str) -> bool:
    """In NO_LOGIC by name, or by a pattern ("formula/functions/*/__init__.py") when it
    defines nothing (numfmt/__init__.py, which holds logic, is not exempt)."""
    return module in NO_LOGIC or any(
        "*" in pattern and fnmatch.fnmatchcase(module, pattern) and not _defines(module)
        for pattern in NO_LOGIC)


def _missing() -> list[str]:
    return [m for m in modules()
            if not exempt(m) and not (TESTS / expected_test(m)).is_file()]


def test_the_mapping_follows_the_path():
    assert expected_test("cellref.py") == "test_cellref.py"
    assert expected_test("xlsx/reader.py") == "xlsx/test_reader.py"
    assert expected_test("formula/functions/numfmt/dates.py") == \
        "formula/functions/numfmt/test_dates.py"
    assert expected_test("xlmath/__init__.py") == "xlmath/test_xlmath.py"
    assert expected_test("__init__.py") == "test_workbook_gen.py"


def test_every_module_has_its_mirrored_test_file():
    missing = [m for m in _missing() if m not in NOT_YET]
    for m in missing:
        print(f"missing: tests/{expected_test(m)}  (for workbook_gen/{m})")
    assert not missing, f"{len(missing)} modules without their test file: " + ", ".join(
        f"workbook_gen/{m} -> tests/{expected_test(m)}" for m in missing)


def test_not_yet_only_shrinks():
    """A module of NOT_YET that has its test file now, or no longer exists, leaves it."""
    done = sorted(m for m in NOT_YET if m not in _missing())
    assert not done, f"remove from NOT_YET (tested or gone): {done}"


def test_exemptions_are_real_and_hold_no_logic():
    known = modules()
    for pattern in NO_LOGIC:
        assert fnmatch.filter(known, pattern), f"NO_LOGIC names no module: {pattern}"
    for module in filter(exempt, known):
        if module.endswith("__init__.py"):
            defined = _defines(module)
            assert not defined, f"{module} defines {defined}: it needs a test file of its own"


def _module_of(test: Path) -> str | None:
    """The module a test file is found from: tests/<pkg>/test_<mod>[_<topic>].py names
    workbook_gen/<pkg>/<mod>.py (or the package's __init__ by its name); None if none."""
    folder = PACKAGE.joinpath(*test.relative_to(TESTS).parent.parts)
    if not (folder / "__init__.py").is_file():
        return None
    stem = test.stem[len("test_"):]
    candidates = [p.stem for p in folder.glob("*.py") if p.stem != "__init__"]
    candidates.append("workbook_gen" if folder == PACKAGE else folder.name)
    hits = [c for c in candidates if stem == c or stem.startswith(c + "_")]
    if not hits:
        return None
    best = max(hits, key=len)
    module = folder / (best + ".py") if best in candidates[:-1] else folder / "__init__.py"
    return module.relative_to(PACKAGE).as_posix()


def test_every_test_file_names_its_module():
    """The other way round: each test file sits in a folder mirroring a package and
    starts with the name of one of its modules (or is one of PROJECT_WIDE)."""
    strays = []
    for test in sorted(TESTS.rglob("test_*.py")):
        if test.parent == TESTS and test.name in PROJECT_WIDE:
            continue
        if _module_of(test) is None:
            strays.append(test.relative_to(TESTS).as_posix())
    for stray in strays:
        print(f"stray: tests/{stray} names no module of its folder")
    assert not strays, strays
    assert _module_of(TESTS / "formula/functions/test_registry_edges.py") == \
        "formula/functions/registry.py"
    assert _module_of(TESTS / "reference/test_reference_workbooks.py") == "reference/__init__.py"


def test_no_module_is_both_exempt_and_awaited():
    assert not {m for m in NOT_YET if exempt(m)}


if __name__ == "__main__":
    # python tests/test_test_tree.py: rewrite NOT_YET as the modules still without their
    # test file (after a merge adds or renames modules; the list should only shrink)
    import re
    missing = _missing()
    body = ("NOT_YET: set[str] = {\n" + "".join(f'    "{m}",\n' for m in missing) + "}\n"
            if missing else "NOT_YET: set[str] = set()\n")
    source = Path(__file__).read_text(encoding="utf-8")
    source = re.sub(r"NOT_YET: set\[str\] = (set\(\)|\{\n.*?\n\})\n", lambda _: body, source,
                    count=1, flags=re.S)
    Path(__file__).write_text(source, encoding="utf-8")
    print(f"NOT_YET: {len(missing)} of {len(modules())} modules")
