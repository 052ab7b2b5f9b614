"""TEXT's number formats laid placeholder by placeholder, sections, text sections, time
texts and elapsed counts.

References: Excel's cached results in pycel's text.xlsx (saved by Excel: 66 number
formats on TextNumbers, 48 date/time cases on TextDates), and a table of number formats
recalculated by LibreOffice headless where LibreOffice follows the same rules.
LibreOffice 7.4 differs from Excel on some odd formats; those are listed in
``LO_DIFFERS`` with Excel's evidence and are tested against the Excel file only.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import openpyxl
import pytest
from lo_sheet import recalculated_sheet

from workbook_gen import audit
from workbook_gen.engines.libreoffice import recalculate
from workbook_gen.formula import functions as fx
from workbook_gen.formula.values import Range

CORPUS = Path("/work/shared/corpus/xlsx")
VALUES = [1234567.89, 890123.456789, 0.5, -1234.5, 0, 5, 0.000123, 123456789, -0.004]
FORMATS = [  # LibreOffice and Excel agree on these (every value above)
    "#,##0.00", "0.0%", '#,#"ZZ"#.0"YY"00', "0,", '#,##0,"K"', "0.00E+00", "##0.0E+0",
    "0.0E-0", "$#,##0_);($#,##0)", '0;(0);"zero"', "?.??", "000-00-0000", "#,###",
    "0.0,,", '"x"0"y"', "\\#0", "w;x;z@", "0.0;-0.0", "00.0?#",
    # colours, currency and locale brackets, conditions, padding and fill, "?" separators
    "[$€-407]#,##0.00", "[Red]0.0_);[Blue](0.0)", "#,##0.00;[Red]-#,##0.00",
    "[<100]0.0;[>1000]#,##0;0.000", "0.00E+00;(0.00E+00)", "?,??0.00",
    "\\$#,##0_);\\(\\$#,##0\\)", '0.0%;-0.0%;"nil"', '#,##0.0,,"M"', "* #,##0",
]
LO_DIFFERS = {  # format: Excel's rule and its evidence in pycel text.xlsx (TextNumbers)
    "%#%#%": "each % multiplies by 100 (row 48: 890123.456789 -> %89012345678%9%); "
             "LibreOffice multiplies once",
    "#x,0,#.00.0": "a comma after a literal is a literal (row 37: 890,1x,23.45.7)",
    "0,x#.00.0": "a comma after a placeholder not followed by one is dropped, no "
                 "separators (row 34: 89012x3.45.7); LibreOffice separates thousands",
    "#.###x,##": "no separators, the comma after x a literal (row 40: 890123.456x,79)",
    "#.#####00#0": "a # among trailing zeros shows nothing even before a 0 "
                   "(row 50: 890123.45678900); LibreOffice shows every digit after it",
    ".##0": "as above (row 66: 1234.56 -> 1234.560)",
    "#.##": "the decimal point stays without decimals (row 58: 1 -> 1.); LibreOffice "
            "drops it",
    "#.###.#.#.#": "later dots are literals that stay (rows 25, 58)",
}
LO_DIFFERS_AT = {  # (value, format) of FORMATS that LibreOffice shows otherwise
    (0, "##0.0E+0"): "zero shows every integer placeholder of a scientific pattern as 0 "
                     "(NPOI NumberFormatApproxTests.xlsx, saved by Excel: |####.####|e-|#| of "
                     "0 is |0000.|e|0|); LibreOffice shows 0.0E+0",
}


@pytest.fixture(scope="module")
def recalculated(libreoffice, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("textfmt")
    wb = openpyxl.Workbook()
    ws = wb.active
    ws.title = "T"
    for i, (v, f) in enumerate(itertools.product(VALUES, FORMATS), 1):
        ws.cell(i, 1, v)
        ws.cell(i, 2, f)
        ws.cell(i, 3, f"=TEXT(A{i},B{i})")
    wb.save(tmp / "text.xlsx")
    return recalculate(tmp / "text.xlsx", tmp / "out")


def _ours(v, f):
    out = fx.call("TEXT", [v, f])
    return str(out) if isinstance(out, fx.ExcelError) else out


def test_number_formats_agree_with_libreoffice(recalculated):
    ws = openpyxl.load_workbook(recalculated, data_only=True)["T"]
    wrong = []
    for i, (v, f) in enumerate(itertools.product(VALUES, FORMATS), 1):
        if (v, f) in LO_DIFFERS_AT:
            continue
        theirs = ws.cell(i, 3).value
        theirs = "" if theirs is None else theirs
        if _ours(float(v), f) != theirs:
            wrong.append((v, f, theirs, _ours(float(v), f)))
    assert wrong == []


DATES = [45000.25, 45123.75, 36526.5, 61.125, 48000.5]  # March 1900 to 2^32 s (LibreOffice)
DATE_FORMATS = [  # (LibreOffice counts dates before March 1900 on the true calendar and
    # truncates fractions of a second; Excel keeps its 29 February 1900 and rounds)
    "[$-409]mmmm d, yyyy", "dddd", "[h]:mm:ss", "mm:ss.0", "h:mm AM/PM",
    "yyyy-mm-dd hh:mm:ss", "d-mmm-yy", '"Week of" mmm d', "[Red]hh:mm", "hh:mm:ss a/p",
    "[mm]:ss", "dd/mm/yyyy h:mm", "mmmmm yy", "h \\h m \\m",
]


def test_date_formats_agree_with_libreoffice(libreoffice, tmp_path):
    cells = {}
    pairs = list(itertools.product(DATES, DATE_FORMATS))
    for i, (v, f) in enumerate(pairs, 1):
        cells[f"A{i}"], cells[f"B{i}"], cells[f"C{i}"] = v, f, f"=TEXT(A{i},B{i})"
    ws = openpyxl.load_workbook(recalculated_sheet(tmp_path, "D", cells), data_only=True)["D"]
    wrong = [(v, f, ws.cell(i, 3).value, _ours(v, f)) for i, (v, f) in enumerate(pairs, 1)
             if _ours(v, f) != ws.cell(i, 3).value]
    assert wrong == []


@pytest.fixture(scope="module")
def pycel_text():
    path = CORPUS / "pycel__text.xlsx"
    if not path.is_file():
        pytest.fail(f"corpus file missing: {path}", pytrace=False)
    return path


@pytest.mark.parametrize("sheet", ["TextNumbers", "TextDates"])
def test_every_case_of_the_excel_saved_file(pycel_text, sheet):
    ws = openpyxl.load_workbook(pycel_text, data_only=True)[sheet]
    checked = 0
    for r in range(2, ws.max_row + 1):
        value, fmt, excel = (ws.cell(r, k).value for k in (1, 2, 3))
        if value is None and fmt is None and excel is None:
            continue
        assert _ours(value, "" if fmt is None else fmt) == ("" if excel is None else excel), (
            sheet, r, value, fmt)
        checked += 1
    assert checked >= 45


def test_excel_saved_file_fully_audited(pycel_text):
    report = audit(pycel_text)
    assert report.mismatches == [] and report.not_checked == {}
    assert report.cells_checked == report.formula_cells


def test_libreoffice_differences_follow_excel():
    """The formats LibreOffice lays out otherwise, on Excel's own cases (rows above)."""
    assert _ours(890123.456789, "%#%#%") == "%89012345678%9%"
    assert _ours(890123.456789, "#x,0,#.00.0") == "890,1x,23.45.7"
    assert _ours(890123.456789, "0,x#.00.0") == "89012x3.45.7"
    assert _ours(890123.456789, "#.###x,##") == "890123.456x,79"
    assert _ours(890123.456789, "#.#####00#0") == "890123.45678900"
    assert _ours(1234.56, ".##0") == "1234.560"
    assert _ours(1.0, "#.##") == "1."
    assert _ours(890123.456789, "#.###.#.#.#") == "890123.456.7.8.9"


