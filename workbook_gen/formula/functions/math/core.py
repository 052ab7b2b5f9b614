"""Math and trigonometry: SIN .. POWER (section 4), rounding, logarithms, products."""

from __future__ import annotations

import math
import random
from decimal import (
    ROUND_CEILING, ROUND_DOWN, ROUND_FLOOR, ROUND_HALF_UP, ROUND_UP, Decimal, localcontext,
)

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.numeric import choices
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import TRIG_LIMIT, ExcelError
from workbook_gen.xlmath import kernels as k


def power(x: float, y: float) -> float | ExcelError:
    """Excel's ``x^y`` and POWER: 0^0 #NUM!, 0^-n #DIV/0!, (-x)^fraction #NUM!."""
    if x == 0:
        if y == 0:
            return ExcelError.NUM
        return ExcelError.DIV0 if y < 0 else 0.0
    if x < 0 and y != math.floor(y):
        return ExcelError.NUM
    try:
        return c.checked(math.pow(x, y))
    except OverflowError:
        return ExcelError.NUM


def _numeric(*xs):
    """The first error among already-coerced numbers, else None."""
    return next((x for x in xs if isinstance(x, ExcelError)), None)


def _math1(name, fn, vector=None, booleans=True, **kw):
    """``booleans=False``: a function of Excel's Analysis ToolPak, which takes no boolean
    argument (#VALUE!; formulas__test.xlsx 'MATH & TRIG'!Y70, SQRTPI(TRUE))."""
    def scalar(ctx, a):
        if not booleans and isinstance(a, bool):
            return ExcelError.VALUE
        x = c.to_number(a)
        return x if isinstance(x, ExcelError) else c.result(fn(x))
    register(name, 1, 1, vector=vector, **kw)(scalar)


def _math2(name, fn, vector=None, min_args=2):
    def scalar(ctx, a, b=None):
        x = c.to_number(a)
        y = c.to_number(b)
        bad = _numeric(x, y)
        return bad if bad is not None else c.result(fn(x, y))
    register(name, min_args, 2, vector=vector)(scalar)


def _unary_vector(name):
    def vector(xs, n):
        (x, ex), = xs
        return (*k.unary(name, x, ex), False)
    return vector


def _trig(fn):
    return lambda x: ExcelError.NUM if abs(x) >= TRIG_LIMIT else fn(x)


def _domain(fn, lo, hi, open_lo=False):
    return lambda x: fn(x) if (lo < x if open_lo else lo <= x) and x <= hi else ExcelError.NUM


def _atan2(x: float, y: float):
    """Excel's ATAN2(x, y): x first; (0, 0) is #DIV/0!."""
    return ExcelError.DIV0 if x == 0 and y == 0 else math.atan2(y, x)


def _mod(n: float, d: float):
    """MOD(n, d) = n - d*INT(n/d); the result takes the sign of d; #NUM! if n/d overflows."""
    if d == 0:
        return ExcelError.DIV0
    q = n / d
    return n - d * math.floor(q) if math.isfinite(q) else ExcelError.NUM


def _sign(x: float) -> float:
    return float((x > 0) - (x < 0))


for _name, _fn in (("SIN", _trig(math.sin)), ("COS", _trig(math.cos)), ("TAN", _trig(math.tan)),
                   ("ASIN", _domain(math.asin, -1.0, 1.0)),
                   ("ACOS", _domain(math.acos, -1.0, 1.0)), ("ATAN", math.atan),
                   ("SQRT", _domain(math.sqrt, 0.0, math.inf)), ("ABS", abs), ("SIGN", _sign),
                   ("RADIANS", math.radians), ("DEGREES", math.degrees)):
    _math1(_name, _fn, _unary_vector(_name))


def _hyper(fn):
    def call(x):
        try:
            return fn(x)
        except (OverflowError, ValueError):
            return ExcelError.NUM
    return call


