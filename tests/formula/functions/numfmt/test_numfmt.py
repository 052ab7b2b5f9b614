"""TEXT's number formats against Excel's own outputs.

Two independent references:
* the values Excel cached in NPOI's format test workbooks (NumberFormatApproxTests.xlsx:
  scientific patterns with literals, commas and percent between the digits;
  FormatChoiceTests.xlsx: conditional sections; DateFormatTests.xlsx: a 1904 workbook),
  read from the files here: every TEXT cell is recomputed from its row's format and value;
* SheetJS ssf's published tests of Excel's outputs (test/exp.tsv, test/fraction.json,
  test/oddities.json in github.com/SheetJS/ssf), a few rows of each transcribed below as
  (value, format, Excel's text).
"""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import openpyxl
import pytest
from openpyxl.utils.datetime import to_excel

from workbook_gen import audit
from workbook_gen.formula import functions as fx
from workbook_gen.formula.functions.numfmt.fraction import convergent
from workbook_gen.formula.functions.serials import date_system

CORPUS = Path("/work/shared/corpus/xlsx")
NPOI = ["npoi__NumberFormatApproxTests.xlsx", "npoi__FormatChoiceTests.xlsx",
        "npoi__DateFormatTests.xlsx"]


def _text(v, f):
    out = fx.call("TEXT", [v, f])
    return str(out) if isinstance(out, fx.ExcelError) else out


def _book(name: str) -> Path:
    path = CORPUS / name
    if not path.is_file():
        pytest.fail(f"corpus file missing: {path}", pytrace=False)
    return path


@pytest.mark.parametrize("name", NPOI)
def test_every_text_cell_of_npoi_format_tests(name):
    """Row by row: A holds =TEXT(C, B) with Excel's cached text; B the format, C the
    value (a date in the 1904 workbook is turned back into its serial in that system)."""
    path = _book(name)
    cached = openpyxl.load_workbook(path, data_only=True)
    formulas = openpyxl.load_workbook(path)
    ws, fs = cached["Tests"], formulas["Tests"]
    checked, wrong = 0, []
    with date_system(cached.epoch.year == 1904):
        for r in range(2, ws.max_row + 1):
            formula = fs.cell(r, 1).value
            if not (isinstance(formula, str) and formula.upper().startswith("=TEXT(")):
                continue
            excel, fmt, value = (ws.cell(r, k).value for k in (1, 2, 3))
            if fmt is None or value is None:
                continue  # (a row without a case: its formula reads empty cells)
            if not isinstance(value, (int, float)):
                value = to_excel(value, cached.epoch)
            ours = _text(float(value), fmt)
            if ours != excel:
                wrong.append((r, fmt, value, excel, ours))
            checked += 1
    assert wrong == []
    assert checked >= 24  # (NumberFormatApprox 248, FormatChoice 24, DateFormat 41 rows)


@pytest.mark.parametrize("name", NPOI)
def test_npoi_format_tests_fully_agree_in_the_audit(name):
    report = audit(_book(name))
    assert report.mismatches == [] and report.not_checked == {}
    assert report.cells_checked == report.formula_cells


