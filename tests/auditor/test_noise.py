"""auditor/noise.py: the rounding noise of a Table column, a first-order running error
bound. Checked two ways: against the propagation rules worked by hand for each column's
formula (m(a*b) = |b| m(a) + |a| m(b), m(f(a)) = |f'(a)| m(a) + |f(a)|, a number's m its
size), and as a bound: the float64 value's error against mpmath at 50 digits stays below
eps * m."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import xlsxwriter

from workbook_gen.auditor.noise import INPUT, ColumnNoise, column_tree, column_trees, \
    numbers_or_nan
from workbook_gen.xlsx import read_workbook

ROWS = range(2, 5)
THETA = [0.3, 1.7, 2.9]
K = 3.0
EPS = np.finfo(float).eps


@pytest.fixture(scope="module")
def table(tmp_path_factory):
    path = tmp_path_factory.mktemp("noise") / "noise.xlsx"
    book = xlsxwriter.Workbook(str(path))
    s = book.add_worksheet("Table")
    s.write_row(0, 0, list("ABCDEFGHI"))
    for i, (r, a) in enumerate(zip(ROWS, THETA)):
        s.write_number(r - 1, 0, a)
        s.write_formula(r - 1, 1, f"=A{r}*2", None, a * 2)
        s.write_formula(r - 1, 2, f"=SIN(A{r})", None, math.sin(a))
        s.write_formula(r - 1, 3, f"=B{r}-A{r}*2", None, 0)
        s.write_formula(r - 1, 4, f"=A{r}/$A$2", None, a / THETA[0])
        s.write_formula(r - 1, 5, f"=A{r}+1" if i != 1 else f"=A{r}*2", None, 0)
        s.write_formula(r - 1, 6, f"=C{r}^2", None, math.sin(a) ** 2)
        s.write_formula(r - 1, 7, f"=k*A{r}", None, K * a)
        s.write_formula(r - 1, 8, f"=IF(A{r}>1,A{r},B{r})", None, a if a > 1 else 2 * a)
    book.define_name("k", f"={K}")
    book.close()
    sheet = read_workbook(path).sheet("Table")
    values = {c: [sheet.cell(r, c).value for r in ROWS] for c in range(1, 10)}
    return sheet, values


def _noise(table, trees=None):
    sheet, values = table
    return ColumnNoise(sheet, ROWS, values.__getitem__,
                       lambda name: K if name.lower() == "k" else None, trees)


def test_numbers_or_nan_keeps_numbers_only():
    got = numbers_or_nan([1, 2.5, True, "x", None, np.float64(3.0)])
    assert np.array_equal(got, [1.0, 2.5, np.nan, np.nan, np.nan, 3.0], equal_nan=True)


def test_the_propagation_rules_by_hand(table):
    noise = _noise(table)
    a = np.abs(THETA)
    s, c = np.sin(THETA), np.cos(THETA)
    assert np.allclose(noise.of(1), a)                       # an input: exact as given
    assert np.allclose(noise.of(2), 2 * a + a * 2)           # a*2: |2| m(a) + |a| 2
    assert np.allclose(noise.of(3), np.abs(c) * a + np.abs(s))
    assert np.allclose(noise.of(4), 4 * a + 4 * a)           # B - A*2
    m_c = np.abs(c) * a + np.abs(s)
    assert np.allclose(noise.of(7), np.abs(2 * s) * m_c + s * s)  # ^2: a literal exponent
    assert np.allclose(noise.of(8), a * K + K * a)           # name k times A
    assert np.allclose(noise.of(9), np.where(np.array(THETA) > 1, a, 4 * a))
    assert noise.of(5) is None       # $A$2: not a same-row reference
    assert noise.of(6) is None       # two different formulas down the column


def test_the_noise_bounds_the_float64_error(table):
    """|float64 - exact| <= eps * m for the columns a float64 computation gives."""
    noise = _noise(table)
    with mpmath.workdps(50):
        for i, a in enumerate(THETA):
            x = mpmath.mpf(a)
            exact = {3: mpmath.sin(x), 4: 2 * x - x * 2, 7: mpmath.sin(x) ** 2, 8: K * x}
            computed = {3: math.sin(a), 4: a * 2 - a * 2, 7: math.sin(a) ** 2, 8: K * a}
            for col, value in exact.items():
                error = abs(float(mpmath.mpf(computed[col]) - value))
                assert error <= EPS * noise.of(col)[i], (col, a)


def test_column_trees_ahead_and_inputs(table):
    sheet, _ = table
    assert column_tree(sheet, ROWS, 1) == INPUT
    trees = column_trees(sheet, ROWS)
    assert set(trees) == set(range(1, 10))
    assert trees[1] == INPUT and trees[6] is None and trees[2] is not None
    ahead = _noise(table, trees)
    assert np.allclose(ahead.of(2), _noise(table).of(2))
    assert ahead.of(6) is None
    assert _noise(table, {2: None}).of(2) is None   # computed ahead: none
