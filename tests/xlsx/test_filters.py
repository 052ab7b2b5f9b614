"""Rows a filter hid: SUBTOTAL 1-11 leaves them out as 101-111 do, AGGREGATE only with
the options that leave out hidden rows; rows hidden by hand stay in SUBTOTAL 1-11.

References: Microsoft's SUBTOTAL page ("ignores any rows that are not included in the
result of a filter, no matter which function_num value you use"); Excel's cached values
in ironcalc__tables.xlsx (sheets "filters" and "Functions Filters": tables filtered by
value and by a custom criterion); a sheet autoFilter and a filtered table written with
openpyxl and recalculated by LibreOffice headless.
"""

from __future__ import annotations

from pathlib import Path

import openpyxl
import pytest
from openpyxl.worksheet.filters import AutoFilter, FilterColumn, Filters
from openpyxl.worksheet.table import Table, TableStyleInfo

from workbook_gen import audit
from workbook_gen.engines.libreoffice import recalculate
from workbook_gen.xlsx.filters import _active
from workbook_gen.xlsx.reader import read_workbook

TABLES = Path("/work/shared/corpus/xlsx/ironcalc__tables.xlsx")
DATA = [("East", 1), ("West", 2), ("East", 4), ("North", 8), ("West", 16), ("East", 32)]
SHEET_CASES = {"D1": "=SUBTOTAL(9,B2:B9)", "D2": "=SUBTOTAL(109,B2:B9)",
               "D3": "=SUBTOTAL(2,B1:B9)", "D4": "=SUBTOTAL(102,B1:B9)",
               "D5": "=SUM(B2:B9)", "D6": "=_xlfn.AGGREGATE(9,5,B2:B9)",
               "D7": "=SUBTOTAL(4,B2:B9)", "D8": "=SUBTOTAL(1,B2:B7)",
               "D9": "=_xlfn.AGGREGATE(9,4,B2:B9)", "D10": "=_xlfn.AGGREGATE(9,0,B2:B9)"}
TABLE_CASES = {"D1": "=SUBTOTAL(9,Sales[Units])", "D2": "=SUBTOTAL(9,B2:B10)",
               "D3": "=SUBTOTAL(109,B2:B10)", "D4": "=SUBTOTAL(3,Sales[Region])"}


@pytest.fixture(scope="module")
def recalculated(libreoffice, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("filters")
    wb = openpyxl.Workbook()
    ws = wb.active
    ws.title = "F"  # a sheet autoFilter showing East; B9 hidden by hand below it
    ws.append(["Region", "Units"])
    for row in DATA:
        ws.append(list(row))
    ws.auto_filter.ref = "A1:B7"
    ws.auto_filter.add_filter_column(0, ["East"])
    for i, (region, _) in enumerate(DATA, start=2):
        ws.row_dimensions[i].hidden = region != "East"
    ws["B9"] = 64
    ws.row_dimensions[9].hidden = True
    for ref, formula in SHEET_CASES.items():
        ws[ref] = formula
    t = wb.create_sheet("T")  # a table filtered to West; B10 hidden by hand
    t.append(["Region", "Units"])
    for row in DATA:
        t.append(list(row))
    table = Table(displayName="Sales", ref="A1:B7")
    table.tableStyleInfo = TableStyleInfo(name="TableStyleMedium9")
    table.autoFilter = AutoFilter(ref="A1:B7", filterColumn=[
        FilterColumn(colId=0, filters=Filters(filter=["West"]))])
    t.add_table(table)
    for i, (region, _) in enumerate(DATA, start=2):
        t.row_dimensions[i].hidden = region != "West"
    t["B10"] = 128
    t.row_dimensions[10].hidden = True
    for ref, formula in TABLE_CASES.items():
        t[ref] = formula
    wb.save(tmp / "f.xlsx")
    return recalculate(tmp / "f.xlsx", tmp / "lo")


def test_libreoffice_computed_what_the_cases_mean(recalculated):
    wb = openpyxl.load_workbook(recalculated, data_only=True)
    east = 1 + 4 + 32
    assert [wb["F"][r].value for r in ("D1", "D2", "D3", "D5")] == [east + 64, east, 4, 127]
    assert [wb["F"][r].value for r in ("D9", "D10")] == [127, 127]  # AGGREGATE keeps them
    assert [wb["T"][r].value for r in ("D1", "D2", "D3")] == [18, 18 + 128, 18]


def test_filtered_rows_left_out_as_libreoffice_left_them_out(recalculated):
    report = audit(recalculated)
    assert report.not_checked == {}
    assert report.ok, [(m.cell, m.formula, m.cached, m.recomputed) for m in report.mismatches]
    assert report.cells_checked == len(SHEET_CASES) + len(TABLE_CASES)


def test_reader_tells_filtered_from_hidden(recalculated):
    book = read_workbook(recalculated)
    assert book.sheet("F").filter_ref == "A1:B7"
    assert book.sheet("T").tables[0].filter_ref == "A1:B7"


def test_excel_filtered_tables_agree_with_excel():
    report = audit(TABLES)
    for cell in ("filters!B8", "filters!B10", "'Functions Filters'!D46",
                 "'Functions Filters'!D50", "'Functions Filters'!E48"):
        assert cell not in report.not_checked
        assert all(m.cell != cell for m in report.mismatches), cell


@pytest.mark.parametrize("tail, active", [
    (b'<autoFilter ref="A1:B7"/>', None),                          # no column filters
    (b'<autoFilter ref="A1:B7"><filterColumn colId="0" hiddenButton="1"/></autoFilter>',
     None),                                                         # a button, no criterion
    (b'<autoFilter ref="A1:B7"><filterColumn colId="0"><filters><filter val="x"/>'
     b'</filters></filterColumn></autoFilter>', "A1:B7"),
    (b'<x:autoFilter ref="C3:D9"><x:filterColumn colId="1"><x:customFilters>'
     b'<x:customFilter operator="greaterThan" val="20"/></x:customFilters></x:filterColumn>'
     b'</x:autoFilter>', "C3:D9"),                                  # a prefixed part
    (b'<customSheetViews><customSheetView guid="{0}"><autoFilter ref="A1:B7"><filterColumn'
     b' colId="0"><filters><filter val="x"/></filters></filterColumn></autoFilter>'
     b'</customSheetView></customSheetViews>', None),               # a custom view's filter
])
def test_sheet_autofilter_filters_only_with_a_criterion(tail, active):
    assert _active(b"<mergeCells/>" + tail + b"<pageMargins/>") == active