for _name, _fn in (("SINH", math.sinh), ("COSH", math.cosh), ("TANH", math.tanh),
                   ("ASINH", math.asinh), ("EXP", math.exp)):
    _math1(_name, _hyper(_fn))
_math1("ACOSH", _domain(math.acosh, 1.0, math.inf))
_math1("ATANH", _domain(math.atanh, -1.0, 1.0, open_lo=True))
_math1("LN", _domain(math.log, 0.0, math.inf, open_lo=True))
_math1("LOG10", _domain(math.log10, 0.0, math.inf, open_lo=True))
_math1("SQRTPI", _domain(lambda x: math.sqrt(x * math.pi), 0.0, math.inf), booleans=False)
_math1("INT", lambda x: float(math.floor(x)))
_math1("EVEN", lambda x: math.copysign(2 * math.ceil(abs(x) / 2), x))
_math1("ODD", lambda x: math.copysign(max(1, 2 * math.ceil((abs(x) + 1) / 2) - 1), x)
       if x != 0 else 1.0)
_math1("FACT", lambda x: float(math.factorial(int(x))) if 0 <= x < 171 else ExcelError.NUM)


@register("FACTDOUBLE", 1, 1)
def _factdouble(ctx, a):
    """n!! of TRUNC(x). Excel (an Analysis ToolPak function): no boolean; #NUM! below -1,
    and -1 (or -1 < x < 0) gives the empty product 1 (Mac Excel 16, formulas__test.xlsx
    'MATH & TRIG'!V31: FACTDOUBLE(-1) = 1, T31: FACTDOUBLE(-1.1) = #NUM!). LibreOffice
    7.4: #VALUE! for any negative (measured: -1, -1.1, -2)."""
    if isinstance(a, bool):
        return ExcelError.VALUE
    x = c.to_number(a)
    if isinstance(x, ExcelError):
        return x
    if ctx.dialect == "libreoffice" and x < 0:
        return ExcelError.VALUE
    if x < -1 or x >= 301:
        return ExcelError.NUM
    return float(math.prod(range(int(x), 0, -2)))


def _vector2(kernel):
    def vector(xs, n):
        (x, ex), (y, ey) = xs
        return (*kernel(x, ex, y, ey), False)
    return vector


_math2("ATAN2", _atan2, _vector2(k.atan2))
_math2("MOD", _mod, _vector2(k.mod))
_math2("POWER", power, _vector2(lambda x, ex, y, ey: k.power(x, y, k.first_error(ex, ey))))


@register("PI", 0, 0)
def _pi(ctx):
    return math.pi


@register("LOG", 1, 2)
def _log(ctx, x, base=10.0):
    x, b = c.to_number(x), c.to_number(base)
    bad = _numeric(x, b)
    if bad is not None:
        return bad
    if x <= 0 or b <= 0:
        return ExcelError.NUM
    if b == 1:
        return ExcelError.DIV0
    return c.result(math.log(x) / math.log(b))


# -- rounding -------------------------------------------------------------------------

def _decimal(x: float) -> Decimal:
    """``x`` as Excel sees it for rounding: its 15 significant digits."""
    return Decimal(f"{x:.15g}") if math.isfinite(x) else Decimal(0)


def round_digits(x: float, digits: float, mode) -> float:
    """``x`` to ``digits`` places (negative: tens, hundreds...) by decimal's rounding
    ``mode``: ROUND, ROUNDUP, ROUNDDOWN, TRUNC; and TEXT, FIXED and the number formats."""
    d = int(max(min(digits, 400.0), -400.0))
    if d > 15 or x == 0:
        return x
    q = Decimal(1).scaleb(-d)
    with localcontext() as ctx:
        ctx.prec = 800  # quantize must not run out of digits (1E300 to 15 places)
        return float(_decimal(x).quantize(q, rounding=mode) if d >= 0 else
                     (_decimal(x) / q).quantize(Decimal(1), rounding=mode) * q)


