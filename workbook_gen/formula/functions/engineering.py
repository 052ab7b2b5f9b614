"""Engineering and other math: ERF, ERFC (.PRECISE), BITAND/OR/XOR/LSHIFT/
RSHIFT, ROMAN, ARABIC, BASE, DECIMAL, the reciprocal trigonometric functions (COT, CSC,
SEC and hyperbolic, ACOT, ACOTH), MULTINOMIAL, SERIESSUM. Special functions by mpmath
at 30 digits, rounded to a float."""

from __future__ import annotations

import math

import mpmath

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.distributions import DPS, args_of, numeric
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError


@register("ERF", "eng", 1, 2)
def _erf(ctx, *limits):
    """ERF(lower) or ERF(lower, upper): an empty upper cell is 0, not omitted."""
    xs = args_of(*limits, booleans=False)
    if isinstance(xs, ExcelError):
        return xs
    with mpmath.workdps(DPS):
        if len(xs) == 1:
            return c.result(float(mpmath.erf(xs[0])))
        return c.result(float(mpmath.erf(xs[1]) - mpmath.erf(xs[0])))


def _no_bool(fn):
    def scalar(ctx, x):
        return ExcelError.VALUE if isinstance(x, bool) else fn(ctx, x)
    return scalar


register("ERF.PRECISE", "eng", 1, 1)(_no_bool(numeric(mpmath.erf)))
register("ERFC", "eng", 1, 1, aliases=("ERFC.PRECISE",))(_no_bool(numeric(mpmath.erfc)))


def _bit_arg(x):
    if x < 0 or x != math.floor(x) or x >= 2 ** 48:
        return None
    return int(x)


def _bits(op):
    def fn(a, b):
        a, b = _bit_arg(a), _bit_arg(b)
        if a is None or b is None:
            return ExcelError.NUM
        return op(a, b)
    return numeric(fn)


register("BITAND", "eng", 2, 2)(_bits(lambda a, b: a & b))
register("BITOR", "eng", 2, 2)(_bits(lambda a, b: a | b))
register("BITXOR", "eng", 2, 2)(_bits(lambda a, b: a ^ b))


def _shift(sign):
    def fn(x, k):
        x, k = _bit_arg(x), math.trunc(k) * sign
        if x is None or abs(k) > 53:
            return ExcelError.NUM
        r = x << k if k >= 0 else x >> -k
        return ExcelError.NUM if r >= 2 ** 48 else r
    return numeric(fn)


register("BITLSHIFT", "eng", 2, 2)(_shift(1))
register("BITRSHIFT", "eng", 2, 2)(_shift(-1))


# -- Roman numerals ----------------------------------------------------------------------------

_CHARS = "MDCLXVI"
_VALUES = (1000, 500, 100, 50, 10, 5, 1)


