"""Excel's coercion rules that Excel-saved files pin down: number-to-text (Apache POI's table
measured in Excel), currency text read as a number (Microsoft's VALUE page), criteria ranges
intersected, single text values in SUMPRODUCT, MODE's direct arguments, FV's rounding; and the
Excel-saved POI FormulaEvalTestData.xlsx whose cached cells show each rule."""

from __future__ import annotations

import os
import struct

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.formula.values import number_to_text
from workbook_gen.xlerror import ExcelError as E

# raw bits -> Excel's text (POI NumberToTextConverter's table, measured in Excel)
EXCEL_TEXT = {
    0x3FF00068DB8BAC71: "1.0001", 0x405EDD3C07FB4C99: "123.456789012346",
    0x3EE9E409302678BA: "1.23456789012346E-05", 0x3F202E85BE180B74: "0.000123456789012346",
    0x3EE9E409301B5A02: "0.0000123456789", 0x3E6E7D05BDABDE50: "0.000000056789012345",
    0x3E6E7D05BDAD407E: "5.67890123456E-08", 0x2BCB5733CB32AE6E: "9.99999999999912E-98",
    0x359DEE7A4AD4B81F: "2E-50", 0x42A674E79C5FE523: "12345678901234.6",
    0x42DC12218377DE6B: "123456789012346", 0x43118B54F22AEB03: "1234567890123460",
    0x43E56A95319D63E1: "12345678901234600000", 0x441AC53A7E04BCDA: "1.23456789012346E+20",
    0xC41AC53A7E04BCDA: "-1.23456789012346E+20", 0x4A611B0EC57E649A: "2E+50",
    0x441AC7A08EAD02F2: "1.235E+20", 0x40FE26BFFFFFFFF9: "123500",
    0x3E4A857BFB2F2809: "0.00000001235", 0x3BCD291DEF868C89: "1.235E-20",
    0x444B1AE4D6E2EF4F: "1E+21", 0x412E847FFFFFFFFF: "1000000", 0x3E45798EE2308C39: "0.00000001",
    0x3C32725DD1D243AB: "0.000000000000000001", 0x3BFD83C94FB6D2AB: "1E-19",
    0xBE45798EE2308C39: "-0.00000001", 0x000FFFFFFFFFFFFF: "0",
}


@pytest.mark.parametrize("bits", list(EXCEL_TEXT), ids=[EXCEL_TEXT[b] for b in EXCEL_TEXT])
def test_number_to_text_as_excel_writes_it(bits):
    x = struct.unpack(">d", struct.pack(">Q", bits))[0]
    assert number_to_text(x) == EXCEL_TEXT[bits]


CELLS = {"A1": "$1.00", "A2": "4", "B2": 2.0, "B8": 1.0, "B9": 2.0, "C9": 1.1,
         "AA8": E.DIV0, "AA9": E.VALUE, "C10": 1.00001}


@pytest.mark.parametrize("formula,expected", [
    ('=VALUE("$1,000")', 1000.0),             # Microsoft's VALUE page
    ('=DOLLAR(A1)', "$1.00"),
    ('="1,00"+1', E.VALUE),                   # not a thousands grouping
    ('=SEARCH(1,0.00001)', 7.0),
    ('=SUMPRODUCT(A2:A2,B2:B2)', E.VALUE), ('=SUMPRODUCT(B2,3)', 6.0),
    ('=SUMPRODUCT(A2:B2,A2:B2)', 4.0),        # text in a range is 0
    ('=MODE(B8,"1",2,3)', E.VALUE), ('=MODE(B9,2,D7)', E.VALUE), ('=MODE(1,1,2,3)', 1.0),
])
def test_excel_rules(formula, expected):
    assert evaluate(parse(formula), DictResolver(CELLS), dialect="excel") == expected


def test_criteria_range_without_a_shared_cell_is_value_error():
    from workbook_gen.evaluator import evaluate_cells
    formulas = {("S", 20, 1): "SUMIF(AA7:AA13,C10:D10,C7)", ("S", 20, 3): "SUMIF(AA7:AA13,C10:D10,C7)"}
    consts = {("S", 7, 27): E.NULL, ("S", 8, 27): E.DIV0, ("S", 9, 27): E.VALUE,
              ("S", 10, 27): 1.00001, ("S", 10, 3): 1.00001, ("S", 7, 3): 5.0, ("S", 9, 3): 1.1}
    got = evaluate_cells(formulas, consts, {}, dialect="excel").values
    assert got[("S", 20, 1)] == 1.1          # criterion #VALUE! matches AA9
    assert got[("S", 20, 3)] == 1.00001      # column C shares C10: 1.00001 matches AA10