def _rounder(name, mode):
    def scalar(ctx, x, digits=0.0):
        x, d = c.to_number(x), c.to_number(digits)
        bad = _numeric(x, d)
        return bad if bad is not None else c.result(round_digits(x, d, mode))
    register(name, 1 if name == "TRUNC" else 2, 2)(scalar)


_rounder("ROUND", ROUND_HALF_UP)
_rounder("ROUNDUP", ROUND_UP)
_rounder("ROUNDDOWN", ROUND_DOWN)
_rounder("TRUNC", ROUND_DOWN)


def _multiple(x: float, m: float, mode) -> float:
    if m == 0:
        return 0.0
    with localcontext() as ctx:
        ctx.prec = 800
        ratio = Decimal(format(_decimal(x) / _decimal(m), ".15g"))  # 15 digits, as Excel
        q = ratio.quantize(Decimal(1), rounding=mode)
        return float(format(q * _decimal(m), ".15g"))


@register("MROUND", 2, 2)
def _mround(ctx, x, m):
    if isinstance(x, bool) or isinstance(m, bool):  # Analysis ToolPak: no booleans
        return ExcelError.VALUE                     # (formulas__test 'MATH & TRIG'!Y45)
    x, m = c.to_number(x), c.to_number(m)
    bad = _numeric(x, m)
    if bad is not None:
        return bad
    if m != 0 and (x > 0) != (m > 0) and x != 0:
        return ExcelError.NUM
    return c.result(_multiple(x, m, ROUND_HALF_UP))


def _value_and_significance(x, sig):
    """CEILING's and FLOOR's arguments as numbers, or the first error; #NUM! for a positive
    number with a negative significance."""
    x, s = c.to_number(x), c.to_number(sig)
    bad = _numeric(x, s)
    if bad is not None:
        return bad
    if x > 0 and s < 0:
        return ExcelError.NUM
    return x, s


@register("CEILING", 2, 2)
def _ceiling(ctx, x, sig):
    args = _value_and_significance(x, sig)
    if isinstance(args, ExcelError):
        return args
    x, s = args
    if s == 0:
        return 0.0
    mode = ROUND_UP if (x < 0 and s < 0) else ROUND_CEILING
    return c.result(_multiple(x, s, mode if s > 0 else ROUND_UP))


@register("ECMA.CEILING", 2, 2)
def _ecma_ceiling(ctx, x, sig):
    """ECMA-376's CEILING (Part 1, 18.17.7.33, and Microsoft's MS-OI29500 note on it): away
    from zero to a multiple of significance; x and significance of different signs: #NUM!."""
    xs, s = c.to_number(x), c.to_number(sig)
    bad = _numeric(xs, s)
    if bad is not None:
        return bad
    if xs * s < 0:
        return ExcelError.NUM
    return _ceiling(ctx, xs, s)


@register("FLOOR", 2, 2)
def _floor(ctx, x, sig):
    args = _value_and_significance(x, sig)
    if isinstance(args, ExcelError):
        return args
    x, s = args
    if s == 0:
        return ExcelError.DIV0 if x != 0 else 0.0
    return c.result(_multiple(x, s, ROUND_FLOOR if s > 0 else ROUND_DOWN))


def _math_round(name, toward_up):
    def scalar(ctx, x, sig=1.0, mode=0.0):
        x, s, m = c.to_number(x), c.to_number(sig), c.to_number(mode)
        bad = _numeric(x, s, m)
        if bad is not None:
            return bad
        if s == 0:
            return 0.0
        s = abs(s)
        if x < 0 and m != 0:  # away from zero (CEILING.MATH) / toward zero (FLOOR.MATH)
            rounding = ROUND_UP if toward_up else ROUND_DOWN
        else:
            rounding = ROUND_CEILING if toward_up else ROUND_FLOOR
        return c.result(_multiple(x, s, rounding))
    return scalar


