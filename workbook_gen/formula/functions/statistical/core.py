"""Statistics: MIN, MAX, AVERAGE(A), COUNT(A/BLANK), the *IF(S) family with criteria,
SUMPRODUCT, MEDIAN, MODE, STDEV/VAR (sample and population), LARGE, SMALL, RANK."""

from __future__ import annotations

import math
import statistics

import numpy as np

from workbook_gen.formula.functions import coerce as c
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

def _criterion_value(ctx, crit):
    """A criteria range is implicitly intersected with the formula's row or column; no
    shared cell is #VALUE!, a criterion that matches the cells holding #VALUE! (POI
    FormulaEvalTestData.xlsx: SUMIF(AA7:AA13,C10:D10,C7) in row 1324 is C9, 1.1)."""
    if not isinstance(crit, Range):
        return crit
    return ctx.scalar(crit) if ctx is not None else ExcelError.VALUE


_OPS = ("<=", ">=", "<>", "=", "<", ">")


def _lo_number(v):
    """A criterion as LibreOffice's, which has no boolean type: TRUE, "TRUE" are 1."""
    if isinstance(v, bool):
        return float(v)
    if isinstance(v, str):
        op = next((o for o in _OPS if v.startswith(o)), "")
        body = v[len(op):].upper()
        if body in ("TRUE", "FALSE"):
            return float(body == "TRUE") if not op else op + ("1" if body == "TRUE" else "0")
    return v


def _lo_values(crit, values):
    """LibreOffice 7.4 (measured: COUNTIF over {TRUE,1,"1"}) sees a boolean cell as its
    number except under a plain text criterion (" 1" counts 1 and "1", not TRUE)."""
    if isinstance(crit, str) and not crit.startswith(_OPS):
        return values
    return [float(v) if isinstance(v, bool) else v for v in values]


def _matches(pairs, ctx=None) -> list[bool] | ExcelError:
    """Per cell of the first range, whether every (range, criterion) pair holds."""
    shape = None
    mask = None
    for rng, crit in pairs:
        area = c.as_area(rng)
        if shape is None:
            shape = area.shape
        elif area.shape != shape:
            return ExcelError.VALUE
        crit = _criterion_value(ctx, crit)
        values = area.flat()
        if ctx is not None and ctx.dialect == "libreoffice":  # no boolean type: TRUE is 1
            if isinstance(crit, ExcelError):  # an error criterion is the result (measured,
                return crit                   # tests/differential.py)
            crit = _lo_number(crit)
            values = _lo_values(crit, values)
        pred = c.criterion(crit)
        if isinstance(pred, ExcelError):
            return pred
        hits = [pred(v) for v in values]
        mask = hits if mask is None else [a and b for a, b in zip(mask, hits)]
    return mask


def _resized(area: Range, shape, ctx) -> list:
    """SUMIF's sum range takes the criteria range's shape from its top-left cell."""
    if area.shape == shape or area.ref is None:
        return list(area.flat())
    ref = area.ref
    from workbook_gen.formula.values import Ref
    grown = ctx.read(Ref(ref.sheet, ref.row1, ref.col1, ref.row1 + shape[0] - 1,
                         ref.col1 + shape[1] - 1))
    return list(area.flat()) if isinstance(grown, ExcelError) else list(grown.flat())


def _picked(ctx, target, pairs):
    mask = _matches(pairs, ctx)
    if isinstance(mask, ExcelError):
        return mask
    area = c.as_area(target)
    values = _resized(area, c.as_area(pairs[0][0]).shape, ctx)
    out = []
    for v, hit in zip(values, mask):
        if not hit:
            continue
        if isinstance(v, ExcelError):
            return v
        if c.is_number(v) or (ctx.dialect == "libreoffice" and isinstance(v, bool)):
            out.append(float(v))
    return out


def _ifs_pairs(args):
    if len(args) % 2:
        return ExcelError.VALUE
    return [(args[i], args[i + 1]) for i in range(0, len(args), 2)]