def test_poi_formula_eval_test_data_fully_agrees():
    from workbook_gen.auditor import audit
    path = "/work/shared/corpus/xlsx/poi__FormulaEvalTestData_Copy.xlsx"
    if not os.path.isfile(path):
        pytest.fail(f"the corpus is missing: {path}")
    report = audit(path)
    assert report.mismatches == [] and report.not_checked == {}
    assert report.libreoffice_semantics == 0   # Excel's rules, none explained away


def test_text_e_is_the_year():
    """Excel's "e" date code is the (era) year: sheetjs formula_stress_test.xlsx, saved by
    Excel, caches TEXT(7-Jul-1977, "ee-mm-dd") as "1977-07-07"."""
    got = evaluate(parse('=TEXT(28313,"ee-mm-dd")'), DictResolver({}), dialect="excel")
    assert got == "1977-07-07"


def test_cached_formula_text_is_unescaped():
    """A formula's cached text is an ST_Xstring as shared strings are: CHAR(7) is stored as
    _x0007_ (sheetjs formula_stress_test.xlsx Text!C38)."""
    from workbook_gen.auditor.inputs import read_inputs
    path = "/work/shared/corpus/xlsx/sheetjs__formula_stress_test.xlsx"
    if not os.path.isfile(path):
        pytest.fail(f"the corpus is missing: {path}")
    assert read_inputs(path).cached[("Text", 38, 3)] == "\x077\x07"


@pytest.mark.parametrize("formula,expected", [
    # ECMA-376 Part 1 18.17.7.33 CEILING (examples of the pre-2010 CEILING page, whose rule it is)
    ("ECMA.CEILING(2.5,1)", 3.0), ("ECMA.CEILING(-2.5,-2)", -4.0), ("ECMA.CEILING(-2.5,2)", E.NUM),
    ("ECMA.CEILING(1.5,0.1)", 1.5), ("ECMA.CEILING(0.234,0.01)", 0.24),
])
def test_ecma_ceiling(formula, expected):
    got = evaluate(parse("=" + formula), DictResolver({}), dialect="excel")
    assert got == expected or (isinstance(got, float) and abs(got - expected) < 1e-12), got


def test_char_and_code_use_the_macintosh_set_in_excel_for_mac():
    """Microsoft's CHAR page: Windows uses the ANSI set, the Macintosh the Macintosh set. The
    Excel-for-Mac-saved sheetjs stress test caches CHAR(240) as the Apple logo (U+F8FF) and
    CODE of it as 240; the same cells of a Windows workbook are cp1252's."""
    from workbook_gen.auditor.inputs import read_inputs
    from workbook_gen.evaluator import evaluate_cells
    from workbook_gen.evaluator.book import BookInfo
    path = "/work/shared/corpus/xlsx/sheetjs__formula_stress_test.xlsx"
    if not os.path.isfile(path):
        pytest.fail(f"the corpus is missing: {path}")
    inputs = read_inputs(path)
    assert inputs.book.application == "Microsoft Macintosh Excel"
    got = evaluate_cells(inputs.formulas, inputs.constants, inputs.book.defined_names,
                         book=inputs.book_info()).values
    for key in (("Text", 20, 2), ("Text", 21, 2)):
        assert got[key] == inputs.cached[key], key
    formulas = {("S", 1, 1): "CHAR(240)", ("S", 2, 1): 'CODE("\u00f0")', ("S", 3, 1): "CHAR(65)"}
    windows = evaluate_cells(formulas, {}, {}, book=BookInfo(["S"])).values
    mac = evaluate_cells(formulas, {}, {}, book=BookInfo(["S"], charset="mac_roman")).values
    assert [windows[k] for k in formulas] == ["\u00f0", 240.0, "A"]
    assert [mac[k] for k in formulas] == ["\uf8ff", 63.0, "A"]  # no eth in Mac Roman
