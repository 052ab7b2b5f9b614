"""formula/functions/regress.py: LINEST's coefficients and its statistics (stats=TRUE: the
standard errors, R^2, the F statistic, degrees of freedom, sums of squares) against
numpy's least squares and the textbook formulas; TREND on new x; LOGEST and GROWTH as
LINEST and TREND of ln(y), exponentiated (Microsoft's definitions)."""

from __future__ import annotations

import math
import random

import numpy as np
import pytest

from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula.arrays import evaluate_array
from workbook_gen.xlerror import ExcelError


def ev(text: str):
    value = evaluate_array(parse(text), DictResolver({}), "excel", None)
    return np.array([[math.nan if isinstance(x, ExcelError) else float(x) for x in row]
                     for row in value.rows])


def row(xs) -> str:
    return "{" + ",".join(repr(float(x)) for x in xs) + "}"


def columns(matrix) -> str:
    return "{" + ";".join(",".join(repr(float(x)) for x in r) for r in matrix) + "}"


def ols(y, X):
    """coefficients, their standard errors, r2, se_y, F, df, ss_reg, ss_resid (with a
    constant): the textbook formulas over numpy's least squares."""
    n, k = X.shape
    A = np.column_stack([X, np.ones(n)])
    beta, *_ = np.linalg.lstsq(A, y, rcond=None)
    resid = y - A @ beta
    df = n - k - 1
    ss_resid = float(resid @ resid)
    ss_reg = float(((A @ beta - y.mean()) ** 2).sum())
    sigma2 = ss_resid / df
    se = np.sqrt(np.diag(sigma2 * np.linalg.inv(A.T @ A)))
    r2 = ss_reg / (ss_reg + ss_resid)
    return beta, se, r2, math.sqrt(sigma2), (ss_reg / k) / sigma2, df, ss_reg, ss_resid


@pytest.mark.parametrize("seed", range(8))
def test_linest_with_statistics_as_least_squares(seed):
    rng = np.random.default_rng(seed)
    n, k = int(rng.integers(6, 20)), int(rng.integers(1, 4))
    X = rng.uniform(-5, 5, (n, k))
    y = X @ rng.uniform(-3, 3, k) + 2.5 + rng.normal(0, 0.7, n)
    got = ev(f"=LINEST({columns(y[:, None])},{columns(X)},TRUE,TRUE)")
    beta, se, r2, se_y, f, df, ss_reg, ss_resid = ols(y, X)
    # row 1: the coefficients right to left (x_k ... x_1), then the constant
    np.testing.assert_allclose(got[0], [*beta[:k][::-1], beta[k]], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(got[1], [*se[:k][::-1], se[k]], rtol=1e-9)
    np.testing.assert_allclose(got[2, :2], [r2, se_y], rtol=1e-9)
    np.testing.assert_allclose(got[3, :2], [f, df], rtol=1e-9)
    np.testing.assert_allclose(got[4, :2], [ss_reg, ss_resid], rtol=1e-9)
    assert np.isnan(got[2:, 2:]).all()                 # Excel fills the rest with #N/A


def test_trend_logest_growth():
    rng = random.Random(3)
    x = [float(i) for i in range(1, 13)]
    y = [3.0 * 1.2 ** xi * math.exp(rng.gauss(0, 0.05)) for xi in x]
    slope, intercept = np.polyfit(x, y, 1)
    new = [13.0, 14.5]
    np.testing.assert_allclose(ev(f"=TREND({row(y)},{row(x)},{row(new)})")[0],
                               [slope * v + intercept for v in new], rtol=1e-12)
    b, a = np.polyfit(x, np.log(y), 1)
    np.testing.assert_allclose(ev(f"=LOGEST({row(y)},{row(x)})")[0], [math.exp(b), math.exp(a)],
                               rtol=1e-12)
    np.testing.assert_allclose(ev(f"=GROWTH({row(y)},{row(x)},{row(new)})")[0],
                               [math.exp(a + b * v) for v in new], rtol=1e-12)


def test_microsofts_linest_example():
    # support.microsoft.com LINEST, example 1: slope 2, intercept 1 for y = {1,9,5,7}, x = {0,4,2,3}
    np.testing.assert_allclose(ev("=LINEST({1,9,5,7},{0,4,2,3})")[0], [2.0, 1.0], rtol=1e-12)
