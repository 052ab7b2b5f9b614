"""Least-squares fits returning arrays: LINEST, TREND, LOGEST, GROWTH.

Shapes as Excel reads them: known_y's in one column makes each column of known_x's a
variable, in one row each row; known_y's of another shape needs known_x's of the same
shape (one variable). Sizes that do not fit are #REF!; a non-number is #VALUE!. An x
variable that adds nothing to those before it (a constant column, a copy) is dropped and
gets the coefficient 0, as Excel's LINEST does (pycel stats.xlsx: LINEST of y against a
constant x is {0, mean(y)}). The exponential forms fit ln(y) (y <= 0 is #NUM!)."""

from __future__ import annotations

import math

import numpy as np

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.math.matrix import matrix
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError


def _flag(v, default=True):
    if v is None:
        return default
    return c.to_bool(c.scalar_of(v))


def _error(v: ExcelError, dialect: str) -> ExcelError:
    """An error among the values or the flags: #VALUE! in Excel, whichever it is (Mac
    Excel 16, formulas__test.xlsx STATISTICAL!Z58, AB58, AA51: LINEST, LOGEST, TREND and
    GROWTH); itself in LibreOffice."""
    return ExcelError.VALUE if dialect == "excel" else v


def _data(known_y, known_x, dialect: str = "excel"):
    """(y vector n, X n x k, layout, y's shape) with layout 'col', 'row' or 'one', or an
    error (sizes are checked before the values, as Excel does: #REF! before #VALUE!)."""
    ya = c.as_area(known_y)
    rows, cols = ya.shape
    if known_x is None:
        y = matrix(ya)
        if isinstance(y, ExcelError):
            return _error(y, dialect)
        return y.ravel(), np.arange(1, y.size + 1, dtype=float).reshape(-1, 1), "one", y.shape
    xa = c.as_area(known_x)
    if cols == 1 and xa.shape[0] == rows:
        layout = "col"
    elif rows == 1 and xa.shape[1] == cols:
        layout = "row"
    elif xa.shape == ya.shape:
        layout = "one"
    else:
        return ExcelError.REF
    y, x = matrix(ya), matrix(xa)
    for v in (y, x):
        if isinstance(v, ExcelError):
            return _error(v, dialect)
    if layout == "col":
        return y[:, 0], x, layout, y.shape
    if layout == "row":
        return y[0], x.T, layout, y.shape
    return y.ravel(), x.ravel().reshape(-1, 1), layout, y.shape


def fit(y, x, const):
    """Coefficients (k,), intercept and the kept columns, dropping collinear x columns."""
    n, k = x.shape
    xm = x.mean(axis=0) if const else np.zeros(k)
    ym = y.mean() if const else 0.0
    xc, yc = x - xm, y - ym
    kept, basis = [], []
    for j in range(k):
        v = xc[:, j].copy()
        norm0 = np.linalg.norm(v)
        for q in basis:
            v -= (q @ v) * q
        if norm0 > 0 and np.linalg.norm(v) > 1e-12 * norm0 and len(kept) < n - (1 if const else 0):
            kept.append(j)
            basis.append(v / np.linalg.norm(v))
    coef = np.zeros(k)
    if kept:
        sol, *_ = np.linalg.lstsq(xc[:, kept], yc, rcond=None)
        coef[kept] = sol
    b = ym - float(coef @ xm) if const else 0.0
    return coef, b, kept