def test_time_texts_and_elapsed_counts():
    """Time texts whose last (or first) field runs over, and elapsed counts past 9999."""
    assert _ours("23:9999", "#.#####") == "7.90208"
    assert _ours("24:99", "#.#####") == "24:99"  # not a time: the text itself
    assert _ours("59:9999.0", "#.#####") == ".1567"
    assert _ours(-1.0, "[h]") == "-24" and _ours(-1.0, "[h]:m") == "#VALUE!"
    assert _ours(2958466.0, "[h]") == "71003184" and _ours(2958466.0, "yy") == "#VALUE!"


@pytest.fixture(scope="module")
def formulas_test():
    path = CORPUS / "formulas__test.xlsx"
    if not path.is_file():
        pytest.fail(f"corpus file missing: {path}", pytrace=False)
    return openpyxl.load_workbook(path, data_only=True)


BIG = "123456789076754345682.2121234567832131341"


@pytest.mark.parametrize("cell, call", [  # formulas test.xlsx (saved by Excel): its cells
    ("EXTRA!A4", ("TEXT", [1.23, '#"°F""'])),                 # an unclosed quote
    ("EXTRA!A35", ("TEXT", [2.0, "[<=1]a;[=2]xx;xcx"])),      # conditions
    ("EXTRA!A36", ("TEXT", [3.0, "[<=1]a;[=2]aa;xxx"])),
    ("EXTRA!A37", ("TEXT", [130.0, "m mm mmm mmmm mmmmm mmmmmm mmmmmmm"])),  # long code runs
    ("EXTRA!A38", ("TEXT", [130.0, "d dd ddd dddd ddddd dddddd"])),
    ("EXTRA!A39", ("TEXT", [130.0, "y yy yyy yyyy yyyyyy"])),
    ("EXTRA!A40", ("TEXT", [130.31322, "s ss sss ssss"])),
    ("EXTRA!A41", ("TEXT", [130.63332, "h hh hhh hhhh"])),
    ("EXTRA!N4", ("FIXED", [BIG, "3", 0.0])),                 # 15 significant digits
    ("EXTRA!P4", ("FIXED", [BIG, "3", 2.0])),
])
def test_excel_cells_of_formulas_test(formulas_test, cell, call):
    sheet, ref = cell.split("!")
    out = fx.call(*call)
    out = str(out) if isinstance(out, fx.ExcelError) else out
    assert out == formulas_test[sheet][ref].value


@pytest.mark.parametrize("row", [57, 95])
def test_large_and_small_give_k_error_first(formulas_test, row):
    """LARGE/SMALL(C:K, k) with an error among the values and an error k: k's error."""
    ws = formulas_test["STATISTICAL"]
    values = [[ws.cell(row, col).value for col in range(3, 12)]]
    values = [[fx.ExcelError.from_text(v) or v if isinstance(v, str) else v
               for v in values[0]]]
    name = ws.cell(row, 1).value
    for col in range(12, 18):  # L..Q hold #N/A, #DIV/0!, ... as k
        k = fx.ExcelError.from_text(ws.cell(row, col).value)
        out = fx.call(name, [Range.of(values), k])
        assert str(out) == ws.cell(row, col + 15).value == str(k)
