"""Statistics: MIN, MAX, AVERAGE(A), COUNT(A/BLANK), AVERAGEIF(S), COUNTIF(S), MAXIFS,
MINIFS (criteria in :mod:`..criteria`), MEDIAN, MODE, STDEV/VAR (sample and population),
LARGE, SMALL, RANK."""

from __future__ import annotations

import math
import statistics

import numpy as np

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.criteria import ifs, ifs_pairs, matches, picked
from workbook_gen.formula.functions.math.core import fsum
from workbook_gen.formula.functions.registry import ARRAY_LIFTED, register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError
from workbook_gen.xlmath import kernels as k


def _minmax_vector(reduce):
    def vector(xs, n):
        err = k.first_error(*(e for _, e in xs))
        val = reduce.reduce(np.array([v for v, _ in xs]), axis=0)
        return (*k.finish(val, err), False)
    return vector


def _agg(name, fn, empty=0.0, vector=None):
    numeric = vector is not None
    def scalar(ctx, *args):
        xs = c.numbers(args, ctx)
        if isinstance(xs, ExcelError):
            return xs
        return c.result(fn(xs)) if xs else empty
    register(name, 1, -1, "range", vector=vector, range_numbers=numeric)(scalar)


_agg("MIN", min, vector=_minmax_vector(np.minimum))
_agg("MAX", max, vector=_minmax_vector(np.maximum))
_agg("AVERAGE", lambda xs: fsum(xs) / len(xs), ExcelError.DIV0)
_agg("MEDIAN", statistics.median, ExcelError.NUM)


def _variance(xs, sample: bool):
    n = len(xs)
    if n - sample <= 0:
        return ExcelError.DIV0
    mean = fsum(xs) / n
    return fsum([(x - mean) ** 2 for x in xs]) / (n - sample)


def _sqrt(v):
    return v if isinstance(v, ExcelError) else math.sqrt(v)


for _names, _fn in ((("STDEV", "STDEV.S"), lambda xs: _sqrt(_variance(xs, True))),
                    (("STDEVP", "STDEV.P"), lambda xs: _sqrt(_variance(xs, False))),
                    (("VAR", "VAR.S"), lambda xs: _variance(xs, True)),
                    (("VARP", "VAR.P"), lambda xs: _variance(xs, False))):
    for _name in _names:
        _agg(_name, _fn, ExcelError.DIV0)


@register("MODE", 1, -1, "range")
def _mode(ctx, *args):
    if ctx is None or ctx.dialect != "libreoffice":
        # Excel's legacy MODE: a direct argument or a one-cell reference must be a number
        # (text, a boolean, an empty cell: #VALUE!, in argument order); ranges keep their
        # numbers. POI FormulaEvalTestData.xlsx row 936: MODE(B8,"1",2,3), MODE(B9,2,D7)
        # with D7 empty and MODE("1",1,#DIV/0!,2,3) are #VALUE!. MODE.SNGL ignores them
        # (formulas test.xlsx STATISTICAL!X71: MODE.SNGL(I71,G71) over a text is #N/A)
        for a in args:
            v = a.rows[0][0] if isinstance(a, Range) and a.shape == (1, 1) else a
            if isinstance(v, Range):
                bad = next((x for x in v.flat() if isinstance(x, ExcelError)), None)
            else:
                bad = None if c.is_number(v) else v if isinstance(v, ExcelError) else ExcelError.VALUE
            if bad is not None:
                return bad
    return _mode_sngl(ctx, *args)


def mode_args(ctx, args):
    """MODE.SNGL's and MODE.MULT's arguments in Excel: a direct "" is left out, an omitted
    argument is #VALUE! (Mac Excel 16, formulas__test.xlsx STATISTICAL!S71, S69, AG69);
    in LibreOffice an omitted argument is 0."""
    if ctx is not None and ctx.dialect == "excel":
        if any(a is None for a in args):
            return ExcelError.VALUE
        return [a for a in args if not (isinstance(a, str) and a == "")]
    return [0.0 if a is None else a for a in args]


@register("MODE.SNGL", 1, -1, "range", omitted=True)
def _mode_sngl(ctx, *args):
    args = mode_args(ctx, args)
    if isinstance(args, ExcelError):
        return args
    xs = c.numbers(args, ctx)
    if isinstance(xs, ExcelError):
        return xs
    counts: dict[float, int] = {}
    for x in xs:
        counts[x] = counts.get(x, 0) + 1
    best = max(counts.values(), default=0)
    if best < 2:
        return ExcelError.NA
    return next(x for x in xs if counts[x] == best)


def _agg_a(name, fn, empty):
    def scalar(ctx, *args):
        xs = c.values_a(args)
        if isinstance(xs, ExcelError):
            return xs
        return c.result(fn(xs)) if xs else empty
    register(name, 1, -1, "range")(scalar)


_agg_a("AVERAGEA", lambda xs: fsum(xs) / len(xs), ExcelError.DIV0)
_agg_a("MINA", min, 0.0)
_agg_a("MAXA", max, 0.0)