def roman(n: int, mode: int) -> str:
    """Excel's ROMAN with forms 0 (classic) to 4 (most simplified): a subtractive pair may
    reach ``mode`` steps further down the numeral list."""
    out = []
    last = len(_VALUES) - 1
    for i in range(0, last // 2 + 1):
        idx = 2 * i
        digit = n // _VALUES[idx]
        if digit % 5 == 4:
            idx2 = idx - 1 if digit == 4 else idx - 2
            steps = 0
            while steps < mode and idx < last:
                steps += 1
                if _VALUES[idx2] - _VALUES[idx + 1] <= n:
                    idx += 1
                else:
                    steps = mode
            out.append(_CHARS[idx] + _CHARS[idx2])
            n = n + _VALUES[idx] - _VALUES[idx2]
        else:
            if digit > 4:
                out.append(_CHARS[idx - 1])
            out.append(_CHARS[idx] * (digit % 5))
            n %= _VALUES[idx]
    return "".join(out)


@register("ROMAN", "math", 1, 2)
def _roman(ctx, number, form=0.0):
    if isinstance(form, bool):
        form = 0.0 if form else 4.0
    xs = args_of(number, 0.0 if form is None else form)
    if isinstance(xs, ExcelError):
        return xs
    n, mode = math.trunc(xs[0]), math.trunc(xs[1])
    if not 0 <= n <= 3999 or not 0 <= mode <= 4:
        return ExcelError.VALUE
    return roman(n, mode)


@register("ARABIC", "math", 1, 1)
def _arabic(ctx, text):
    t = c.to_text(text)
    if isinstance(t, ExcelError):
        return t
    t = t.strip().upper()
    sign = -1.0 if t.startswith("-") else 1.0
    t = t.lstrip("-")
    if len(t) > 255 or set(t) - set(_CHARS):
        return ExcelError.VALUE
    vals = [_VALUES[_CHARS.index(ch)] for ch in t]
    if ctx.dialect == "libreoffice":  # a numeral before a larger next one is subtracted
        total = sum(-v if i + 1 < len(vals) and v < vals[i + 1] else v
                    for i, v in enumerate(vals))
        return sign * total
    # Excel: read from the right, a numeral smaller than the largest seen so far is
    # subtracted (Mac Excel 16, formulas__test.xlsx 'MATH & TRIG'!T9: ARABIC("IIIIIIV") = -1,
    # V9: ARABIC("IILmIIC") = 1046); the same as the pairwise rule on well-formed numerals
    total, largest = 0, 0
    for v in reversed(vals):
        if v < largest:
            total -= v
        else:
            total += v
            largest = v
    return sign * float(total)


_DIGITS = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ"


@register("BASE", "math", 2, 3)
def _base(ctx, number, radix, min_length=0.0):
    xs = args_of(number, radix, 0.0 if min_length is None else min_length)
    if isinstance(xs, ExcelError):
        return xs
    n, r, k = (math.trunc(v) for v in xs)
    if n < 0 or n >= 2 ** 53 or not 2 <= r <= 36 or not 0 <= k <= 255:
        return ExcelError.NUM
    out = ""
    while n:
        n, d = divmod(n, r)
        out = _DIGITS[d] + out
    return (out or "0").rjust(k, "0")


@register("DECIMAL", "math", 2, 2)
def _decimal(ctx, text, radix):
    t, r = c.to_text(text), c.to_number(radix)
    for v in (t, r):
        if isinstance(v, ExcelError):
            return v
    r = math.trunc(r)
    if not 2 <= r <= 36 or len(t) > 255:
        return ExcelError.NUM
    try:
        return float(int(t, r)) if t.strip() else 0.0
    except ValueError:
        return ExcelError.NUM


# -- reciprocal trigonometry -----------------------------------------------------------------

def _recip(fn, limit=2 ** 27):
    def f(x):
        if abs(x) >= limit:
            return ExcelError.NUM
        d = fn(x)
        return ExcelError.DIV0 if d == 0 else 1 / d
    return numeric(f)


register("COT", "math", 1, 1)(_recip(math.tan))
register("CSC", "math", 1, 1)(_recip(math.sin))
register("SEC", "math", 1, 1)(_recip(math.cos))
register("COTH", "math", 1, 1)(_recip(math.tanh, float("inf")))
register("CSCH", "math", 1, 1)(_recip(math.sinh, float("inf")))
register("SECH", "math", 1, 1)(_recip(math.cosh, float("inf")))
register("ACOT", "math", 1, 1)(numeric(lambda x: math.pi / 2 - math.atan(x)))
register("ACOTH", "math", 1, 1)(numeric(
    lambda x: ExcelError.NUM if abs(x) <= 1 else 0.5 * math.log((x + 1) / (x - 1))))


@register("MULTINOMIAL", "math", 1, -1, "range")
def _multinomial(ctx, *args):
    xs = c.numbers(args, ctx)
    if isinstance(xs, ExcelError):
        return xs
    ks = [math.trunc(x) for x in xs]
    if any(k < 0 for k in ks):
        return ExcelError.NUM
    r = math.factorial(sum(ks))
    for k in ks:
        r //= math.factorial(k)
    return c.result(float(r))


@register("SERIESSUM", "math", 4, 4, ("scalar", "scalar", "scalar", "range"))
def _seriessum(ctx, x, n, m, coefficients):
    xs = args_of(x, n, m)
    if isinstance(xs, ExcelError):
        return xs
    x, n, m = xs
    total = 0.0
    for i, a in enumerate(c.flat(coefficients)):
        if isinstance(a, ExcelError):
            return a
        a = c.to_number(a)
        if isinstance(a, ExcelError):
            return ExcelError.VALUE
        total += a * x ** (n + i * m)
    return c.result(total)
