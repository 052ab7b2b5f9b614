"""workbook_gen/xlmath: Excel's arithmetic over columns with error codes, against Python's
math element by element and Excel's documented error rules: x/0 is #DIV/0!, SQRT of a
negative, ASIN/ACOS beyond 1, 0^0, a negative base with a fractional power and overflow
are #NUM!, 0^-1 is #DIV/0!, ATAN2(0,0) and MOD(x,0) are #DIV/0!, MOD takes the divisor's
sign (n - d*INT(n/d)); the leftmost operand's error wins; no negative zero."""

from __future__ import annotations

import math
import random

import numpy as np
import pytest

from workbook_gen import xlmath as xm
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)
SPECIAL = [0.0, -0.0, 1.0, -1.0, 2.0, -8.0, 0.5, 1e308, -1e308, 1e-308, 3.0, 1 / 3]
XS = SPECIAL + [RNG.uniform(-50, 50) for _ in range(150)]
YS = list(reversed(SPECIAL)) + [RNG.uniform(-5, 5) for _ in range(150)]


def column(values, errors=None) -> xm.XArray:
    a = xm.array(np.array(values, dtype=float))
    if errors is None:
        return a
    err = np.array([e.code if e else 0 for e in errors], np.uint8)
    val = np.where(err == 0, a.val, np.nan)
    return xm.XArray(val, err)


def results(a: xm.XArray) -> list:
    return [e if e else float(v) for v, e in zip(a.val, a.errors())]


def excel_power(x, y):
    if x == 0 and y == 0:
        return ExcelError.NUM
    if x == 0 and y < 0:
        return ExcelError.DIV0
    if x < 0 and y != int(y):
        return ExcelError.NUM
    try:
        r = math.pow(x, y)
    except OverflowError:
        return ExcelError.NUM
    return finite(r)


def finite(r):
    if isinstance(r, ExcelError):
        return r
    return r + 0.0 if math.isfinite(r) else ExcelError.NUM   # +0.0: no negative zero


REFERENCE = {
    "add": lambda x, y: finite(x + y), "sub": lambda x, y: finite(x - y),
    "mul": lambda x, y: finite(x * y),
    "div": lambda x, y: ExcelError.DIV0 if y == 0 else finite(x / y),
    "power": excel_power,
    "mod": lambda x, y: ExcelError.DIV0 if y == 0 else finite(x - y * math.floor(x / y)),
    "atan2": lambda x, y: ExcelError.DIV0 if x == 0 and y == 0 else math.atan2(y, x) + 0.0,
}


def same(got, want, rel=4e-16) -> bool:
    if isinstance(want, ExcelError) or isinstance(got, ExcelError):
        return got == want
    if math.copysign(1, got) != math.copysign(1, want) and got == 0 == want:
        return False
    return got == want or abs(got - want) <= rel * abs(want)


@pytest.mark.parametrize("name", sorted(REFERENCE))
def test_binary_operations(name):
    got = results(getattr(xm, name)(column(XS), column(YS)))
    for x, y, g in zip(XS, YS, got):
        want = REFERENCE[name](x, y)
        if name == "mod" and not isinstance(want, ExcelError) and abs(x / y) > 2**50:
            continue   # beyond 2^50 quotients Excel itself gives #NUM!; not asked here
        assert same(g, want, 2e-15 if name in ("power", "mod") else 4e-16), (name, x, y, g, want)


UNARY = {
    "sin": math.sin, "cos": math.cos, "tan": math.tan, "atan": math.atan, "abs_": abs,
    "sqrt": lambda x: ExcelError.NUM if x < 0 else math.sqrt(x),
    "asin": lambda x: ExcelError.NUM if abs(x) > 1 else math.asin(x),
    "acos": lambda x: ExcelError.NUM if abs(x) > 1 else math.acos(x),
    "radians": math.radians, "degrees": lambda x: finite(math.degrees(x)),
    "sign": lambda x: float((x > 0) - (x < 0)),
}


@pytest.mark.parametrize("name", sorted(UNARY))
def test_unary_functions(name):
    xs = [x for x in XS if abs(x) < 1e15] + [0.3, -0.7, 1.0, -1.0, 1.5]   # SIN(1e308): #NUM!
    got = results(getattr(xm, name)(column(xs)))
    for x, g in zip(xs, got):
        assert same(g, finite(UNARY[name](x)), 2e-16 * 4), (name, x, g)


def test_the_leftmost_error_wins_and_no_fresh_error_over_an_old_one():
    a = column([1.0, 1.0, 0.0, 4.0], [ExcelError.NA, None, None, ExcelError.REF])
    b = column([0.0, 0.0, 0.0, 1.0], [ExcelError.VALUE, ExcelError.NAME, None, None])
    assert results(xm.div(a, b)) == [ExcelError.NA, ExcelError.NAME, ExcelError.DIV0,
                                     ExcelError.REF]
    assert results(xm.add(b, a)) == [ExcelError.VALUE, ExcelError.NAME, 0.0, ExcelError.REF]
    assert results(xm.iferror(xm.div(a, b), column([7.0] * 4))) == [7.0] * 4
    assert results(xm.iserror(xm.div(a, b))) == [1.0, 1.0, 1.0, 1.0]


def test_text_that_is_not_a_number_is_value():
    text = xm.const("abc", 2)
    assert results(xm.add(text, column([1.0, 2.0]))) == [ExcelError.VALUE] * 2
    assert results(xm.add(xm.const("2.5", 2), column([1.0, 2.0]))) == [3.5, 4.5]
