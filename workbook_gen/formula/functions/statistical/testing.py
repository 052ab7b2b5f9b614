"""Descriptive statistics and hypothesis tests: GEOMEAN, HARMEAN, SKEW(.P), KURT, TRIMMEAN,
PERCENTRANK(.INC/.EXC), MODE.MULT, PROB, PERMUT, PERMUTATIONA, CHISQ.TEST, F.TEST, T.TEST,
Z.TEST (and their legacy names). Ranges keep their numbers only (Excel's rule for
statistical functions); the p-values come from :mod:`.distributions`."""

from __future__ import annotations

import math

import mpmath

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.numeric import DPS, args_of, choices
from workbook_gen.formula.functions.statistical.distributions import f_cdf, t_cdf
from workbook_gen.formula.functions.math.core import fsum
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.functions.statistical.core import mode_args
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError


def _nums(ctx, *args):
    return c.numbers(args, ctx)


def _array_nums(ctx, arg):
    """One array's numbers, or its first error (#NULL! passed over in Excel when another
    error follows: c.past_null)."""
    xs = _nums(ctx, arg)
    if xs is ExcelError.NULL and ctx.dialect == "excel" and isinstance(arg, Range):
        return c.past_null(xs, arg.flat())
    return xs


def _stat(name, fn, aliases=()):
    def scalar(ctx, *args):
        xs = _nums(ctx, *args)
        if isinstance(xs, ExcelError):
            return xs
        return c.result(fn(xs))
    register(name, 1, -1, "range", aliases=aliases)(scalar)


def _mean(xs):
    return fsum(xs) / len(xs)


def _geomean(xs):
    if not xs or min(xs) <= 0:
        return ExcelError.NUM
    return math.exp(fsum(math.log(x) for x in xs) / len(xs))


def _harmean(xs):
    if not xs or min(xs) <= 0:
        return ExcelError.NUM
    return len(xs) / fsum(1 / x for x in xs)


def _central(xs, k, ddof):
    n = len(xs)
    m = _mean(xs)
    s = math.sqrt(fsum((x - m) ** 2 for x in xs) / (n - ddof))
    if s == 0:
        return None
    return fsum(((x - m) / s) ** k for x in xs)


def _skew(xs):
    n = len(xs)
    if n < 3:
        return ExcelError.DIV0
    t = _central(xs, 3, 1)
    return ExcelError.DIV0 if t is None else n / ((n - 1) * (n - 2)) * t


def _skew_p(xs):
    if len(xs) < 1:
        return ExcelError.DIV0
    t = _central(xs, 3, 0)
    return ExcelError.DIV0 if t is None else t / len(xs)


def _kurt(xs):
    n = len(xs)
    if n < 4:
        return ExcelError.DIV0
    t = _central(xs, 4, 1)
    if t is None:
        return ExcelError.DIV0
    return (n * (n + 1) / ((n - 1) * (n - 2) * (n - 3)) * t
            - 3 * (n - 1) ** 2 / ((n - 2) * (n - 3)))


_stat("GEOMEAN", _geomean)
_stat("HARMEAN", _harmean)
_stat("SKEW", _skew)
_stat("SKEW.P", _skew_p)
_stat("KURT", _kurt)


@register("TRIMMEAN", 2, 2, ("range", "scalar"))
def _trimmean(ctx, data, percent):
    xs = _nums(ctx, data)
    p = c.to_number(percent)
    for v in (xs, p):
        if isinstance(v, ExcelError):
            return v
    if not 0 <= p < 1 or not xs:
        return ExcelError.NUM
    k = int(len(xs) * p / 2)
    xs = sorted(xs)[k:len(xs) - k]
    return c.result(_mean(xs))


def _percentrank(exclusive):
    def fn(ctx, data, x, significance=3.0):
        xs = _nums(ctx, data)
        args = args_of(x, 3.0 if significance is None else significance)
        for v in (xs, args):
            if isinstance(v, ExcelError):
                return v
        x, sig = args
        sig = math.trunc(sig)
        if sig < 1 or not xs:
            return ExcelError.NUM
        xs = sorted(xs)
        n = len(xs)
        if x < xs[0] or x > xs[-1]:
            return ExcelError.NA

        def rank(k):  # the fraction for the k-th smallest value (0-based)
            return (k + 1) / (n + 1) if exclusive else (k / (n - 1) if n > 1 else 1.0)
        below = sum(1 for t in xs if t < x)
        if x in xs:
            r = rank(below)
        else:  # between the last copy of the value below and the first of the one above
            lo, hi = xs[below - 1], xs[below]
            r = rank(below - 1) + (x - lo) / (hi - lo) * (rank(below) - rank(below - 1))
        scale = 10 ** sig
        return c.result(math.floor(r * scale + 1e-9) / scale)
    return fn