def _stats(y, x, coef, b, kept, const):
    n = len(y)
    fitted = x @ coef + b
    resid = y - fitted
    ss_resid = float(resid @ resid)
    ss_total = float(((y - y.mean()) ** 2).sum()) if const else float(y @ y)
    if ss_resid <= 1e-20 * ss_total:  # an exact fit: rounding noise is no residual
        ss_resid = 0.0
    ss_reg = ss_total - ss_resid
    k = x.shape[1]
    # Microsoft: each x column removed for collinearity adds 1 to df; a constant column
    # (collinear with the intercept only) does not: Excel gives df 0 for 3 points and
    # two constant columns (pycel stats.xlsx LinestArrayExp!F21:H25)
    moving = [j for j in range(k) if np.ptp(x[:, j]) > 0 or not const]
    df = n - k - (1 if const else 0) + sum(1 for j in moving if j not in kept)
    if df == 0:  # as many parameters as points: Excel reports an exact fit
        ss_resid, ss_reg = 0.0, ss_total
        return ([0.0] * k, 0.0 if const else ExcelError.NA, 1.0 if ss_total else ExcelError.NUM,
                0.0, ExcelError.NUM, 0.0, ss_reg, ss_resid)
    se = [0.0] * k
    se_b = ExcelError.NA
    if df > 0 and kept:
        s2 = ss_resid / df
        xs = x[:, kept]
        if const:
            xs = np.column_stack([xs, np.ones(n)])
        cov = s2 * np.linalg.pinv(xs.T @ xs)
        for i, j in enumerate(kept):
            se[j] = math.sqrt(max(cov[i, i], 0.0))
        if const:
            se_b = math.sqrt(max(cov[-1, -1], 0.0))
    elif const and df > 0:
        se_b = math.sqrt(ss_resid / df / n)
    r2 = ss_reg / ss_total if ss_total else ExcelError.NUM
    sey = math.sqrt(ss_resid / df) if df > 0 else ExcelError.NUM
    f = ((ss_reg / len(kept)) / (ss_resid / df) if df > 0 and kept and ss_resid
         else ExcelError.NUM)
    return se, se_b, r2, sey, f, float(df), ss_reg, ss_resid


def _linest(known_y, known_x, const, stats, log, dialect):
    got = _data(known_y, known_x, dialect)
    if isinstance(got, ExcelError):
        return got
    y, x, _, _ = got
    const, stats = _flag(const), _flag(stats, False)
    for v in (const, stats):
        if isinstance(v, ExcelError):
            return _error(v, dialect)
    if log:
        if np.any(y <= 0):
            return ExcelError.NUM
        y = np.log(y)
    coef, b, kept = fit(y, x, const)
    top = [float(v) for v in coef[::-1]] + [b]
    if log:
        top = [math.exp(v) for v in top]
    if not stats:
        return Range.array_of([top])
    se, se_b, r2, sey, f, df, ss_reg, ss_resid = _stats(y, x, coef, b, kept, const)
    width = len(top)
    na = ExcelError.NA

    def row(*vals):
        return list(vals) + [na] * (width - len(vals))
    return Range.array_of([top, [*se[::-1], se_b], row(r2, sey), row(f, df),
                           row(ss_reg, ss_resid)])


def _trend(known_y, known_x, new_x, const, log, dialect):
    got = _data(known_y, known_x, dialect)
    if isinstance(got, ExcelError):
        return got
    y, x, layout, yshape = got
    const = _flag(const)
    if isinstance(const, ExcelError):
        return _error(const, dialect)
    if log:
        if np.any(y <= 0):
            return ExcelError.NUM
        y = np.log(y)
    k = x.shape[1]
    if new_x is None:
        points, shape = x, (yshape if layout != "row" else (1, len(y)))
        if layout == "one":
            shape = yshape
    else:
        nx = matrix(new_x)
        if isinstance(nx, ExcelError):
            return _error(nx, dialect)
        if k == 1:
            points, shape = nx.reshape(-1, 1), nx.shape
        elif layout == "col" and nx.shape[1] == k:
            points, shape = nx, (nx.shape[0], 1)
        elif layout == "row" and nx.shape[0] == k:
            points, shape = nx.T, (1, nx.shape[1])
        else:
            return ExcelError.REF
    coef, b, _ = fit(y, x, const)
    out = points @ coef + b
    if log:
        out = np.exp(out)
    return Range.array_of([[c.result(float(v)) for v in row] for row in out.reshape(shape)])


@register("LINEST", 1, 4, ("range", "range", "scalar", "scalar"), omitted=True)
def _linest_fn(ctx, known_y, known_x=None, const=None, stats=None):
    return _linest(known_y, known_x, const, stats, False, ctx.dialect)


@register("LOGEST", 1, 4, ("range", "range", "scalar", "scalar"), omitted=True)
def _logest_fn(ctx, known_y, known_x=None, const=None, stats=None):
    return _linest(known_y, known_x, const, stats, True, ctx.dialect)


@register("TREND", 1, 4, ("range", "range", "range", "scalar"), omitted=True)
def _trend_fn(ctx, known_y, known_x=None, new_x=None, const=None):
    return _trend(known_y, known_x, new_x, const, False, ctx.dialect)


@register("GROWTH", 1, 4, ("range", "range", "range", "scalar"), omitted=True)
def _growth_fn(ctx, known_y, known_x=None, new_x=None, const=None):
    return _trend(known_y, known_x, new_x, const, True, ctx.dialect)
