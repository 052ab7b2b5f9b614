"""Spill references ``A1#`` (``_xlfn.ANCHORARRAY``) and implicit intersection ``@``
(``_xlfn.SINGLE``).

References: Excel's cached values in IronCalc's Excel-saved files ironcalc__dynamic_arrays
(``SUM(D1#)`` over a dynamic array, ``CONCAT(K1#)`` over an array entered the old way),
ironcalc__DynamicArrays (``TAKE(A3#,3,1)``, ``SUM(A3#)`` over a SEQUENCE) and
ironcalc__weekly_timesheet (``TEXT(A3#,"ddd")``, ``SUMIF(..., E14#)``); Microsoft's
implicit intersection operator page for ``@`` (a range intersected with the formula's
row or column, an array's top-left value).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from workbook_gen import audit
from workbook_gen.formula.parser import parse
from workbook_gen.formula.scalar import DictResolver, evaluate
from workbook_gen.xlerror import ExcelError

CORPUS = Path("/work/shared/corpus/xlsx")
# file -> cells that call ANCHORARRAY
FILES = {"ironcalc__dynamic_arrays.xlsx": ["Sheet1!F1", "Sheet1!M1"],
         "ironcalc__DynamicArrays.xlsx": ["DynamicArrays!F3", "DynamicArrays!A14"],
         "ironcalc__weekly_timesheet.xlsx": ["Timesheet!B3", "Overview!E14", "Overview!F14"]}


@pytest.mark.parametrize("name", FILES)
def test_spill_references_agree_with_excel(name):
    report = audit(CORPUS / name)
    assert report.ok, [(m.cell, m.formula, m.cached, m.recomputed) for m in report.mismatches]
    assert not any("ANCHORARRAY" in reason for reason in report.not_checked.values())
    for cell in FILES[name]:
        assert cell not in report.not_checked


def test_anchor_without_an_array_is_a_ref_error():
    resolver = DictResolver({"A1": 3.0})
    assert evaluate(parse("_xlfn.ANCHORARRAY(A1)"), resolver) == ExcelError.REF


@pytest.mark.parametrize("formula, cell, expected", [
    ("_xlfn.SINGLE(A1:A3)", ("Sheet1", 2, 3), 20.0),         # the formula's row
    ("_xlfn.SINGLE(A1:C1)", ("Sheet1", 5, 2), 2.0),          # the formula's column
    ("_xlfn.SINGLE(A1:A3)", ("Sheet1", 7, 3), ExcelError.VALUE),  # no intersection
    ("_xlfn.SINGLE({4,5;6,7})", ("Sheet1", 1, 1), 4.0),     # an array: its top-left
])
def test_implicit_intersection(formula, cell, expected):
    resolver = DictResolver({"A1": 10.0, "A2": 20.0, "A3": 30.0, "B1": 2.0, "C1": 3.0})
    assert evaluate(parse(formula), resolver, cell=cell) == expected


def test_spill_reference_beside_a_range_in_a_plain_formula(tmp_path):
    """``SUM(A1:A2)+SUM(D1#)`` as a plain formula (the aggregates' local evaluation reads
    it too): D1# is the dynamic array D1:D3 = SEQUENCE(3); cached 1+2+(1+2+3) by hand.
    XlsxWriter writes any formula calling ANCHORARRAY as a dynamic array: the cell is
    turned back into a plain formula in the written XML."""
    import zipfile

    import xlsxwriter
    first, path = tmp_path / "dyn.xlsx", tmp_path / "plain.xlsx"
    wb = xlsxwriter.Workbook(str(first))
    ws = wb.add_worksheet("S")
    ws.write_column("A1", [1, 2])
    ws.write_dynamic_array_formula("D1:D3", "=_xlfn.SEQUENCE(3)", None, 1)
    ws.write_column("D2", [2, 3])
    ws.write_formula("F1", "=SUM(A1:A2)+SUM(_xlfn.ANCHORARRAY(D1))", None, 9)
    wb.close()
    with zipfile.ZipFile(first) as zin, zipfile.ZipFile(path, "w") as zout:
        for item in zin.infolist():
            data = zin.read(item.filename)
            if item.filename == "xl/worksheets/sheet1.xml":
                data = data.replace(b'<c r="F1" cm="1"><f t="array" ref="F1">',
                                    b'<c r="F1"><f>')
            zout.writestr(item, data)
    report = audit(path)
    assert report.ok and report.not_checked == {}, report.mismatches
    assert report.formula_cells == 2 and report.cells_checked == 2  # an array counts once


def test_sheet_numbers_count_chart_sheets(tmp_path):
    """Microsoft's SHEET page: every sheet counts, chart sheets and hidden ones too.
    Sheets: Data, a chart sheet, Main (hidden Data2 last); cached values by that rule."""
    import xlsxwriter
    path = tmp_path / "sheets.xlsx"
    wb = xlsxwriter.Workbook(str(path))
    data = wb.add_worksheet("Data")
    data.write_column("A1", [1, 2, 3])
    chart_sheet = wb.add_chartsheet("Chart1")
    chart = wb.add_chart({"type": "line"})
    chart.add_series({"values": "=Data!$A$1:$A$3"})
    chart_sheet.set_chart(chart)
    main = wb.add_worksheet("Main")
    wb.add_worksheet("Data2").hide()
    for ref, formula, value in [("A1", "=_xlfn.SHEET()", 3), ("A2", "=_xlfn.SHEETS()", 4),
                                ("A3", '=_xlfn.SHEET("chart1")', 2),
                                ("A4", "=_xlfn.SHEET(Data!A1:A3)", 1),
                                ("A5", '=_xlfn.SHEET("Data2")', 4),
                                ("A6", '=_xlfn.SHEET("Nowhere")', "#N/A")]:
        main.write_formula(ref, formula, None, value)
    wb.close()
    report = audit(path)
    assert report.not_checked == {}
    assert report.ok and report.cells_checked == 6, report.mismatches


def test_randarray_draws_checked_against_the_contract(tmp_path):
    """Microsoft's RANDARRAY page: whole numbers between min and max with whole_number
    TRUE. Excel's own draws in ironcalc__DynamicArrays (A19:C21, RANDARRAY(3,3,0,100,TRUE))
    hold; a cached 7 or 2.5 among die rolls RANDARRAY(2,2,1,6,TRUE) does not."""
    import xlsxwriter
    report = audit(CORPUS / "ironcalc__DynamicArrays.xlsx")
    assert report.not_checked == {} and report.ok
    assert sum("RANDARRAY" in how for how in report.by_contract.values()) == 9
    path = tmp_path / "dice.xlsx"
    wb = xlsxwriter.Workbook(str(path))
    ws = wb.add_worksheet("S")
    ws.write_dynamic_array_formula("A1:B2", "=_xlfn.RANDARRAY(2,2,1,6,TRUE)", None, 3)
    ws.write_number("B1", 7)
    ws.write_number("A2", 2.5)
    ws.write_number("B2", 6)
    wb.close()
    report = audit(path)
    assert [(m.cell, m.area, sorted(m.cells)) for m in report.mismatches] == [
        ("S!A1", "A1:B2", ["S!A2", "S!B1"])]  # the array once, at its anchor
    assert report.counts.disagree == 1 and report.counts.by_contract == 0
    assert report.not_checked == {}
