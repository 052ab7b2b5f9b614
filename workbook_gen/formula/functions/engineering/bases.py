"""Whole numbers in bases 2, 8 and 16 and their bits: DEC2BIN/OCT/HEX and back, the
crossings BIN2OCT ... (10-digit two's complement), BITAND, BITOR, BITXOR, BITLSHIFT,
BITRSHIFT (whole numbers below 2^48)."""

from __future__ import annotations

import math

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.numeric import numeric
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError


# -- bases ---------------------------------------------------------------------------------

_BASES = {"BIN": (2, 9), "OCT": (8, 29), "HEX": (16, 39)}  # two's complement sign bit


def _digits(n: int, base: int) -> str:
    return {2: format(n, "b"), 8: format(n, "o"), 16: format(n, "X")}[base] if n else "0"


def _dec2(base_name):
    base, bits = _BASES[base_name]

    def fn(ctx, v, places=None):
        p = None
        if places is not None:  # Excel checks the places first (xlcalculator's BASES.xlsx)
            p = c.to_number(places)
            if isinstance(p, ExcelError):
                return p
            p = int(p)
            if not 1 <= p <= 10:
                return ExcelError.NUM
        if isinstance(v, bool):
            return ExcelError.VALUE
        x = c.to_number(v)
        if isinstance(x, ExcelError):
            return ExcelError.NUM if isinstance(v, str) else x
        n = int(x)
        if not -(2 ** bits) <= n < 2 ** bits:
            return ExcelError.NUM
        if n < 0:  # ten digits of two's complement; places ignored
            return _digits(n + 2 ** (bits + 1), base)
        text = _digits(n, base)
        if p is None:
            return text
        return ExcelError.NUM if p < len(text) else text.zfill(p)
    register(f"DEC2{base_name}", 1, 2)(fn)


def _parse_base(v, base: int, bits: int) -> int | ExcelError:
    if isinstance(v, ExcelError):
        return v
    if isinstance(v, bool):
        return ExcelError.VALUE
    text = c.to_text(v)
    if isinstance(text, ExcelError):
        return text
    text = text.strip() or "0"
    if len(text) > 10:
        return ExcelError.NUM
    try:
        n = int(text, base)
    except ValueError:
        return ExcelError.NUM
    if n < 0:
        return ExcelError.NUM
    return n - 2 ** (bits + 1) if n >= 2 ** bits else n


def _from(base_name):
    base, bits = _BASES[base_name]

    def fn(ctx, v):
        n = _parse_base(v, base, bits)
        return n if isinstance(n, ExcelError) else float(n)
    register(f"{base_name}2DEC", 1, 1)(fn)


def _cross(src_name, dst_name):
    src, sbits = _BASES[src_name]
    dec2 = f"DEC2{dst_name}"

    def fn(ctx, v, places=None):
        n = _parse_base(v, src, sbits)
        if isinstance(n, ExcelError):
            return n
        from workbook_gen.formula.functions.registry import REGISTRY
        return REGISTRY[dec2].fn(ctx, float(n), places)
    register(f"{src_name}2{dst_name}", 1, 2)(fn)


for _b in _BASES:
    _dec2(_b)
    _from(_b)
for _s in _BASES:
    for _d in _BASES:
        if _s != _d:
            _cross(_s, _d)


# -- bits ---------------------------------------------------------------------------------

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


register("BITAND", 2, 2)(_bits(lambda a, b: a & b))
register("BITOR", 2, 2)(_bits(lambda a, b: a | b))
register("BITXOR", 2, 2)(_bits(lambda a, b: a ^ b))


def _shift(sign):
    def fn(x, k):
        x, k = _bit_arg(x), math.trunc(k) * sign
        if x is None or abs(k) > 53:
            return ExcelError.NUM
        r = x << k if k >= 0 else x >> -k
        return ExcelError.NUM if r >= 2 ** 48 else r
    return numeric(fn)


register("BITLSHIFT", 2, 2)(_shift(1))
register("BITRSHIFT", 2, 2)(_shift(-1))