register("CEILING.MATH", 1, 3)(_math_round("CEILING.MATH", True))
register("FLOOR.MATH", 1, 3)(_math_round("FLOOR.MATH", False))
register("CEILING.PRECISE", 1, 2, aliases=("ISO.CEILING",))(
    lambda ctx, x, s=1.0: _math_round("", True)(ctx, x, s, 0.0))
register("FLOOR.PRECISE", 1, 2)(lambda ctx, x, s=1.0: _math_round("", False)(ctx, x, s, 0.0))


@register("QUOTIENT", 2, 2)
def _quotient(ctx, a, b):
    x, y = c.to_number(a), c.to_number(b)
    bad = _numeric(x, y)
    if bad is not None:
        return bad
    return ExcelError.DIV0 if y == 0 else c.result(float(math.trunc(x / y)))


# -- aggregates over numbers ---------------------------------------------------------------

def fsum(xs: list[float]) -> float:
    """Correctly rounded sum; NaN (so #NUM!) where it overflows."""
    try:
        return math.fsum(xs)
    except (OverflowError, ValueError):  # fsum raises instead of returning inf
        return math.nan


def _sum_vector(xs, n):
    err = k.first_error(*(e for _, e in xs))
    return (*k.finish(k.fsum_rows([v for v, _ in xs], err), err), False)


@register("SUM", 1, -1, "range", vector=_sum_vector, range_numbers=True)
def _sum(ctx, *args):
    xs = c.numbers(args, ctx)
    return xs if isinstance(xs, ExcelError) else c.result(fsum(xs))


@register("PRODUCT", 1, -1, "range")
def _product(ctx, *args):
    xs = c.numbers(args, ctx)
    if isinstance(xs, ExcelError):
        return xs
    return c.result(math.prod(xs)) if xs else 0.0


@register("SUMSQ", 1, -1, "range")
def _sumsq(ctx, *args):
    xs = c.numbers(args, ctx)
    return xs if isinstance(xs, ExcelError) else c.result(fsum([x * x for x in xs]))


def _gcd_args(args, strict: bool = False):
    """``strict`` (Excel): every value, a referenced cell's too, must be a number: an empty
    cell, text or a boolean is #VALUE! (formulas__test MATH & TRIG!W34:Y37, before a
    negative's #NUM!)."""
    if strict:
        for a in args:
            for v in (a.flat() if isinstance(a, Range) else [a]):
                if isinstance(v, ExcelError):
                    return v
                if v is None or isinstance(v, (str, bool)):
                    return ExcelError.VALUE
    xs = c.numbers(args)
    if isinstance(xs, ExcelError):
        return xs
    if any(x < 0 or x >= 2 ** 53 for x in xs):
        return ExcelError.NUM
    return [int(x) for x in xs]


@register("GCD", 1, -1, "range")
def _gcd(ctx, *args):
    xs = _gcd_args(args, ctx.dialect != "libreoffice")
    return xs if isinstance(xs, ExcelError) else float(math.gcd(*xs))


@register("LCM", 1, -1, "range")
def _lcm(ctx, *args):
    xs = _gcd_args(args, ctx.dialect != "libreoffice")
    return xs if isinstance(xs, ExcelError) else c.result(float(math.lcm(*xs)))


register("COMBIN", 2, 2)(choices(math.comb))  # PERMUT is statistical (statistical/testing)


# -- volatile ------------------------------------------------------------------------------

@register("RAND", 0, 0, volatile=True)
def _rand(ctx):
    return random.random()


@register("RANDBETWEEN", 2, 2, volatile=True)
def _randbetween(ctx, lo, hi):
    a, b = c.to_number(lo), c.to_number(hi)
    bad = _numeric(a, b)
    if bad is not None:
        return bad
    a, b = math.ceil(a), math.floor(b)
    return ExcelError.NUM if a > b else float(random.randint(a, b))
