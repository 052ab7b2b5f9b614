"""formula/functions/information/sheets.py: SHEET and SHEETS against Microsoft's pages
(support.microsoft.com, "SHEET function": =SHEET("Stuff") finds the sheet named Stuff (3),
a reference finds its sheet, "If the value argument is not a valid sheet name, SHEET
returns the #N/A error"; "SHEETS function": =SHEETS() the number of sheets, =SHEETS(C5) 1
for a reference to one sheet), and the corpus's ironcalc__tables.xlsx, whose
SHEET(), SHEET("Filters") and SHEET(Table1[]) Excel cached, audited against the cache."""

from __future__ import annotations

from pathlib import Path

import pytest

from workbook_gen import audit
from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.formula.functions.information import sheets
from workbook_gen.xlerror import ExcelError

SHEETS = ["Sales", "Chart1", "Stuff", "Data"]   # a chart sheet counts (the page's remarks)


class _Book(DictResolver):
    def sheet_number(self, sheet):
        names = [s.casefold() for s in SHEETS]
        name = (sheet or self.sheet).casefold()
        return names.index(name) + 1 if name in names else None

    def sheet_count(self):
        return len(SHEETS)


def ev(text, cell=("Data", 1, 1)):
    return evaluate(parse(text), _Book({}, sheet=cell[0]), cell=cell)


@pytest.mark.parametrize("formula, expected", [
    ('=SHEET("Stuff")', 3.0),
    ('=SHEET("stuff")', 3.0),                  # any case
    ('=SHEET("Chart1")', 2.0),
    ('=SHEET("badSheetName")', ExcelError.NA),
    ("=SHEET()", 4.0),                         # the calling cell's sheet
    ("=SHEET(Sales!B2:C9)", 1.0),              # a reference: its sheet
    ("=SHEET(A1)", 4.0),                       # unqualified: the calling sheet
    ("=SHEET(12)", ExcelError.NA),             # a number names no sheet
    ("=SHEET(#REF!)", ExcelError.REF),
    ("=SHEETS()", 4.0),
    ("=SHEETS(C5)", 1.0),
    ("=SHEETS(Stuff!A1:B3)", 1.0),
])
def test_microsofts_rules(formula, expected):
    assert ev(formula) == expected


def test_unknown_sheets_are_na():
    book = DictResolver({})            # the default: the workbook's sheets not known
    assert evaluate(parse("=SHEET()"), book) is ExcelError.NA
    assert evaluate(parse('=SHEET("Sheet1")'), book) is ExcelError.NA
    assert evaluate(parse("=SHEETS()"), book) is ExcelError.NA


def test_which_calls_are_computed():
    args = lambda text: parse(text).args  # noqa: E731
    assert sheets._not_3d(args("=SHEET(A1)")) and sheets._not_3d(())
    assert not sheets._not_3d(args("=SHEET(Sheet1:Sheet3!A1)"))
    assert sheets._sheets_accepts(args("=SHEETS(A1:B2)"))
    assert sheets._sheets_accepts(args("=SHEETS(Table1[])"))
    assert sheets._sheets_accepts(())
    assert not sheets._sheets_accepts(args("=SHEETS(Sheet1:Sheet3!A1)"))
    assert not sheets._sheets_accepts(args('=SHEETS("x")'))


def test_the_excel_saved_tables_file_agrees():
    report = audit(Path("/work/shared/corpus/xlsx/ironcalc__tables.xlsx"))
    assert report.cells_checked == report.formula_cells > 0
    assert report.mismatches == [] and report.not_checked == {}
