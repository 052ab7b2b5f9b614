"""MATCH with match_type -1 (smallest value >= the lookup value, data sorted descending).

Excel's reference: its cached results in pycel's lookup.xlsx (saved by Excel), row 32:
MATCH(x, {0;1;2;3;4}, -1), ascending data, which Excel scans from the top down to the
first value below x or past a run of values equal to x. LibreOffice headless recalculates
a table of cases on data sorted descending (the documented use), duplicates included
(LibreOffice gives the last of equal values, as Excel's bisection does for ascending data;
the Excel file has no duplicates): it must agree with us.
"""

from __future__ import annotations

from pathlib import Path

import openpyxl
import pytest

from workbook_gen import audit
from workbook_gen.formula import functions as fx
from workbook_gen.formula.values import Range

from lo_sheet import recalculated_sheet

CORPUS = Path("/work/shared/corpus/xlsx")
DESC = [40, 30, 20, 20, 10]  # A1:A5
CASES = {  # formula -> its documented value on descending data (smallest value >= x)
    "=MATCH(25,$A$1:$A$5,-1)": 2,
    "=MATCH(30,$A$1:$A$5,-1)": 2,
    "=MATCH(20,$A$1:$A$5,-1)": 4,  # the last of equal values
    "=MATCH(40,$A$1:$A$5,-1)": 1,
    "=MATCH(5,$A$1:$A$5,-1)": 5,
    "=MATCH(10,$A$1:$A$5,-1)": 5,
    "=MATCH(50,$A$1:$A$5,-1)": "#N/A",
    '=MATCH("x",$A$1:$A$5,-1)': "#N/A",
}


@pytest.fixture(scope="module")
def recalculated(libreoffice, tmp_path_factory):
    cells = {**{f"A{i}": x for i, x in enumerate(DESC, 1)},
             **{f"C{i}": formula for i, formula in enumerate(CASES, 1)}}
    return recalculated_sheet(tmp_path_factory.mktemp("match"), "M", cells)


def test_descending_data_agrees_with_libreoffice_and_the_documentation(recalculated):
    ws = openpyxl.load_workbook(recalculated, data_only=True)["M"]
    assert [ws[f"C{i}"].value for i in range(1, len(CASES) + 1)] == list(CASES.values())
    report = audit(recalculated)
    assert report.mismatches == [] and report.cells_checked == len(CASES)


def test_excel_scan_on_ascending_data():
    """pycel lookup.xlsx, Lookup!B32:I32: Excel's own results over ascending 0..4."""
    path = CORPUS / "pycel__lookup.xlsx"
    if not path.is_file():
        pytest.fail(f"corpus file missing: {path}", pytrace=False)
    cached = openpyxl.load_workbook(path, data_only=True)["Lookup"]
    data = Range.of([[float(x)] for x in range(5)])
    for col in "BCDEFGHI":
        x = cached[f"{col}3"].value
        ours = fx.call("MATCH", [x, data, -1.0])
        excel = cached[f"{col}32"].value
        assert (str(ours) if isinstance(ours, fx.ExcelError) else ours) == excel, (col, x)
    report = audit(path)
    assert report.mismatches == [] and report.not_checked == {}


ARRAYS = {  # formulas test.xlsx LOOKUP rows: the array constant each row looks up
    56: [-1.1, 2.1, 3.1, 4.1], 57: ["a", 2.1, "b", 4.1], 58: [False, 2.1, True, 4.1],
    59: [4.1, 2.1, 3.1, 1.1], 60: ["b", 4.1, "a", 1.1], 61: ["", 4.1, "a", 1.1],
    62: [True, 4.1, False, 1.1], 63: [True, 4.1, False, "b"], 64: [True, False, "a", "b"],
    65: [-1.1, 2.1, 3.1, 4.1], 66: ["a", 2.1, "c bau c", 4.1], 67: [False, 2.1, True, 4.1],
    68: [4.1, 3.1, 2.1, 1.1], 69: ["c bau c", 4.1, "a", 1.1], 70: ["", 4.1, "a", 1.1],
    71: [True, 4.1, False, 1.1], 72: [True, 4.1, False, "c bau c"],
    73: [True, False, "a", "c bau c"],
}


def test_approximate_lookup_over_mixed_types():
    """Excel's bisection over arrays of mixed types (formulas test.xlsx, saved by Excel,
    LOOKUP!X56:Y73): a value of another type at the middle sends the search back to the
    previous comparable value, which is then only a candidate, even when equal."""
    path = CORPUS / "formulas__test.xlsx"
    if not path.is_file():
        pytest.fail(f"corpus file missing: {path}", pytrace=False)
    ws = openpyxl.load_workbook(path, data_only=True)["LOOKUP"]
    for row, items in ARRAYS.items():
        array = Range.array_of([items])
        for col in ("X", "Y"):
            src = ws[f"{'I' if col == 'X' else 'J'}{row if row >= 65 else 56}"].value
            if row < 65:
                ours = fx.call("LOOKUP", [src, array])
            else:
                ours = fx.call("MATCH", [src, array])
            ours = str(ours) if isinstance(ours, fx.ExcelError) else ours
            assert ours == ws[f"{col}{row}"].value, (col, row, src)
