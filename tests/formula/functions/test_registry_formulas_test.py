"""Function semantics fixed against Excel's own cached values in formulas__test.xlsx
(saved by Microsoft Macintosh Excel, 13,487 formula cells; issue 10): each case reads the
file's formula inputs and Excel's cached result, and evaluates the formula with our
functions."""

from __future__ import annotations

import re
from pathlib import Path

import openpyxl
import pytest

from workbook_gen.formula import functions as fx

PATH = Path("/work/shared/corpus/xlsx/formulas__test.xlsx")


@pytest.fixture(scope="module")
def book():
    if not PATH.is_file():
        pytest.fail(f"corpus file missing: {PATH}")
    values = openpyxl.load_workbook(PATH, data_only=True, read_only=True)
    formulas = openpyxl.load_workbook(PATH, read_only=True)
    return values, formulas


def _rows(book, sheet, first, last, cols):
    values, formulas = book
    v = list(values[sheet].iter_rows(min_row=first, max_row=last, max_col=cols,
                                     values_only=True))
    f = list(formulas[sheet].iter_rows(min_row=first, max_row=last, max_col=cols,
                                       values_only=True))
    return v, f


def test_convert_every_unit_and_prefix_of_the_extra_sheet(book):
    """EXTRA!T:AR: a unit per row (T), CONVERT(1,T,"base") in U and CONVERT(1,prefix&T,
    "base") under each prefix of row 1: the ^2/^3 spellings, ly2/ly3, Pica2/Pica3,
    prefixes on uk_pt and mph, "pc" read as a picocalorie next to "J"."""
    values, formulas = _rows(book, "EXTRA", 1, 170, 44)
    prefixes = values[0]
    simple = re.compile(r'=CONVERT\(1,T(\d+),"([^"]+)"\)')
    prefixed = re.compile(r'=CONVERT\(1,([A-Z]+)\$1&\$T(\d+),"([^"]+)"\)')
    checked = 0
    for vrow, frow in zip(values, formulas):
        for j, text in enumerate(frow):
            if not isinstance(text, str):
                continue
            if m := simple.fullmatch(text):
                unit, to = values[int(m.group(1)) - 1][19], m.group(2)
            elif m := prefixed.fullmatch(text):
                unit, to = prefixes[j] + values[int(m.group(2)) - 1][19], m.group(3)
            else:
                continue
            got, cached = fx.call("CONVERT", [1.0, unit, to]), vrow[j]
            if isinstance(cached, str):  # an error: a unit or prefix Excel refuses
                assert str(got) == cached, (unit, to)
            else:
                assert got == pytest.approx(cached, rel=1e-12), (unit, to)
            checked += 1
    assert checked >= 1000
    assert fx.call("CONVERT", [1.0, "pc", "m"]) == pytest.approx(30856775812815500.0)


def _evaluate_block(book, sheet, first, last, cols, pick, arrays_too=True):
    """Evaluate the formula cells of a block (those whose text ``pick`` accepts; array
    formulas over their whole area) from the block's other cells (constants, and other
    formulas' cached values), with our evaluator: [(cell, formula, ours, cached)]."""
    from openpyxl.utils.cell import range_boundaries
    from openpyxl.worksheet.formula import ArrayFormula

    from workbook_gen.evaluator import evaluate_cells
    from workbook_gen.xlerror import ExcelError
    values, formulas = _rows(book, sheet, first, last, cols)
    constants, wanted, arrays, texts = {}, {}, {}, {}
    for i, frow in enumerate(formulas):
        for j, f in enumerate(frow):
            key = (sheet, first + i, j + 1)
            if isinstance(f, ArrayFormula) and arrays_too and pick(f.text):
                _, _, c2, r2 = range_boundaries(f.ref)
                arrays[key] = (f.text[1:], (r2, c2))
                for r in range(key[1], r2 + 1):
                    for k in range(key[2], c2 + 1):
                        texts[(sheet, r, k)] = f.text
            elif isinstance(f, str) and f.startswith("=") and pick(f):
                wanted[key] = texts[key] = f[1:]
    for i, vrow in enumerate(values):
        for j, v in enumerate(vrow):
            key = (sheet, first + i, j + 1)
            if key not in texts and v is not None:
                constants[key] = (ExcelError.from_text(v) or v) if isinstance(v, str) else v
    result = evaluate_cells(wanted, constants, {}, arrays=arrays)
    return [(k, texts[k], result.values[k], values[k[1] - first][k[2] - 1])
            for k in texts if k[1] <= last and k[2] <= cols]


def _same(ours, cached) -> bool:
    if isinstance(cached, str) and cached.startswith("#"):
        return str(ours) == cached
    if isinstance(cached, (int, float)) and not isinstance(cached, bool):
        return isinstance(ours, float) and ours == pytest.approx(cached, rel=1e-12)
    return ours == cached


