"""More statistics: regression (SLOPE, INTERCEPT, FORECAST, RSQ, CORREL, COVARIANCE, STEYX),
spread (DEVSQ, AVEDEV, VARA, STDEVA), quantiles (PERCENTILE, QUARTILE), FREQUENCY, the
normal distribution (SUBTOTAL and AGGREGATE: :mod:`..math.subtotal`)."""

from __future__ import annotations

import math
from statistics import NormalDist

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.math.core import fsum
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError


def _pairs(ys, xs, dialect: str = "excel"):
    """Paired numbers of two equal-sized areas (pairs with a non-number skipped); an
    argument that is an error (an undefined name: #NAME?) is that error; else the first
    error pair by pair (c.first_pair_error)."""
    for arg in (ys, xs):
        if isinstance(arg, ExcelError):
            return arg
    a, b = c.flat(c.as_area(ys)), c.flat(c.as_area(xs))
    if len(a) != len(b):
        return ExcelError.NA
    error = c.first_pair_error(a, b, dialect)
    if error is not None:
        return error
    return [(float(y), float(x)) for y, x in zip(a, b) if c.is_number(y) and c.is_number(x)]


def _moments(pairs):
    n = len(pairs)
    my = fsum([y for y, _ in pairs]) / n
    mx = fsum([x for _, x in pairs]) / n
    sxy = fsum([(x - mx) * (y - my) for y, x in pairs])
    sxx = fsum([(x - mx) ** 2 for _, x in pairs])
    syy = fsum([(y - my) ** 2 for y, _ in pairs])
    return n, my, mx, sxy, sxx, syy


def _fit(kind):
    def fn(ctx, ys, xs):
        pairs = _pairs(ys, xs, ctx.dialect)
        if isinstance(pairs, ExcelError):
            return pairs
        if len(pairs) < (3 if kind == "steyx" else 1):
            return ExcelError.DIV0
        n, my, mx, sxy, sxx, syy = _moments(pairs)
        if kind == "cov_p":
            return c.result(sxy / n)
        if kind == "cov_s":
            return ExcelError.DIV0 if n < 2 else c.result(sxy / (n - 1))
        if sxx == 0:
            return ExcelError.DIV0
        if kind == "slope":
            return c.result(sxy / sxx)
        if kind == "intercept":
            return c.result(my - sxy / sxx * mx)
        if syy == 0:
            return ExcelError.DIV0
        if kind == "correl":
            return c.result(sxy / math.sqrt(sxx * syy))
        if kind == "rsq":
            return c.result(sxy * sxy / (sxx * syy))
        return c.result(math.sqrt((syy - sxy * sxy / sxx) / (n - 2)))
    return fn


for _names, _kind in ((("SLOPE",), "slope"), (("INTERCEPT",), "intercept"),
                      (("CORREL", "PEARSON"), "correl"), (("RSQ",), "rsq"),
                      (("STEYX",), "steyx"), (("COVAR", "COVARIANCE.P"), "cov_p"),
                      (("COVARIANCE.S",), "cov_s")):
    register(_names[0], 2, 2, "range", aliases=_names[1:])(_fit(_kind))


@register("FORECAST", 3, 3, ("scalar", "range", "range"), aliases=("FORECAST.LINEAR",))
def _forecast(ctx, x, ys, xs):
    x = c.to_number(x)
    if isinstance(x, ExcelError):
        return x
    pairs = _pairs(ys, xs, ctx.dialect)
    if isinstance(pairs, ExcelError):
        return pairs
    if not pairs:
        return ExcelError.DIV0
    n, my, mx, sxy, sxx, _ = _moments(pairs)
    return ExcelError.DIV0 if sxx == 0 else c.result(my + sxy / sxx * (x - mx))


def _numbers_stat(name, fn, empty=ExcelError.DIV0):
    def scalar(ctx, *args):
        xs = c.numbers(args, ctx)
        if isinstance(xs, ExcelError):
            return xs
        return c.result(fn(xs)) if xs else empty
    register(name, 1, -1, "range")(scalar)


def _devsq(xs):
    m = fsum(xs) / len(xs)
    return fsum([(x - m) ** 2 for x in xs])


_numbers_stat("DEVSQ", _devsq, ExcelError.NUM)
_numbers_stat("AVEDEV", lambda xs: fsum([abs(x - fsum(xs) / len(xs)) for x in xs]) / len(xs),
              ExcelError.NUM)


def _var_a(name, sample, root):
    def scalar(ctx, *args):
        xs = c.values_a(args)
        if isinstance(xs, ExcelError):
            return xs
        if len(xs) - sample <= 0:
            return ExcelError.DIV0
        v = _devsq(xs) / (len(xs) - sample)
        return c.result(math.sqrt(v) if root else v)
    register(name, 1, -1, "range")(scalar)