@register("SUMIF", 2, 3, "range")
def _sumif(ctx, rng, crit, target=None):
    xs = _picked(ctx, rng if target is None else target, [(rng, crit)])
    return xs if isinstance(xs, ExcelError) else c.result(fsum(xs))


@register("AVERAGEIF", 2, 3, "range")
def _averageif(ctx, rng, crit, target=None):
    xs = _picked(ctx, rng if target is None else target, [(rng, crit)])
    if isinstance(xs, ExcelError):
        return xs
    return c.result(fsum(xs) / len(xs)) if xs else ExcelError.DIV0


@register("COUNTIF", 2, 2, "range")
def _countif(ctx, rng, crit):
    mask = _matches([(rng, crit)], ctx)
    return mask if isinstance(mask, ExcelError) else float(sum(mask))


@register("COUNTIFS", 2, -1, "range")
def _countifs(ctx, *args):
    pairs = _ifs_pairs(args)
    if isinstance(pairs, ExcelError):
        return pairs
    mask = _matches(pairs, ctx)
    return mask if isinstance(mask, ExcelError) else float(sum(mask))


def _xifs(name, fn, empty):
    def scalar(ctx, target, *args):
        pairs = _ifs_pairs(args)
        if isinstance(pairs, ExcelError):
            return pairs
        if c.as_area(target).shape != c.as_area(pairs[0][0]).shape:
            return ExcelError.VALUE
        xs = _picked(ctx, target, pairs)
        if isinstance(xs, ExcelError):
            return xs
        return c.result(fn(xs)) if xs else empty
    register(name, 3, -1, "range")(scalar)


# an array of criteria in an array formula gives one result per criterion (formulas__test
# STATISTICAL!AH24:AW24 {=COUNTIF(F24:J24,{"*ao","","TRUE",TRUE,"*a?"})} = {0,1,1,1,0})
ARRAY_LIFTED.update({"SUMIF": (1).__eq__, "AVERAGEIF": (1).__eq__, "COUNTIF": (1).__eq__,
                     "COUNTIFS": lambda i: i % 2 == 1})
ARRAY_LIFTED.update({name: (lambda i: i >= 2 and i % 2 == 0)
                     for name in ("SUMIFS", "AVERAGEIFS", "MAXIFS", "MINIFS")})

_xifs("SUMIFS", fsum, 0.0)
_xifs("AVERAGEIFS", lambda xs: fsum(xs) / len(xs), ExcelError.DIV0)
_xifs("MAXIFS", max, 0.0)
_xifs("MINIFS", min, 0.0)


@register("SUMPRODUCT", 1, -1, "range")
def _sumproduct(ctx, *args):
    areas = [c.as_area(a) for a in args]
    shape = areas[0].shape
    if any(a.shape != shape for a in areas):  # Excel: an error in the arrays first (Mac
        # Excel's 'MATH & TRIG'!AE75:AF75: the first array's #NUM!, #REF!); LibreOffice
        # (7.4, measured): #VALUE!
        if ctx is not None and ctx.dialect == "libreoffice":
            return ExcelError.VALUE
        return next((v for a in areas for v in a.flat() if isinstance(v, ExcelError)),
                    ExcelError.VALUE)
    columns = [list(a.flat()) for a in areas]
    lo = ctx.dialect == "libreoffice"  # a boolean is a number there
    if shape == (1, 1) and not lo and any(isinstance(v, (str, bool)) for (v,) in columns):
        # single values multiply as direct arguments: text is #VALUE!, not the zero of a
        # non-numeric array entry (POI FormulaEvalTestData.xlsx J1328: SUMPRODUCT(G1330:G1330,
        # I1330:I1330) over "4" and 2)
        return c.first_error([v for (v,) in columns]) or ExcelError.VALUE
    total = []
    for row in zip(*columns):
        err = c.first_error(row)
        if err is not None:
            return err
        total.append(math.prod(float(v) if c.is_number(v) or (lo and isinstance(v, bool))
                               else 0.0 for v in row))
    return c.result(fsum(total))


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