def test_xmatch_modes_across_types_and_binary_searches(book):
    """LOOKUP!R170:Y197 and EXTRA!K70:P95: next smaller/larger across types (numbers <
    text < FALSE < TRUE, an empty lookup past everything), wildcards with a binary search
    (#VALUE!), the binary search over descending data, "ß" = "ss"."""
    cases = (_evaluate_block(book, "LOOKUP", 160, 200, 26, lambda f: "XMATCH(" in f)
             + _evaluate_block(book, "EXTRA", 70, 95, 17, lambda f: "XMATCH(" in f))
    wrong = [c for c in cases if not _same(c[2], c[3])]
    assert len(cases) >= 150 and wrong == []


def test_criteria_functions_map_over_an_array_of_criteria(book):
    """{=COUNTIF(F24:J24,{"*ao","","TRUE",TRUE,"*a?"})} and the SUMIF, AVERAGEIF(S),
    SUMIFS, COUNTIFS, MAXIFS, MINIFS rows: one result per criterion, #N/A past them."""
    crit = '{"*ao","","TRUE",TRUE,"*a?"}'
    cases = (_evaluate_block(book, "STATISTICAL", 1, 130, 50, lambda f: crit in f)
             + _evaluate_block(book, "MATH & TRIG", 60, 90, 50, lambda f: crit in f))
    wrong = [c for c in cases if not _same(c[2], c[3])]
    assert len(cases) >= 100 and wrong == []


def test_is_functions_map_over_a_range_and_n_takes_its_first_cell(book):
    """INFORMATION!R5:AW20: {=ISERR(C7:Q7)} tests each cell; {=N(C19:Q19)} is N(C19) in
    every cell of its area. (Left: the cells of an area past its range, where Excel tests
    the #N/A that pads the range to the area (ISNA gives TRUE there): ours is the padding
    #N/A itself.)"""
    from workbook_gen.xlerror import ExcelError
    cases = _evaluate_block(book, "INFORMATION", 5, 20, 49, lambda f: f.startswith(
        ("=ISBLANK", "=ISERR", "=ISNA", "=ISNUMBER", "=ISTEXT", "=ISNONTEXT", "=ISLOGICAL",
         "=N(")))
    wrong = [c for c in cases if not _same(c[2], c[3])]
    assert len(cases) >= 250
    assert all(c[2] is ExcelError.NA and isinstance(c[3], bool) for c in wrong), wrong
    assert len(wrong) <= 20


def test_isoweeknum_datedif_yd_and_quartile_rows(book):
    """DATE & TIME rows 4 and 12: ISOWEEKNUM before March 1900 on Excel's weekdays
    (serial 1 a Sunday: week 52), DATEDIF "YD" in the start date's year (DATEDIF(8, 1987,
    "YD") = 153); COMPATIBILITY row 32 and STATISTICAL row 88: the quart argument floored
    (-0.1 is -1: #NUM!)."""
    cases = (_evaluate_block(book, "DATE & TIME", 4, 4, 49, lambda f: "DATEDIF(" in f)
             + _evaluate_block(book, "DATE & TIME", 12, 12, 49, lambda f: "ISOWEEKNUM(" in f)
             + _evaluate_block(book, "COMPATIBILITY", 32, 32, 49, lambda f: "QUARTILE(" in f)
             + _evaluate_block(book, "STATISTICAL", 88, 88, 49, lambda f: "QUARTILE" in f))
    wrong = [c for c in cases if not _same(c[2], c[3])]
    assert len(cases) >= 80 and wrong == []
    assert fx.call("DATEDIF", [37043.0, 37483.0, "YD"]) == 75.0  # Microsoft's example


def test_weeknum_and_edate_on_day_zero(book):
    """DATE & TIME rows 9 and 23: WEEKNUM of 1900-01-00 is 0 and of TRUE #VALUE!; EDATE
    from 1900-01-00 keeps day 0 (the day before the 1st)."""
    cases = (_evaluate_block(book, "DATE & TIME", 9, 9, 49, lambda f: "EDATE(" in f, False)
             + _evaluate_block(book, "DATE & TIME", 23, 23, 49, lambda f: "WEEKNUM(" in f,
                               False))
    wrong = [c for c in cases if not _same(c[2], c[3])]
    assert len(cases) >= 20 and wrong == []
    # Excel's 1900 starts on a Sunday: 4 March 1900 (serial 64) opens week 10
    assert fx.call("WEEKNUM", [64.0, 1.0]) == 10.0 and fx.call("WEEKNUM", [63.0, 1.0]) == 9.0


def test_gcd_and_lcm_want_numbers_in_every_cell(book):
    """MATH & TRIG rows 34 and 37: GCD/LCM of an empty cell, text or a boolean is #VALUE!,
    before a negative number's #NUM! (GCD(G34,J34) with G34 = -0.4, J34 = TRUE)."""
    cases = (_evaluate_block(book, "MATH & TRIG", 34, 34, 33, lambda f: "GCD(" in f, False)
             + _evaluate_block(book, "MATH & TRIG", 37, 37, 33, lambda f: "LCM(" in f, False))
    wrong = [c for c in cases if not _same(c[2], c[3])]
    assert len(cases) >= 28 and wrong == []