@register("COUNT", 1, -1, "range")
def _count(ctx, *args):
    lo = ctx.dialect == "libreoffice"
    n = 0
    for a in args:
        if isinstance(a, Range):
            n += sum(1 for v in a.flat() if c.is_number(v) or (lo and isinstance(v, bool)))
        elif not isinstance(a, ExcelError) and not isinstance(c.to_number(a), ExcelError):
            n += 1
    return float(n)


@register("COUNTA", 1, -1, "range")
def _counta(ctx, *args):
    n = 0
    for a in args:
        n += sum(1 for v in c.flat(a) if v is not None) if isinstance(a, Range) else 1
    return float(n)


@register("COUNTBLANK", 1, 1, "range")
def _countblank(ctx, a):
    return float(sum(1 for v in c.flat(a) if v is None or v == ""))


# -- conditional aggregates ------------------------------------------------------------

@register("AVERAGEIF", 2, 3, "range")
def _averageif(ctx, rng, crit, target=None):
    xs = picked(ctx, rng if target is None else target, [(rng, crit)])
    if isinstance(xs, ExcelError):
        return xs
    return c.result(fsum(xs) / len(xs)) if xs else ExcelError.DIV0


@register("COUNTIF", 2, 2, "range")
def _countif(ctx, rng, crit):
    mask = matches([(rng, crit)], ctx)
    return mask if isinstance(mask, ExcelError) else float(sum(mask))


@register("COUNTIFS", 2, -1, "range")
def _countifs(ctx, *args):
    pairs = ifs_pairs(args)
    if isinstance(pairs, ExcelError):
        return pairs
    mask = matches(pairs, ctx)
    return mask if isinstance(mask, ExcelError) else float(sum(mask))


# an array of criteria in an array formula gives one result per criterion (formulas__test
# STATISTICAL!AH24:AW24 {=COUNTIF(F24:J24,{"*ao","","TRUE",TRUE,"*a?"})} = {0,1,1,1,0})
ARRAY_LIFTED.update({"AVERAGEIF": (1).__eq__, "COUNTIF": (1).__eq__,
                     "COUNTIFS": lambda i: i % 2 == 1})
ARRAY_LIFTED.update({name: (lambda i: i >= 2 and i % 2 == 0)
                     for name in ("AVERAGEIFS", "MAXIFS", "MINIFS")})

register("AVERAGEIFS", 3, -1, "range")(ifs(lambda xs: fsum(xs) / len(xs), ExcelError.DIV0))
register("MAXIFS", 3, -1, "range")(ifs(max, 0.0))
register("MINIFS", 3, -1, "range")(ifs(min, 0.0))


def _kth(ctx, area, kth, largest: bool):
    kk = c.to_number(kth)  # k's error first (formulas test.xlsx STATISTICAL!AA57:AF57)
    if isinstance(kk, ExcelError):
        return kk
    xs = c.numbers([area], ctx)  # a direct argument converts: LARGE("2.3",1) is 2.3
    if isinstance(xs, ExcelError):
        return xs
    # k below 1 is #NUM!; a fractional k is truncated, except that Excel's LARGE takes
    # SMALL(n + 1 - k) truncated, i.e. k rounded up (Mac Excel 16, formulas__test.xlsx
    # STATISTICAL!AG57:AK57 and AG95:AK95: LARGE(..,2.2) is the 3rd, SMALL(..,2.2) the 2nd,
    # LARGE(..,0.9) #NUM!; LibreOffice 7.4 truncates both, measured)
    if kk < 1:
        return ExcelError.NUM
    kk = math.ceil(kk) if largest and ctx.dialect == "excel" else math.trunc(kk)
    if kk > len(xs):
        return ExcelError.NUM
    return sorted(xs, reverse=largest)[kk - 1]


register("LARGE", 2, 2, ("range", "scalar"))(
    lambda ctx, a, kk: _kth(ctx, a, kk, True))
register("SMALL", 2, 2, ("range", "scalar"))(
    lambda ctx, a, kk: _kth(ctx, a, kk, False))


def _rank(ctx, x, ref, order=0.0, average=False):
    x, o = c.to_number(x), c.to_number(order)
    for v in (x, o):
        if isinstance(v, ExcelError):
            return v
    xs = c.numbers([c.as_area(ref)], ctx)
    if isinstance(xs, ExcelError):
        return xs
    if x not in xs:
        return ExcelError.NA
    before = sum(1 for v in xs if (v > x if o == 0 else v < x))
    if not average:
        return float(before + 1)
    ties = xs.count(x)
    return before + (ties + 1) / 2.0


register("RANK", 2, 3, ("scalar", "range", "scalar"), aliases=("RANK.EQ",))(
    lambda ctx, x, ref, order=0.0: _rank(ctx, x, ref, order))
register("RANK.AVG", 2, 3, ("scalar", "range", "scalar"))(
    lambda ctx, x, ref, order=0.0: _rank(ctx, x, ref, order, True))
