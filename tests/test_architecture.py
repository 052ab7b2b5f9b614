"""docs/ARCHITECTURE.md is the map: every package folder has a row, and every entry point
and test file it names exists (issue 23)."""

from __future__ import annotations

import importlib
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MAP = ROOT / "docs" / "ARCHITECTURE.md"


def _rows() -> list[list[str]]:
    lines = [l for l in MAP.read_text().splitlines() if l.startswith("| `")]
    return [[c.strip() for c in l.strip("|").split("|")] for l in lines]


def test_every_package_folder_has_a_row():
    named = {re.match(r"`workbook_gen/|`([\w/]+)/`", r[0]).group(1) or ""
             for r in _rows()}
    packages = {str(p.parent.relative_to(ROOT / "workbook_gen")).replace(".", "")
                for p in (ROOT / "workbook_gen").rglob("__init__.py")
                if "__pycache__" not in str(p)}
    packages = {p for p in packages if p and p.count("/") <= 1 and "numfmt" not in p}
    assert packages - named == set(), "folders missing from docs/ARCHITECTURE.md"
    assert named - packages - {""} == set(), "rows for folders that do not exist"


def test_entry_points_resolve():
    for row in _rows():
        for name in re.findall(r"`([\w.]+)(?:\([^`]*\))?`", row[2]):
            module, _, attr = name.rpartition(".")
            if not module:  # a name exported by the package itself
                module, attr = "", name
            target = importlib.import_module("workbook_gen" + ("." + module if module else ""))
            if attr and not hasattr(target, attr):
                importlib.import_module(f"{target.__name__}.{attr}")


def test_named_test_files_exist():
    for row in _rows():
        for name in re.findall(r"`(tests/[\w./]+)`", row[3]):
            assert (ROOT / name).exists(), name
        for pattern in re.findall(r"`(tests/[\w*<>./]+)`", row[3]):
            if "*" in pattern:
                assert list(ROOT.glob(pattern)), pattern
