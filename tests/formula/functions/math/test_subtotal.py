"""SUBTOTAL and AGGREGATE leave out hidden rows, nested subtotals and (by option) errors.

References: Excel's own cached values in the Excel-saved ClosedXML file
functions-excel-2010.xlsx (111 AGGREGATE/SUBTOTAL cells over a sheet with a hidden row
and nested AGGREGATE/SUBTOTAL cells, every option 0-7), and a table of cases written with
openpyxl and recalculated by LibreOffice headless, whose results are also checked against
sums computed here from the visible values.
"""

from __future__ import annotations

import math
from pathlib import Path

import openpyxl
import pytest

from workbook_gen import audit
from workbook_gen.engines.libreoffice import recalculate
from workbook_gen.formula import functions as fx
from workbook_gen.formula.values import Range, Ref

CORPUS = Path("/work/shared/corpus/xlsx")
DATA = [10, 20, 40, 80, 160, 320]  # A1:A6; row 3 hidden; A7 = SUBTOTAL(9,A1:A6)
HIDDEN = 3
VISIBLE = [x for i, x in enumerate(DATA, 1) if i != HIDDEN]
# (formula, value computed here from the rules): every case where a rule matters
CASES = {
    "C1": ("=SUBTOTAL(9,A1:A8)", sum(DATA) + 1),               # A7 nested: left out
    "C2": ("=SUBTOTAL(109,A1:A8)", sum(VISIBLE) + 1),           # and the hidden row
    "C3": ("=SUBTOTAL(2,A1:A8)", 7),
    "C4": ("=SUBTOTAL(102,A1:A8)", 6),
    "C5": ("=SUBTOTAL(104,A1:A6)", 320),
    "C6": ("=SUBTOTAL(105,A1:A6)", 10),
    "C7": ("=SUBTOTAL(101,A1:A6)", sum(VISIBLE) / 5),
    "C8": ("=_xlfn.AGGREGATE(9,0,A1:A8)", sum(DATA) + 1),
    "C9": ("=_xlfn.AGGREGATE(9,1,A1:A8)", sum(VISIBLE) + 1),
    "C10": ("=_xlfn.AGGREGATE(9,4,A1:A8)", 2 * sum(DATA) + 1),         # nothing left out
    "C11": ("=_xlfn.AGGREGATE(9,5,A1:A8)", sum(VISIBLE) + sum(DATA) + 1),
    # B2's #DIV/0! left out; A7 and B7 (= 2 * sum(DATA)) counted, then left out
    "C12": ("=_xlfn.AGGREGATE(9,6,A1:B8)", (2 * sum(DATA) + 1) + (sum(DATA) - 20) + 2 * sum(DATA) + 1),
    "C13": ("=_xlfn.AGGREGATE(9,3,A1:B8)", (sum(VISIBLE) + 1) + (sum(VISIBLE) - 20) + 1),
    "C14": ("=_xlfn.AGGREGATE(14,1,A1:A6,1)", 320),
    "C15": ("=_xlfn.AGGREGATE(15,5,A1:A8,2)", 10),                # 1 (A8), 10, ...
    "C16": ("=_xlfn.AGGREGATE(4,7,A1:B8)", 2 * sum(DATA)),            # B7 counted
    "C17": ("=SUBTOTAL(9,B1:B8)", "#DIV/0!"),                    # errors are met as usual
    # the array form (14-19) takes an array expression without array entry (the Summary
    # sheet's extremes over the ok rows); a row-wise reading would intersect C18 with
    # nothing and give #VALUE!
    "C18": ("=_xlfn.AGGREGATE(14,6,A1:A6/(A1:A6<100),1)", 80),
    "C19": ("=_xlfn.AGGREGATE(15,6,ROW(A1:A6)/(A1:A6=40),1)", 3),
    "C20": ("=_xlfn.AGGREGATE(14,6,B1:B6*2,1)", 640),             # B2's #DIV/0! left out
}


def _sheet(ws):
    for i, x in enumerate(DATA, 1):
        ws[f"A{i}"] = x
        ws[f"B{i}"] = "=1/0" if i == 2 else f"=A{i}"
    ws["A7"] = "=SUBTOTAL(9,A1:A6)"
    ws["B7"] = "=_xlfn.AGGREGATE(9,4,A1:A7)"  # nested, holds 2*sum(DATA)
    ws["A8"] = 1
    ws["B8"] = 1
    ws.row_dimensions[HIDDEN].hidden = True


@pytest.fixture(scope="module")
def recalculated(libreoffice, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("subtotal")
    wb = openpyxl.Workbook()
    ws = wb.active
    ws.title = "S"
    _sheet(ws)
    for ref, (formula, _) in CASES.items():
        ws[ref] = formula
    wb.save(tmp / "subtotal.xlsx")
    return recalculate(tmp / "subtotal.xlsx", tmp / "out")


def test_libreoffice_and_the_rules_agree_with_the_audit(recalculated):
    cached = openpyxl.load_workbook(recalculated, data_only=True)["S"]
    for ref, (_, expected) in CASES.items():
        got = cached[ref].value
        assert got == expected or (isinstance(expected, float) and math.isclose(got, expected)), \
            (ref, got, expected)
    report = audit(recalculated)
    assert report.mismatches == [] and report.not_checked == {}
    assert report.cells_checked == len(CASES) + 8


def test_excel_saved_aggregate_file_is_fully_audited():
    path = CORPUS / "closedxml__functions-excel-2010.xlsx"
    if not path.is_file():
        pytest.fail(f"corpus file missing: {path}", pytrace=False)
    report = audit(path)
    assert report.mismatches == [] and report.not_checked == {}
    assert report.cells_checked == report.formula_cells == 517


def test_without_a_sheet_layout_nothing_is_left_out():
    """A bare value table (no resolver) knows no hidden rows or nested subtotals."""
    rng = Range.of([[1.0], [2.0], [4.0]], Ref(None, 1, 1, 3, 1))
    assert fx.call("SUBTOTAL", [109.0, rng]) == 7.0
    assert fx.call("AGGREGATE", [9.0, 3.0, rng]) == 7.0
    assert fx.call("SUBTOTAL", [12.0, rng]) == fx.ExcelError.VALUE
    assert fx.call("AGGREGATE", [9.0, 8.0, rng]) == fx.ExcelError.VALUE


def test_the_reference_form_refuses_an_array_in_excel_not_in_libreoffice():
    """AGGREGATE 1-13 takes references (Microsoft: "reference form"); LibreOffice 7.4 also
    takes an array there (measured: 12 for the case below)."""
    values = Range.array_of([[5.0], [fx.ExcelError.DIV0], [7.0]])
    assert fx.call("AGGREGATE", [9.0, 6.0, values]) == fx.ExcelError.VALUE
    assert fx.call("AGGREGATE", [9.0, 6.0, values], "libreoffice") == 12.0
