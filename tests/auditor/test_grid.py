"""auditor/grid.py: the sheets as a grid of cell kinds and what each formula reads.

Cells written with XlsxWriter; the R1C1 forms follow Excel's notation ("R1C1 reference
style": RC[-1] the cell one column left in this row, R1C1 the absolute A1,
https://support.microsoft.com/en-us/office/overview-of-formulas-34519a4e-1e8d-4f4b-84d4-d642c4f63263),
and the references each formula reads are derived by hand from its text."""

from __future__ import annotations

import pytest
import xlsxwriter

from workbook_gen.auditor.grid import (BOOL, EMPTY, ERROR, FORMULA, NUMBER, TEXT, Grid,
                                       show_value, value_kind)
from workbook_gen.auditor.inputs import read_inputs
from workbook_gen.evaluator import evaluate_cells
from workbook_gen.xlerror import ExcelError


@pytest.fixture(scope="module")
def grid(tmp_path_factory):
    path = tmp_path_factory.mktemp("grid") / "grid.xlsx"
    book = xlsxwriter.Workbook(str(path))
    s = book.add_worksheet("S")
    for r in range(1, 6):  # B1:B5 one run: =A{r}*2+$A$1
        s.write_number(r - 1, 0, r * 1.5)
        s.write_formula(r - 1, 1, f"=A{r}*2+$A$1", None, r * 3 + 1.5)
    s.write_formula("C1", "=IF(ISBLANK(E1),0,A1)+SUM(A1:A5)", None, 22.5)
    s.write_formula("C2", "=k+1", None, 2.5)
    s.write_formula("C3", '=A3=""', None, False)
    s.write_formula("C4", "=other!B2+'S'!D1", None, 0)
    s.write_string("D1", "t")
    s.write_boolean("D2", True)
    s.write_number("F1", 7)       # column E stays empty inside the used range
    book.define_name("k", "=S!$A$1")
    book.add_worksheet("Other")
    book.close()
    inputs = read_inputs(path)
    evaluation = evaluate_cells(inputs.formulas, inputs.constants, inputs.book.defined_names,
                                book=inputs.book_info())
    return Grid(inputs, evaluation.runs)


def test_kinds_and_values(grid):
    assert grid.kind(("S", 2, 2)) == FORMULA and grid.value(("S", 2, 2)) == 7.5
    assert grid.kind(("S", 1, 1)) == NUMBER and grid.value(("S", 1, 1)) == 1.5
    assert grid.kind(("S", 1, 4)) == TEXT and grid.kind(("S", 2, 4)) == BOOL
    assert grid.kind(("S", 9, 9)) == EMPTY and grid.value(("S", 9, 9)) is None
    assert [value_kind(v) for v in (None, True, 0, 2.5, ExcelError.NA, "x")] == \
        [EMPTY, BOOL, NUMBER, NUMBER, ERROR, TEXT]
    assert show_value(0.1 + 0.2) == "0.3" and show_value(1 / 3) == "0.333333333333333"
    assert show_value(ExcelError.DIV0) == "#DIV/0!" and show_value("a") == "'a'"


def test_runs_and_their_r1c1_form(grid):
    assert grid.run_index(("S", 1, 2)) == grid.run_index(("S", 5, 2)) is not None
    assert grid.run_index(("S", 6, 2)) is None and grid.run_index(("S", 1, 1)) is None
    assert grid.r1c1(("S", 4, 2)) == "RC[-1]*2+R1C1"
    assert grid.r1c1(("S", 1, 1)) is None
    assert grid.unparsed == []
    assert grid.extent("S") == ({1, 2, 3, 4, 6}, (1, 1, 5, 6))
    assert grid.extent("Nowhere") == (set(), (1, 1, 0, 0))


def _reads(grid, key, names=True):
    return sorted((r.sheet, r.r1, r.c1, r.r2, r.c2, r.function, r.guarded)
                  for r in grid.refs(key, names))


def test_references_moved_along_the_run_and_guarded_by_tests(grid):
    assert _reads(grid, ("S", 3, 2)) == [("S", 1, 1, 1, 1, "", False),
                                         ("S", 3, 1, 3, 1, "", False)]
    assert _reads(grid, ("S", 1, 3)) == [("S", 1, 1, 1, 1, "IF", False),
                                         ("S", 1, 1, 5, 1, "SUM", False),
                                         ("S", 1, 5, 1, 5, "ISBLANK", True)]
    assert _reads(grid, ("S", 2, 3)) == [("S", 1, 1, 1, 1, "", False)]   # through k
    assert _reads(grid, ("S", 2, 3), names=False) == []
    assert _reads(grid, ("S", 3, 3)) == [("S", 3, 1, 3, 1, "", True)]    # =A3=""
    # another sheet by any case of its name, the canonical name kept
    assert _reads(grid, ("S", 4, 3)) == [("Other", 2, 2, 2, 2, "", False),
                                         ("S", 1, 4, 1, 4, "", False)]
    assert grid.sheet("[1]Ext", "S") is None and grid.sheet(None, "S") == "S"
    assert list(grid.refs(("S", 9, 9))) == []


def test_empty_cells_that_stand_out(grid):
    outside = "outside the sheet's used range"
    assert grid.notable_empty("S", 5, 4, 7) == [(4, "an empty column"), (5, "an empty column"),
                                                (6, outside), (7, outside)]
    assert grid.notable_empty("S", 2, 4, 7) == [(6, outside), (7, outside)]
    assert grid.notable_empty("S", 9, 1, 1) == [(1, outside)]