register("PERCENTRANK.INC", 2, 3, ("range", "scalar"),
         aliases=("PERCENTRANK",))(_percentrank(False))
register("PERCENTRANK.EXC", 2, 3, ("range", "scalar"))(_percentrank(True))


@register("MODE.MULT", 1, -1, "range", omitted=True)
def _mode_mult(ctx, *args):
    args = mode_args(ctx, args)
    if isinstance(args, ExcelError):
        return args
    xs = _nums(ctx, *args)
    if isinstance(xs, ExcelError):
        return xs
    counts: dict[float, int] = {}
    for x in xs:
        counts[x] = counts.get(x, 0) + 1
    top = max(counts.values(), default=0)
    if top < 2:
        return ExcelError.NA
    return Range.array_of([[x] for x, k in counts.items() if k == top])


register("PERMUT", 2, 2)(choices(math.perm))


@register("PERMUTATIONA", 2, 2)
def _permutationa(ctx, n, k):
    xs = args_of(n, k)
    if isinstance(xs, ExcelError):
        return xs
    n, k = (math.trunc(v) for v in xs)
    return ExcelError.NUM if n < 0 or k < 0 else c.result(float(n) ** k)


_ABSENT = object()  # an argument not given (an empty cell given is 0)


@register("PROB", 3, 4, ("range", "range", "scalar"))
def _prob(ctx, xr, pr, lower, upper=_ABSENT):
    a, b = c.flat(c.as_area(xr)), c.flat(c.as_area(pr))
    if len(a) != len(b):
        return ExcelError.NA
    # upper_limit left out: the probability of lower_limit; an empty cell is 0 in Excel
    # (Mac Excel's STATISTICAL!Z86: PROB({1,2,3,4,5},{...},1,<empty>) = 0), left out in
    # LibreOffice (7.4, measured)
    if upper is _ABSENT or (upper is None and ctx is not None and ctx.dialect == "libreoffice"):
        upper = lower
    bounds = args_of(lower, upper)
    if isinstance(bounds, ExcelError):
        return bounds
    lo, hi = bounds
    pairs = []
    for x, p in zip(a, b):
        for v in (x, p):
            if isinstance(v, ExcelError):
                return v
        if c.is_number(x) and c.is_number(p):
            pairs.append((x, p))
    if any(not 0 <= p <= 1 for _, p in pairs) or abs(fsum(p for _, p in pairs) - 1) > 1e-7:
        return ExcelError.NUM
    return c.result(fsum(p for x, p in pairs if lo <= x <= hi))


# -- tests ---------------------------------------------------------------------------------

def _area_numbers(v):
    """The cells of an area, errors first: (values, error)."""
    vals = c.flat(c.as_area(v))
    return vals, c.first_error(vals)


def _var(xs):
    m = _mean(xs)
    return fsum((x - m) ** 2 for x in xs) / (len(xs) - 1)


@register("CHISQ.TEST", 2, 2, "range", aliases=("CHITEST",))
def _chisq_test(ctx, actual, expected):
    """Excel pairs areas of one size whatever their shapes, the degrees of freedom from
    the actual values' shape (Mac Excel 16, formulas__test.xlsx STATISTICAL!R17: a 2x2
    against a 4x1 is 9.66041305483331E-58, one degree); sizes that differ are #N/A.
    LibreOffice 7.4 (measured): any other shape is #VALUE!."""
    a, b = c.as_area(actual), c.as_area(expected)
    size = (a.shape[0] * a.shape[1], b.shape[0] * b.shape[1])
    if a.shape != b.shape and (ctx.dialect == "libreoffice" or size[0] != size[1]):
        return ExcelError.VALUE if ctx.dialect == "libreoffice" else ExcelError.NA
    rows, cols = a.shape
    if ctx.dialect == "excel":  # the actual values' errors first, then the expected ones'
        for area in (a, b):    # (Mac Excel 16, formulas__test.xlsx STATISTICAL!Y17, AD17)
            error = c.first_error(area.flat())
            if error is not None:
                return c.past_null(error, area.flat())
    stat, pairs = 0.0, 0
    for x, e in zip(a.flat(), b.flat()):
        for v in (x, e):
            if isinstance(v, ExcelError):
                return v
        if c.is_number(x) and c.is_number(e):
            if e == 0:
                return ExcelError.DIV0
            stat += (x - e) ** 2 / e
            pairs += 1
    if not pairs and ctx.dialect == "excel":  # no number against a number (V17)
        return ExcelError.DIV0
    df = (rows - 1) * (cols - 1) if rows > 1 and cols > 1 else max(rows, cols) - 1
    if df < 1:
        return ExcelError.NA
    with mpmath.workdps(DPS):
        return c.result(float(mpmath.gammainc(df / 2, stat / 2, mpmath.inf, regularized=True)))


