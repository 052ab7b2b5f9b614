"""Bounded audits: a formula over a huge range costs what the used cells cost; generate
never writes a workbook its own audit would refuse for size."""

from __future__ import annotations

import json
import re
import resource
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
import xlsxwriter

from workbook_gen.scene import load_scene
from workbook_gen.workbook.writer import OTHER_CELLS, cells_of, workbook_bytes
from workbook_gen.xlsx import read_workbook
from workbook_gen.xlsx.limits import MAX_CELLS

MEMORY = 1536 * 2**20  # the bound an audit must keep (address space, numpy included)
TEMPLATES = sorted(Path("templates").glob("*.toml"))


def _limited():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY, MEMORY))


def test_huge_explicit_ranges_on_a_nearly_empty_sheet_cost_the_used_cells(tmp_path):
    path = tmp_path / "huge.xlsx"
    book = xlsxwriter.Workbook(path)
    sheet = book.add_worksheet()
    other = book.add_worksheet("Other")
    sheet.write_number("C1", 2)
    sheet.write_number("D5", 3)
    sheet.write_number("E2", 4)
    other.write_number("B3", 7)
    # cached values worked out by hand: the sheet holds 2, 3 and 4 (and 7 on Other)
    cases = {"A1": ("=SUM(C1:XFD1048576)", 9), "A2": ("=COUNT(C:XFD)", 3),
             "A3": ("=MAX(C1:XFD1048576)*COUNTA(C1:XFD1048576)", 12),
             "A4": ("=SUMPRODUCT(C1:XFD1048576,C1:XFD1048576)", 29),
             "A5": ("=INDEX(C1:XFD1048576,5,2)", 3), "A6": ("=MATCH(4,E1:E1048576,0)", 2),
             "A7": ("=SUM(Other!A1:XFD1048576)+SUM(Other!2:1048576)", 14)}
    for cell, (formula, value) in cases.items():
        sheet.write_formula(cell, formula, None, value)
    book.close()
    result = subprocess.run([sys.executable, "-m", "workbook_gen.cli", "audit", str(path),
                             "--json"], capture_output=True, text=True, timeout=300,
                            preexec_fn=_limited)
    assert result.returncode == 0, (result.stdout[-2000:], result.stderr[-2000:])
    report = json.loads(result.stdout)
    assert report["cells_agree"] == len(cases) and report["cells_not_checked"] == 0


def _cell_elements(path: Path) -> int:
    """The <c> elements of every worksheet: what the reader counts against its limit."""
    with zipfile.ZipFile(path) as z:
        return sum(len(re.findall(rb"<c[ >/]", z.read(name))) for name in z.namelist()
                   if name.startswith("xl/worksheets/") and name.endswith(".xml"))


@pytest.mark.parametrize("scene", TEMPLATES, ids=[t.stem for t in TEMPLATES])
def test_cells_known_before_computing_bound_the_workbook(scene, tmp_path):
    """At 361 rows a column too few in the estimate would show (OTHER_CELLS is 5,000)."""
    default = load_scene(str(scene)).sweep
    loaded = load_scene(str(scene), step=(default.stop - default.start) / 360)
    assert loaded.sweep.rows == 361
    path = tmp_path / "book.xlsx"
    path.write_bytes(workbook_bytes(loaded, path))
    cells = _cell_elements(path)
    assert read_workbook(path).n_cells <= cells <= cells_of(loaded) <= cells + OTHER_CELLS


def test_generate_refuses_a_sweep_its_audit_would_refuse(tmp_path):
    scene = load_scene("templates/sewing_machine.toml", step=0.01)
    assert cells_of(scene) > MAX_CELLS
    out = tmp_path / "out"
    result = subprocess.run([sys.executable, "-m", "workbook_gen.cli", "generate",
                             "templates/sewing_machine.toml", "--step", "0.01", "--out",
                             str(out)], capture_output=True, text=True, timeout=300)
    assert result.returncode == 2 and len(result.stderr.strip().splitlines()) == 1
    assert "step 0.01" in result.stderr and "at least" in result.stderr
    assert not out.exists()
    least = float(result.stderr.rsplit("at least", 1)[1])
    assert cells_of(load_scene("templates/sewing_machine.toml", step=least)) \
        <= MAX_CELLS


def test_formulas_that_each_differ_are_refused_beyond_the_time_budget(tmp_path, monkeypatch):
    """The cost model (36 us a cell of a run, 0.5 ms a formula parsed on its own) bounds
    the audit's time: refused while grouping, before the long part; runs are cheap."""
    from workbook_gen.errors import WorkbookReadError
    from workbook_gen.evaluator import grouping
    n = 1000
    distinct = {("S", r, 2): f"A{r}*{r}+1" for r in range(1, n + 1)}
    filled = {("S", r, 2): f"A{r}*2+1" for r in range(1, n + 1)}
    budget = grouping.COST_CELL * n + grouping.COST_PARSED * 500  # 500 formulas parsed
    with pytest.raises(WorkbookReadError, match="differ from the cell above"):
        grouping.group_formulas(distinct, budget)
    runs, _ = grouping.group_formulas(filled, budget)
    assert len(runs) == 1
    path = tmp_path / "distinct.xlsx"
    book = xlsxwriter.Workbook(path)
    sheet = book.add_worksheet()
    for r in range(1, 201):
        sheet.write_number(r - 1, 0, r)
        sheet.write_formula(r - 1, 1, f"=A{r}*{r}+1", None, r * r + 1)
    book.close()
    from workbook_gen import audit
    assert audit(path).cells_agree == 200
    monkeypatch.setattr(grouping, "BUDGET", grouping.COST_CELL * 200 + grouping.COST_PARSED * 100)
    with pytest.raises(WorkbookReadError) as refused:
        audit(path)
    assert str(path) in str(refused.value)
