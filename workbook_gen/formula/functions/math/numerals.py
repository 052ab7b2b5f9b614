"""Numbers written as text: ROMAN and ARABIC (Roman numerals, ROMAN's five forms), BASE and
DECIMAL (any radix from 2 to 36)."""

from __future__ import annotations

import math

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.numeric import args_of
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError

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


@register("ROMAN", 1, 2)
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


@register("ARABIC", 1, 1)
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


@register("BASE", 2, 3)
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


@register("DECIMAL", 2, 2)
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