_var_a("VARA", True, False)
_var_a("VARPA", False, False)
_var_a("STDEVA", True, True)
_var_a("STDEVPA", False, True)


def percentile(xs: list[float], p: float, exclusive: bool):
    xs = sorted(xs)
    n = len(xs)
    if exclusive:
        rank = p * (n + 1)
        if rank < 1 or rank > n:
            return ExcelError.NUM
        rank -= 1
    else:
        if not 0 <= p <= 1:
            return ExcelError.NUM
        rank = p * (n - 1)
    lo = int(math.floor(rank))
    if lo + 1 >= n:
        return xs[-1]
    return xs[lo] + (rank - lo) * (xs[lo + 1] - xs[lo])


def _quantile(name, exclusive, quart):
    def scalar(ctx, area, k):
        p = c.to_number(k)
        xs = c.numbers([c.as_area(area)], ctx)
        for v in (p, xs):  # the k argument's error first (formulas' test.xlsx)
            if isinstance(v, ExcelError):
                return v
        if not xs:
            return ExcelError.NUM
        if quart:
            q = math.floor(p)  # -0.1 is quart -1, #NUM! (formulas__test COMPATIBILITY!U32)
            if not (1 if exclusive else 0) <= q <= (3 if exclusive else 4):
                return ExcelError.NUM
            p = q / 4
        return c.result(percentile(xs, p, exclusive))
    register(name, 2, 2, ("range", "scalar"))(scalar)


for _name, _exc, _q in (("PERCENTILE", False, False), ("PERCENTILE.INC", False, False),
                        ("PERCENTILE.EXC", True, False), ("QUARTILE", False, True),
                        ("QUARTILE.INC", False, True), ("QUARTILE.EXC", True, True)):
    _quantile(_name, _exc, _q)


# -- the normal distribution --------------------------------------------------------------

def _norm_args(*vs):
    xs = [c.to_number(v) for v in vs]
    bad = next((x for x in xs if isinstance(x, ExcelError)), None)
    return bad if bad is not None else xs


@register("NORM.DIST", 4, 4, aliases=("NORMDIST",))
def _norm_dist(ctx, x, mean, sd, cumulative):
    xs = _norm_args(x, mean, sd)
    cum = c.to_bool(cumulative)
    for v in (xs, cum):
        if isinstance(v, ExcelError):
            return v
    x, m, s = xs
    if s <= 0:
        return ExcelError.NUM
    d = NormalDist(m, s)
    return c.result(d.cdf(x) if cum else d.pdf(x))


@register("NORM.S.DIST", 1, 2)
def _norm_s_dist(ctx, z, cumulative=True):
    return _norm_dist(ctx, z, 0.0, 1.0, cumulative)


register("NORMSDIST", 1, 1)(lambda ctx, z: _norm_dist(ctx, z, 0.0, 1.0, True))


@register("NORM.INV", 3, 3, aliases=("NORMINV",))
def _norm_inv(ctx, p, mean, sd):
    xs = _norm_args(p, mean, sd)
    if isinstance(xs, ExcelError):
        return xs
    p, m, s = xs
    if not 0 < p < 1 or s <= 0:
        return ExcelError.NUM
    return c.result(NormalDist(m, s).inv_cdf(p))


register("NORM.S.INV", 1, 1, aliases=("NORMSINV",))(
    lambda ctx, p: _norm_inv(ctx, p, 0.0, 1.0))


@register("STANDARDIZE", 3, 3)
def _standardize(ctx, x, mean, sd):
    xs = _norm_args(x, mean, sd)
    if isinstance(xs, ExcelError):
        return xs
    return ExcelError.NUM if xs[2] <= 0 else c.result((xs[0] - xs[1]) / xs[2])


@register("FREQUENCY", 2, 2, "range")
def _frequency(ctx, data, bins):
    xs, bs = c.numbers([c.as_area(data)], ctx), c.numbers([c.as_area(bins)], ctx)
    for v in (xs, bs):
        if isinstance(v, ExcelError):
            return v
    if not bs and any(v is None for v in c.flat(c.as_area(bins))):
        # bins of empty cells only: one bin at 0 in Excel (Mac Excel 16, formulas__test.xlsx
        # STATISTICAL!W43, EXTRA!J50); #VALUE! in LibreOffice 7.4 (measured)
        if ctx.dialect == "libreoffice":
            return ExcelError.VALUE
        bs = [0.0]
    if not bs:
        return Range.array_of([[float(len(xs))]])
    order = sorted(range(len(bs)), key=lambda i: bs[i])
    counts = [0.0] * (len(bs) + 1)
    for x in xs:
        for i in order:
            if x <= bs[i]:
                counts[i] += 1
                break
        else:
            counts[-1] += 1
    return Range.array_of([[k] for k in counts])
