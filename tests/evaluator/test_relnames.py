"""Defined names read from the calling cell: relative references (stored as seen from
A1), names through names, sheet-scoped ones, and structured references to this row.

References: LibreOffice recalculating a workbook of such names (the independent engine;
it does not wrap at the sheet's edges, its dialect), and for Excel's wrapping the
documented example of Jan Karel Pieterse's "Range Names In Excel" (a name defined from
C3 as ``=Sheet2!A1`` is two columns left and two rows up: used in C14 it reads A12; the
file stores it as seen from A1, ``Sheet2!XFC1048575``) and the brief's ``=Sheet1!$H1``
read from I12 (H12).
"""

from __future__ import annotations

import openpyxl
import pytest
import xlsxwriter

from workbook_gen import audit
from workbook_gen.engines.libreoffice import recalculate
from workbook_gen.evaluator.relnames import at_cell
from workbook_gen.formula import ast
from workbook_gen.formula.parser import parse
from workbook_gen.xlerror import ExcelError

# (name, definition as the file stores it)
NAMES = [("LeftH", "=Sheet1!$H1"), ("TwoUp", "=Sheet1!$A1048575"), ("Twice", "=LeftH*2"),
         ("Win", "=SUM(Sheet1!$A1:$A3)"), ("NextCol", "=Other!B1"),
         ("Other!Local", "=Other!$B2")]
COLUMNS = {"I": "=LeftH", "J": "=Twice+1", "K": "=Win", "L": "=TwoUp", "M": "=Other!Local"}


def _book(path):
    wb = xlsxwriter.Workbook(str(path))
    ws, other = wb.add_worksheet("Sheet1"), wb.add_worksheet("Other")
    for r in range(1, 21):
        ws.write_number(r - 1, 7, r * 10)      # H
        ws.write_number(r - 1, 0, r)           # A
        other.write_number(r - 1, 1, r * 100)  # Other!B
    for name, text in NAMES:
        wb.define_name(name, text)
    for r in range(1, 5):
        for col, formula in COLUMNS.items():
            ws.write_formula(f"{col}{r}", formula)
    for r in range(1, 4):
        other.write_formula(f"D{r}", "=Local+NextCol")  # Other!B(r+1) + Other!E(r)
    wb.close()


@pytest.fixture(scope="module")
def recalculated(libreoffice, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("relnames")
    _book(tmp / "names.xlsx")
    return recalculate(tmp / "names.xlsx", tmp / "lo")


def test_libreoffice_reads_the_names_from_the_calling_cell(recalculated):
    """Spot checks of what the cases mean, by hand."""
    wb = openpyxl.load_workbook(recalculated, data_only=True)
    ws = wb["Sheet1"]
    assert [ws[f"I{r}"].value for r in range(1, 5)] == [10, 20, 30, 40]     # H1..H4
    assert ws["J3"].value == 61 and ws["K2"].value == 2 + 3 + 4
    assert [ws[f"L{r}"].value for r in range(1, 5)] == [0, 0, "#REF!", "#REF!"]  # no wrap
    assert [wb["Other"][f"D{r}"].value for r in range(1, 4)] == [200, 300, 400]


def test_relative_names_recomputed_as_libreoffice_computed_them(recalculated):
    report = audit(recalculated)
    assert report.semantics == "libreoffice"
    assert report.not_checked == {}
    assert report.ok, [(m.cell, m.formula, m.cached, m.recomputed) for m in report.mismatches]
    assert report.cells_checked == 4 * len(COLUMNS) + 3


@pytest.mark.parametrize("stored, cell, reads", [
    ("Sheet1!$H1", (12, 9), "Sheet1!$H12"),             # the brief's example
    ("Sheet2!XFC1048575", (14, 3), "Sheet2!A12"),        # Pieterse's C3-relative name
    ("Sheet1!A1048576", (5, 2), "Sheet1!B4"),            # one row above
    ("Sheet1!A1048576", (1, 1), "Sheet1!A1048576"),      # from row 1: the last row
    ("SUM(Sheet1!$A1:$A3)", (12, 11), "SUM(Sheet1!$A12:$A14)"),
])
def test_excel_wraps_a_relative_name_at_the_sheet_edges(stored, cell, reads):
    from workbook_gen.formula.printer import render
    moved = at_cell(parse(stored), *cell, None)
    assert render(moved) == reads


def test_libreoffice_dialect_does_not_wrap():
    assert at_cell(parse("Sheet1!$A1048575"), 3, 1, None, wrap=False) == ast.ErrorLit(
        ExcelError.REF)
    assert at_cell(parse("Sheet1!$A1048575"), 2, 1, None, wrap=False) == parse(
        "Sheet1!$A1048576")


def test_excel_saved_book_reads_a_name_defined_from_another_cell(tmp_path):
    """An Excel-semantics file (XlsxWriter's) whose cached values follow Pieterse's rule:
    the name stored as Sheet1!XFC1048575 reads two columns left and two rows up."""
    path = tmp_path / "excel.xlsx"
    wb = xlsxwriter.Workbook(str(path))
    ws = wb.add_worksheet("Sheet1")
    for r in range(1, 21):
        ws.write_number(r - 1, 0, r * 7)  # A
    wb.define_name("UpLeft", "=Sheet1!XFC1048575")
    wb.define_name("Prev", "=Sheet1!A1048576")  # the cell above, same column
    for r in range(3, 15):
        ws.write_formula(r - 1, 2, "=UpLeft", None, (r - 2) * 7)   # C: A(r-2)
    ws.write_formula("A21", "=Prev+1", None, 20 * 7 + 1)
    wb.close()
    report = audit(path)
    assert report.semantics == "excel" and report.not_checked == {}
    assert report.ok and report.cells_checked == 13, report.mismatches


def test_a_stale_cell_read_through_a_relative_name_is_the_only_source(tmp_path):
    """A5 caches 3 for =1+1 (stale); C7 =UpLeft reads A5 (two rows up, two columns left)
    and caches 3 as well: C7 disagrees too, but follows from A5, the one source."""
    path = tmp_path / "stale.xlsx"
    wb = xlsxwriter.Workbook(str(path))
    ws = wb.add_worksheet("Sheet1")
    wb.define_name("UpLeft", "=Sheet1!XFC1048575")
    ws.write_formula("A5", "=1+1", None, 3)
    ws.write_formula("C7", "=UpLeft", None, 3)
    wb.close()
    report = audit(path)
    assert {m.cell: m.root for m in report.mismatches} == {"Sheet1!A5": True,
                                                           "Sheet1!C7": False}