@pytest.mark.parametrize("value, fmt, excel", [
    # SheetJS ssf test/exp.tsv: engineering steps of the integer placeholders
    (1.23457e-13, "#0.0E+0", "12.3E-14"), (1.23457e-13, "##0.0E+0", "123.5E-15"),
    (1.23457e-13, "###0.0E+0", "1234.6E-16"), (1.23457e-13, "####0.0E+0", "123.5E-15"),
    (0.000123457, "##0.0E+0", "123.5E-6"), (1234.56789, "#0.0E+0", "12.3E+2"),
    (12345678.9, "###0.0E+0", "1234.6E+4"), (1234567890, "####0.0E+0", "12345.7E+5"),
    (123456789000, "##0.0E+0", "123.5E+9"),
    # SheetJS ssf test/oddities.json
    (123456789, "##0.0E+0", "123.5E+6"), (1234, "##0.0E+0", "1.2E+3"),
    (12.3456789, "??/??", "1000/81"), (0.00001, "??/??", " 0/1 "),
    (12.3456789, "# ??/??", "12 28/81"), (12.3456789, "#??/??", "1000/81"),
    (12.3456789, "#0#00??/??", "01000/81"),
    (8675309, "[<=9999999]###-####;(###) ###-####", "867-5309"),
    (2813308004, "[<=9999999]###-####;(###) ###-####", "(281) 330-8004"),
    (1, '_($* #,##0_);_($* (#,##0);_($* "-"_);_(@_)', " $1 "),
    (-1, '_($* #,##0_);_($* (#,##0);_($* "-"_);_(@_)', " $(1)"),
    (0, '_($* #,##0_);_($* (#,##0);_($* "-"_);_(@_)', " $- "),
    (0.7, "hh:mm AM/PM", "04:48 PM"), (0.7, "A/P", "P"),
    (12345, "00,000.00,", "00,012.35"), (941051630, "00000-0000", "94105-1630"),
    # SheetJS ssf test/fraction.json
    (1, "# ?/?", "1    "), (-1.2, "# ?/?", "-1 1/5"), (123.45, "# ?/?", "123 4/9"),
    (-12345.67891, "# ?/?", "-12345 2/3"), (1, "# ??/??", "1      "),
    (-1.2, "# ??/??", "-1  1/5 "), (-123.456, "# ??/??", "-123 26/57"),
    (1234.567, "# ??/??", "1234 55/97"), (-123.456, "# ???/???", "-123  57/125"),
    (-12345.67891, "# ???/???", "-12345 573/844"), (-1.2, "# ?/2", "-1    "),
    (123.45, "# ?/4", "123 2/4"), (12.3, "# ?/8", "12 2/8"), (-1.2, "# ??/16", "-1  3/16"),
    (12345.6789, "# ??/16", "12345 11/16"), (1, "# ?/10", "1     "),
    (-123.456, "# ?/10", "-123 5/10"), (1, "# ??/100", "1       "),
    (-12.34, "# ??/100", "-12 34/100"), (1, "??/??", " 1/1 "), (-1.2, "??/??", "- 6/5 "),
    (12.3, "??/??", "123/10"), (-1234.5678, "??/??", "-100000/81"),
    (0.3, "# ?/?", " 2/7"), (2.3, "# ?/?", "2 2/7"),
    (-123.456, "# ?/?", "-123 1/2"),  # (a convergent: 4/9 would be closer)
])
def test_sheetjs_published_excel_outputs(value, fmt, excel):
    assert _text(float(value), fmt) == excel


@pytest.mark.parametrize("value, fmt, excel", [
    # NPOI NumberFormatApproxTests.xlsx (Excel): rows 2, 6, 10, 20, 104, 226, 244
    (123456.789, "|#,e-#|", "|1e5|"),
    (123456.789, "|#|e-|#|", "|1|e|5|"),
    (123456.789, "|#,######.####|e-|#|", "|123,456.789|e|0|"),
    (123456.789, "|?,??????.????|e-|?|", "|  123,456.789 |e|0|"),
    (0, "|####.####|e-|#|", "|0000.|e|0|"),
    (1.2345678e142, "|#.#|e+|????|", "|1.2|e|+ 142|"),
    (1.2345678e-142, "|#.#|e+|000,00|", "|1.2|e|-00142|"),
    # formulas' test.xlsx (Excel): EXTRA!A27 (a decimal point after the exponent), A28
    (1234578.555, "#,##00000,  ,00 , 0##e+8800######    .  # ,0.00.0,00", "#VALUE!"),
    (12200000, "#######.0E+00", "1.2E+07"),
])
def test_scientific_patterns_with_literals(value, fmt, excel):
    assert _text(float(value), fmt) == excel


def test_fraction_stops_at_a_convergent_close_to_15_digits():
    """ssf's fraction.json: Excel shows 0.123251512342345 as # ??/????????? "  480894/3901729"
    (the layout of a numerator overflowing its placeholders is not modelled)."""
    assert convergent(Fraction(0.123251512342345), 999_999_999) == (480894, 3901729)


def test_conditions_pick_sections_and_fall_back_to_general():
    """NPOI FormatChoiceTests.xlsx (rows 2-19) and Microsoft's KB 67469 (the second
    section's own [<0] drops the sign, another condition keeps it)."""
    assert _text(1.5, '[<10]#" Wow"') == "2 Wow"
    assert _text(10.0, '[<10]#" Wow"') == "10"
    assert _text(10.0, '[<>10]#" Wow"') == "10"
    assert _text(-5.0, "[>100]General;[<100](General);General") == "-(5)"
    assert _text(-5.0, "[>100]General;[<0](General);General") == "(5)"
    assert _text(999.0, "[>1000][red]0.00E+00;General;0.00") == "999.00"
    assert _text(1001.0, "[>1000][red]0.00E+00;General;0.00") == "1.00E+03"
    assert _text(5.0, "[>3][Red]0.00;[<6][Blue]0.00;0.00") == "5.00"


def test_text_sections():
    """SheetJS ssf oddities.json: the text section, and text without one."""
    assert _text("sheetjs", '"foo";"bar";"baz";"qux"') == "qux"
    assert _text("sheetjs", '"foo";"bar";"baz"') == "sheetjs"
    assert _text(0.0, '"foo";"bar";@') == "foo"
    assert _text("sheetjs", "@@") == "sheetjssheetjs"
    assert _text(-1.0, "[Blue]General") == "-1"
