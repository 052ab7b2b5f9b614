"""Cells that were "not checked" although the file holds what checks them (issue 20).

- The consistency rule: a cell that cannot be recomputed holds its cached value for its
  readers (Excel computed them in one recalculation), which are then checked.
- NOW and TODAY are one unknown per recalculation, fixed by the cells that are just
  ``=NOW()``: ``RAND()*NOW()`` is then one draw, checked by its contract.
- An unsupported function on a branch that the evaluation does not take.
- LAMBDAs held by defined names and called by name; FORMULATEXT, SHEET, SHEETS, RRI.
- Availability: a future function stored without its ``_xlfn.`` prefix, an unknown name.

References: the values Excel cached in the corpus files (read from the files here),
Microsoft's documented examples, openpyxl's list of the standard's functions.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from workbook_gen.auditor import audit
from workbook_gen.evaluator import evaluate_cells
from workbook_gen.evaluator.volatile import Clock
from workbook_gen.formula.functions import availability
from workbook_gen.formula.functions.lookup.reference import display_text
from workbook_gen.formula.parser import parse
from workbook_gen.formula.scalar import DictResolver, evaluate
from workbook_gen.xlerror import ExcelError

CORPUS = Path("/work/shared/corpus/xlsx")


def _corpus(name: str):
    path = CORPUS / name
    if not path.is_file():
        pytest.fail(f"the corpus is missing: {path}", pytrace=False)
    return audit(path)


def _cached(name: str):
    """{(sheet, A1 reference): formula text, cached value} of a corpus workbook."""
    import warnings

    import openpyxl
    with warnings.catch_warnings():  # (openpyxl on serials past its date range)
        warnings.simplefilter("ignore")
        formulas = openpyxl.load_workbook(CORPUS / name)
        values = openpyxl.load_workbook(CORPUS / name, data_only=True)
    out = {}
    for ws in formulas:
        for row in ws.iter_rows():
            for c in row:
                text = getattr(c.value, "text", c.value)
                if isinstance(text, str) and text.startswith("="):
                    out[(ws.title, c.coordinate)] = (text, values[ws.title][c.coordinate].value)
    return out


def _name(sheet: str, ref: str) -> str:
    return (f"'{sheet}'" if " " in sheet else sheet) + "!" + ref


# -- the consistency rule ------------------------------------------------------------------

def test_a_cell_without_a_cached_value_still_taints_its_readers():
    S = "S"
    formulas = {(S, 1, 1): '_xlfn.WEBSERVICE("x")', (S, 1, 2): "A1*2",
                (S, 2, 1): '_xlfn.WEBSERVICE("y")', (S, 2, 2): "A2*2"}
    clock = Clock({(S, 1, 1): 21.0, (S, 1, 2): 42.0, (S, 2, 2): 8.0}, None)
    result = evaluate_cells(formulas, {}, {}, saved=clock)
    assert result.values[(S, 1, 2)] == 42.0 and (S, 1, 2) not in result.not_checked
    assert result.not_checked[(S, 2, 2)].startswith("depends on S!A2")  # A2 has no value
    assert set(result.not_checked) == {(S, 1, 1), (S, 2, 1), (S, 2, 2)}


def test_readers_of_vba_functions_are_checked_from_their_cached_values():
    report = _corpus("poi__stress002.xlsx")
    assert report.mismatches == []
    assert not any(r.startswith("depends on") for r in report.not_checked.values())
    # left: the cells whose evaluation reaches a VBA function (SROUND, CROUND ...)
    assert all(r.startswith("unknown function") for r in report.not_checked.values())
    cells = _cached("poi__stress002.xlsx")
    # IF(cond, SROUND(...), 0) with cond false: recomputed, and Excel's value reproduced
    guarded = [_name(s, r) for (s, r), (text, value) in cells.items()
               if text.upper().startswith("=IF(") and "ROUND(" in text.upper() and value == 0]
    checked = [c for c in guarded if c not in report.not_checked]
    assert len(checked) >= 60, (len(guarded), len(checked))


def test_a_branch_not_taken_does_not_need_its_function(tmp_path):
    import xlsxwriter
    path = tmp_path / "branch.xlsx"
    book = xlsxwriter.Workbook(path)
    sheet = book.add_worksheet()
    sheet.write_number("A1", 0)
    sheet.write_number("A2", 1)
    sheet.write_formula("B1", '=IF(A1>0,_xlfn.WEBSERVICE("u"),7)', None, 7)
    sheet.write_formula("B2", '=IF(A2>0,_xlfn.WEBSERVICE("u"),7)', None, 5)
    sheet.write_formula("C1", '=IF(A1>0,_xlfn.WEBSERVICE("u"),7)+1', None, 9)  # stale
    book.close()
    report = audit(path)
    assert set(report.not_checked) == {"Sheet1!B2"}
    assert [m.cell for m in report.mismatches] == ["Sheet1!C1"]


# -- NOW and TODAY: one moment per recalculation ---------------------------------------------

def test_rand_times_now_is_checked_at_the_moment_the_now_cells_cache():
    report = _corpus("openxmlsdk__NoExtDataA1.xlsx")
    cells = _cached("openxmlsdk__NoExtDataA1.xlsx")
    mixed = [_name(s, r) for (s, r), (text, _) in cells.items() if text == "=RAND()*NOW()"]
    assert len(mixed) == 1249
    assert report.not_checked == {} and report.mismatches == []
    assert all("RAND()" in report.by_contract[c] and "NOW()" in report.by_contract[c]
               for c in mixed)


def test_a_moment_never_makes_a_disagreement():
    S = "S"
    t = 46000.25
    formulas = {(S, 1, 1): "NOW()", (S, 2, 1): "RAND()*NOW()", (S, 3, 1): "RAND()*NOW()",
                (S, 4, 1): "NOW()-TODAY()"}
    cached = {(S, 1, 1): t, (S, 2, 1): 0.5 * t, (S, 3, 1): 2 * t, (S, 4, 1): 0.25}
    result = evaluate_cells(formulas, {}, {}, saved=Clock(cached, None))
    assert result.contract[(S, 2, 1)].status == "agrees"
    assert result.contract[(S, 4, 1)].status == "agrees"
    assert (S, 3, 1) in result.not_checked  # RAND() = 2 is outside [0, 1): not settled,
    assert (S, 3, 1) not in result.contract  # but NOW may have been another moment


def test_today_in_a_single_cell_array_formula_is_checked_by_contract():
    report = _corpus("ironcalc__wordle.xlsx")
    assert report.not_checked == {} and report.mismatches == []
    assert "TODAY()" in report.by_contract["Wordle!N2"]


# -- LAMBDAs called by name, FORMULATEXT, SHEET, RRI -----------------------------------------

@pytest.mark.parametrize("name", ["ironcalc__yearly_calendar.xlsx",
                                  "ironcalc__event_calendar.xlsx"])
def test_lambdas_held_by_defined_names_are_called_by_name(name):
    report = _corpus(name)
    assert report.not_checked == {} and report.mismatches == []


def test_a_named_lambda_reads_cells_computed_before_it_is_called():
    S = "S"
    names = {"ADDB": "_xlfn.LAMBDA(_xlpm.x,_xlpm.x+S!$B$1)", "TWICE": "_xlfn.LAMBDA(_xlpm.x,_xlpm.x*2)"}
    formulas = {(S, 1, 3): "ADDB(A1)", (S, 1, 2): "A1*10", (S, 2, 3): "TWICE(ADDB(1))"}
    result = evaluate_cells(formulas, {(S, 1, 1): 3.0}, names)
    assert result.values[(S, 1, 3)] == 33.0 and result.values[(S, 2, 3)] == 62.0
    assert result.not_checked == {}


@pytest.mark.parametrize("name", ["ironcalc__ERF-PRECISE.xlsx", "ironcalc__MONTH.xlsx",
                                  "ironcalc__CHOOSE.xlsx", "ironcalc__RRI.xlsx",
                                  "ironcalc__tables.xlsx"])
def test_formulatext_sheet_and_rri_reproduce_excel(name):
    report = _corpus(name)
    assert report.not_checked == {}
    cells = _cached(name)
    ours = {_name(s, r) for (s, r), (text, _) in cells.items()
            if any(f in text.upper() for f in ("FORMULATEXT(", "SHEET(", "RRI("))}
    assert ours and not ours & {m.cell for m in report.mismatches}


def test_formulatext_shows_the_formula_without_the_file_prefixes():
    assert display_text('_xlfn.LET(_xlpm.x,"_xlfn.A",_xlfn._xlws.SORT(A1:A3)+_xlpm.x)') == (
        'LET(x,"_xlfn.A",SORT(A1:A3)+x)')


def test_rri_microsoft_example():
    # support.microsoft.com, RRI function: $10,000 growing to $11,000 in 96 months
    value = evaluate(parse("_xlfn.RRI(96,10000,11000)"), DictResolver())
    assert value == pytest.approx(0.0009933, abs=5e-8)


# -- availability --------------------------------------------------------------------------

def test_future_functions_are_those_outside_the_standard():
    import openpyxl.utils.formulas
    from workbook_gen.formula import functions as fx
    standard = openpyxl.utils.formulas.FORMULAE  # ECMA-376 Part 1, 18.17.7
    assert not availability.FUTURE & standard
    assert set(fx.REGISTRY) - standard <= availability.FUTURE
    assert standard <= set(fx.REGISTRY) | availability.STANDARD_UNIMPLEMENTED


def test_a_future_function_without_its_prefix_is_an_unknown_name(tmp_path):
    import xlsxwriter
    path = tmp_path / "prefix.xlsx"
    book = xlsxwriter.Workbook(path)
    sheet = book.add_worksheet()
    sheet.write_column("A1", [1, 2, 3])
    sheet.write_formula("B1", '=MINIFS(A1:A3,A1:A3,">1")', None, "#NAME?")
    sheet.write_formula("B2", '=MINIFS(A1:A3,A1:A3,">1")', None, 2)  # an add-in's?
    sheet.write_formula("B3", '=_xlfn.MINIFS(A1:A3,A1:A3,">1")', None, 2)
    sheet.write_formula("B4", '=CRAPNAME(A1)', None, "#NAME?")
    sheet.write_formula("B5", "=B3+1", None, 3)
    book.close()
    report = audit(path)
    assert report.mismatches == []
    assert set(report.not_checked) == {"Sheet1!B2"}
    assert "without its _xlfn. prefix" in report.not_checked["Sheet1!B2"]
    assert report.cells_agree == 4


def test_libreoffice_and_typed_text_compute_a_future_function_without_its_prefix():
    S = "S"
    formulas = {(S, 1, 2): 'MINIFS(A1:A3,A1:A3,">1")'}
    constants = {(S, r, 1): float(r) for r in (1, 2, 3)}
    stored = evaluate_cells(formulas, constants, {}, stored=True)
    assert stored.values[(S, 1, 2)] is ExcelError.NAME
    lo = evaluate_cells(formulas, constants, {}, dialect="libreoffice", stored=True)
    assert lo.values[(S, 1, 2)] == 2.0
    typed = evaluate_cells(formulas, constants, {})  # as a person types it
    assert typed.values[(S, 1, 2)] == 2.0


def test_an_unknown_name_that_excel_cached_as_name_error_is_checked():
    report = _corpus("npoi__testNames.xlsm")
    assert "Sheet1!A6" not in report.not_checked  # =crapName("abc"), #NAME? in Excel
    assert set(report.not_checked) == {"Sheet1!B1", "Sheet1!C1", "Sheet1!A5"}  # VBA
    assert report.mismatches == []
