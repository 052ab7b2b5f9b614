"""lookup/trimrange.py: TRIMRANGE and the trim references, by the rules of Microsoft's
"TRIMRANGE function" page (support.microsoft.com/en-us/excel/functions/trimrange-function:
trim_rows/trim_cols 0 none, 1 leading, 2 trailing, 3 both, the default; A1.:.E10 is
TRIMRANGE(A1:E10,3,3), A1:.E10 is (…,2,2), A1.:E10 is (…,1,1)) on random sparse grids
against a trimming written here, and against Microsoft Excel's cached values of every
TRIMRANGE of formulas__test.xlsx (LOOKUP!R135:AG136)."""

from __future__ import annotations

import random

import pytest

from tests.formula.functions import excel_cached as xc
from workbook_gen.cellref import column_letters
from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula.arrays import evaluate_array
from workbook_gen.xlerror import ExcelError

RNG = random.Random(135)


def test_every_trimrange_of_formulas_test_agrees_with_excel():
    formulas = xc.array_formulas("sheet11", r"TRIMRANGE")
    assert len(formulas) == 11
    res = xc.resolver(("LOOKUP",), 130, 140)
    for anchor, ref, formula in formulas:
        xc.assert_spill(formula, ref, "LOOKUP", res)


def _reference(grid, rows_how, cols_how):
    """The rectangle kept, as (r1, c1, r2, c2) 0-based, or None when nothing is filled."""
    filled_rows = [i for i, r in enumerate(grid) if any(v is not None for v in r)]
    filled_cols = [j for j in range(len(grid[0])) if any(r[j] is not None for r in grid)]
    if not filled_rows:
        return None
    r1 = filled_rows[0] if rows_how in (1, 3) else 0
    r2 = filled_rows[-1] if rows_how in (2, 3) else len(grid) - 1
    c1 = filled_cols[0] if cols_how in (1, 3) else 0
    c2 = filled_cols[-1] if cols_how in (2, 3) else len(grid[0]) - 1
    return r1, c1, r2, c2


@pytest.mark.parametrize("seed", range(12))
def test_trimrange_and_trim_refs_keep_the_rectangle_the_rules_give(seed):
    rng = random.Random(seed)
    h, w = rng.randint(1, 7), rng.randint(1, 6)
    grid = [[float(rng.randint(1, 9)) if rng.random() < 0.15 else None for _ in range(w)]
            for _ in range(h)]
    cells = {f"{column_letters(2 + j)}{3 + i}": v for i, r in enumerate(grid)
             for j, v in enumerate(r) if v is not None}
    res = DictResolver(cells)
    area = f"B3:{column_letters(1 + w)}{2 + h}"
    forms = [(f"TRIMRANGE({area},{a},{b})", a, b) for a in range(4) for b in range(4)]
    forms += [(f"TRIMRANGE({area})", 3, 3), (f"_xlfn._TRO_ALL({area})", 3, 3),
              (f"_xlfn._TRO_TRAILING({area})", 2, 2), (f"_xlfn._TRO_LEADING({area})", 1, 1)]
    for text, a, b in forms:
        want = _reference(grid, a, b)
        got = evaluate_array(parse(text), res, "excel", None)
        if want is None:
            assert got == ExcelError.REF, text
            continue
        r1, c1, r2, c2 = want
        assert got.ref[1:] == (3 + r1, 2 + c1, 3 + r2, 2 + c2), text
        assert [list(r) for r in got.rows] == [r[c1:c2 + 1] for r in grid[r1:r2 + 1]], text


def test_a_trimmed_reference_is_still_a_reference():
    res = DictResolver({"C4": 1.0, "D6": 2.0})
    ev = lambda t: evaluate_array(parse(t), res, "excel", None)  # noqa: E731
    assert ev("ROWS(TRIMRANGE(A1:F9))") == 3.0
    assert ev("MIN(COLUMN(_xlfn._TRO_LEADING(A1:F9)))") == 3.0
    assert ev("COLUMNS(_xlfn._TRO_LEADING(A1:F9))") == 4.0
    assert ev("ROWS(_xlfn._TRO_TRAILING(A1:F9))") == 6.0
    assert ev("SUM(TRIMRANGE(A1:F9))") == 3.0


@pytest.mark.parametrize("option", ["4", "-1", "2.5", '"x"', "{1,2}"])
def test_an_option_outside_the_documented_values_is_an_error(option):
    res = DictResolver({"A1": 1.0})
    got = evaluate_array(parse(f"TRIMRANGE(A1:B2,{option})"), res, "excel", None)
    assert isinstance(got, ExcelError)
