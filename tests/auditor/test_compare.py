"""auditor/compare.py: cached against recomputed.

The tolerance follows Excel's storage of 15 significant digits ("Floating-point
arithmetic may give inaccurate results in Excel",
https://learn.microsoft.com/en-us/office/troubleshoot/excel/floating-point-arithmetic-inaccurate-result):
a value Excel saved differs from the float64 recomputation in the 15th-16th digit, and a
difference tiny against the formula's operands (=0.1+0.2-0.3) is rounding. Errors, text
and booleans compare exactly (TRUE is not 1 in a comparison:
https://support.microsoft.com/en-us/office/calculation-operators-and-precedence-in-excel-48be406d-4975-4d31-b2b8-7af9e0e2878a).
Expected values below are derived by hand from |a-b| <= max(1e-10 |a|, 1e-10 m)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbook_gen.auditor.compare import ColumnStats, Verdict, compare, compare_numbers
from workbook_gen.xlerror import ExcelError


def test_fifteen_digits_agree_and_the_ninth_does_not():
    assert compare(0.3, 0.1 + 0.2, 0.0).agree                   # 0.30000000000000004
    assert compare(1234.56789012345, 1234.567890123449, 0.0).agree
    v = compare(1.0, 1.0 + 1e-9, 0.0)
    assert not v.agree
    assert v.abs_error == pytest.approx(1e-9, rel=1e-6)
    assert v.rel_error == pytest.approx(1e-9 / (1 + 1e-9), rel=1e-6)


def test_a_residual_is_measured_against_its_operands():
    # =0.1+0.2-0.3 is 5.55e-17 in float64; Excel shows 0 (operands ~0.3)
    residual = 0.1 + 0.2 - 0.3
    assert compare(0.0, residual, 0.3).agree
    assert not compare(0.0, residual, 0.0).agree  # nothing to measure it against
    v = compare(0.0, 3e-16, 100.0)
    assert v.agree and v.rel_error == pytest.approx(3e-18)
    assert not compare(0.0, 2e-8, 100.0).agree     # 2e-8 > 1e-10 * 100


def test_non_finite_numbers_must_be_equal():
    assert compare(math.inf, math.inf, 0.0).agree
    assert not compare(math.inf, -math.inf, 0.0).agree
    assert not compare(1.0, math.nan, 0.0).agree


def test_errors_text_and_booleans_are_exact():
    assert compare(ExcelError.DIV0, ExcelError.DIV0, 0.0).agree
    assert not compare(ExcelError.DIV0, ExcelError.NA, 0.0).agree
    assert not compare(0.0, ExcelError.DIV0, 0.0).agree
    assert not compare(True, 1, 0.0).agree and not compare(1.0, True, 0.0).agree
    assert compare(False, False, 0.0).agree
    assert not compare("abc", "ABC", 0.0).agree    # stored text: case kept
    assert compare("", None, 0.0).agree and compare(None, "", 0.0).agree
    assert not compare("", 0.0, 0.0).agree
    assert compare(3, 3.0, 0.0) == Verdict(True, 0.0, 0.0)


def test_arrays_agree_with_the_scalar_rule():
    cached = np.array([0.3, 1.0, 0.0, 0.0, 1e300])
    recomputed = np.array([0.1 + 0.2, 1.0 + 1e-9, 3e-16, 3e-16, 1e300 * (1 + 1e-15)])
    scale = np.array([0.0, 0.0, 100.0, 0.0, 0.0])
    agree, diff, rel = compare_numbers(cached, recomputed, scale)
    assert agree.tolist() == [True, False, True, False, True]
    assert diff[1] == pytest.approx(1e-9, rel=1e-6)
    assert rel[2] == pytest.approx(3e-18)
    assert rel[3] == pytest.approx(1.0)  # 3e-16 against 3e-16
    _, _, rel0 = compare_numbers(np.zeros(1), np.zeros(1), np.zeros(1))
    assert rel0.tolist() == [0.0]


def test_column_statistics_count_and_keep_the_worst():
    stats = ColumnStats("Table", "B")
    stats.add("B2", Verdict(True, 1e-14, 1e-15))
    stats.add("B3", Verdict(False, 2.0, 0.5))
    stats.add("B4", Verdict(False, 3.0, math.inf))  # a finite value against 0: absolute
    assert (stats.cells, stats.mismatches) == (3, 2)
    assert (stats.worst_error, stats.worst_cell) == (3.0, "B4")
    stats.add_many(lambda i: f"B{5 + i}", np.array([True, False, True]),
                   np.array([0.0, 7.0, 1.0]))
    assert (stats.cells, stats.mismatches) == (6, 3)
    assert (stats.worst_error, stats.worst_cell) == (7.0, "B6")
    stats.add_many(lambda i: 1 / 0, np.array([], bool), np.array([]))  # named only if worst
    assert stats.cells == 6
