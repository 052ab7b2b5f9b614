"""xlsx/sheetdata.py (with sheetrows.py and scan.py, which cut and scan the rows it
reads) against openpyxl on Excel- and LibreOffice-saved corpus workbooks: every cell
openpyxl holds is read, with the same cached value (numbers, text, booleans, errors,
dates as their serials) and, for each formula openpyxl gives as text, the same text.

openpyxl leaves the ``_xHHHH_`` escapes of ECMA-376 Part 1, 22.9.2.19 (ST_Xstring) in
the text; they are decoded here before comparing."""

from __future__ import annotations

import datetime
import re
import warnings

import openpyxl
import pytest
from openpyxl.utils.datetime import to_excel
from openpyxl.worksheet.formula import ArrayFormula

from corpus_audits import CORPUS
from workbook_gen.xlerror import ExcelError
from workbook_gen.xlsx import read_workbook

FILES = ["pycel__stats.xlsx", "poi__FormulaEvalTestData_Copy.xlsx",
         "sheetjs__formula_stress_test.xlsx", "edr__Test_num_double_date_bool_string.xlsx",
         "npoi__Booleans.xlsx", "ironcalc__MONTH.xlsx", "poi__shared_formulas.xlsx",
         "phpspreadsheet__Stock_Portfolio.xlsx", "xlcalculator__DATE.xlsx"]
_ESCAPE = re.compile(r"_x([0-9A-Fa-f]{4})_")


def plain(v):
    if isinstance(v, ExcelError):
        return v.value
    if isinstance(v, (datetime.datetime, datetime.date, datetime.time, datetime.timedelta)):
        return float(to_excel(v))
    if isinstance(v, bool) or v is None:
        return v
    if isinstance(v, (int, float)):
        return float(v)
    return _ESCAPE.sub(lambda m: chr(int(m.group(1), 16)), v)


def load(path, data_only: bool):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")   # openpyxl's warnings on extensions it drops
        return openpyxl.load_workbook(path, data_only=data_only)


@pytest.mark.parametrize("name", FILES)
def test_cells_values_and_formulas_as_openpyxl_reads_them(name):
    path = CORPUS / name
    ours = read_workbook(path)
    values, formulas = load(path, True), load(path, False)
    checked = 0
    for sheet in ours.sheets:
        for row in formulas[sheet.name].iter_rows():
            for cell in row:
                if cell.value is None:
                    continue
                mine = sheet.cells.get(cell.coordinate)
                assert mine is not None, (sheet.name, cell.coordinate, cell.value)
                cached = values[sheet.name][cell.coordinate].value
                if not (plain(mine.value) in (None, "") and cached in (None, "")):
                    assert plain(mine.value) == plain(cached), (sheet.name, cell.coordinate)
                text = cell.value.text if isinstance(cell.value, ArrayFormula) else cell.value
                if isinstance(text, str) and text.startswith("=") and mine.formula is not None:
                    assert mine.formula.lstrip("=") == text[1:], (sheet.name, cell.coordinate)
                checked += 1
        for ref, mine in sheet.cells.items():   # and nothing openpyxl does not hold
            theirs = formulas[sheet.name][ref].value
            assert theirs is not None or plain(mine.value) in (None, ""), (sheet.name, ref)
    assert checked > 5