@register("F.TEST", 2, 2, "range", aliases=("FTEST",))
def _f_test(ctx, a1, a2):
    xs, ys = _array_nums(ctx, a1), _array_nums(ctx, a2)
    for v in (xs, ys):
        if isinstance(v, ExcelError):
            return v
    if len(xs) < 2 or len(ys) < 2:
        return ExcelError.DIV0
    v1, v2 = _var(xs), _var(ys)
    if v1 == 0 or v2 == 0:
        return ExcelError.DIV0
    with mpmath.workdps(DPS):
        p = f_cdf(v1 / v2, len(xs) - 1, len(ys) - 1)
        return c.result(float(2 * min(p, 1 - p)))


@register("T.TEST", 4, 4, ("range", "range", "scalar"), aliases=("TTEST",))
def _t_test(ctx, a1, a2, tails, kind):
    opts = args_of(tails, kind)
    if isinstance(opts, ExcelError):
        return opts
    tails, kind = (math.trunc(v) for v in opts)
    if tails not in (1, 2) or kind not in (1, 2, 3):
        return ExcelError.NUM
    if kind == 1:
        a, b = c.flat(c.as_area(a1)), c.flat(c.as_area(a2))
        if len(a) != len(b):
            return ExcelError.NA
        err = (c.first_pair_error(a, b) if ctx.dialect == "excel"  # as the fits (Y107)
               else c.first_error(a + b))
        if err is not None:
            return err
        d = [x - y for x, y in zip(a, b) if c.is_number(x) and c.is_number(y)]
        if len(d) < 2:
            return ExcelError.DIV0
        sd = math.sqrt(_var(d))
        if sd == 0:
            return ExcelError.DIV0
        t, df = _mean(d) / (sd / math.sqrt(len(d))), len(d) - 1
    else:
        xs, ys = _array_nums(ctx, a1), _array_nums(ctx, a2)
        for v in (xs, ys):
            if isinstance(v, ExcelError):
                return v
        n1, n2 = len(xs), len(ys)
        if n1 < 2 or n2 < 2:
            return ExcelError.DIV0
        v1, v2 = _var(xs), _var(ys)
        diff = _mean(xs) - _mean(ys)
        if kind == 2:
            df = n1 + n2 - 2
            pooled = ((n1 - 1) * v1 + (n2 - 1) * v2) / df
            se = math.sqrt(pooled * (1 / n1 + 1 / n2))
        else:
            se = math.sqrt(v1 / n1 + v2 / n2)
            if se == 0:
                return ExcelError.DIV0
            df = (v1 / n1 + v2 / n2) ** 2 / ((v1 / n1) ** 2 / (n1 - 1) + (v2 / n2) ** 2 / (n2 - 1))
        if se == 0:
            return ExcelError.DIV0
        t = diff / se
    with mpmath.workdps(DPS):
        return c.result(float(tails * (1 - t_cdf(abs(t), df))))


@register("Z.TEST", 2, 3, ("range", "scalar"), aliases=("ZTEST",))
def _z_test(ctx, data, x, sigma=None):
    """x's error, then sigma's, come before an error in the array; fewer than two numbers
    are #DIV/0! even with sigma given; a given sigma of 0 is #NUM! (Mac Excel 16,
    formulas__test.xlsx STATISTICAL!U121:AE121; LibreOffice 7.4 measured the same, but
    #VALUE! for sigma 0)."""
    args = args_of(x) if sigma is None else args_of(x, sigma)
    if isinstance(args, ExcelError):
        return args
    xs = _nums(ctx, data)
    if isinstance(xs, ExcelError):
        return xs
    if not xs:
        return ExcelError.NA
    if len(xs) < 2:
        return ExcelError.DIV0
    s = math.sqrt(_var(xs)) if sigma is None else args[1]
    if sigma is not None and s <= 0:
        return ExcelError.VALUE if s == 0 and ctx.dialect == "libreoffice" else ExcelError.NUM
    if s == 0:
        return ExcelError.DIV0
    z = (_mean(xs) - args[0]) / (s / math.sqrt(len(xs)))
    with mpmath.workdps(DPS):
        return c.result(float(1 - mpmath.ncdf(z)))
