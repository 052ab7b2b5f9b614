"""expr.numeric.compile_numpy: a tree as a numpy function, Excel's semantics row by row.

References: Python's math (correctly rounded libm for the smooth functions, fractions for
the exact ones) and Microsoft's documented behaviour of each function:
MOD https://support.microsoft.com/en-us/office/mod-function-9b6cd169-b6ee-406a-a97b-edf2a9dc24f3
ATAN2 https://support.microsoft.com/en-us/office/atan2-function-c04592ab-b9e3-4908-b428-c96b3a565033
SQRT https://support.microsoft.com/en-us/office/sqrt-function-654975c2-05c4-4831-9a24-2c65e4040fdf
POWER https://support.microsoft.com/en-us/office/power-function-d3f2908b-56f4-4c3f-895a-07fb519c362a
IFERROR https://support.microsoft.com/en-us/office/iferror-function-c526fd07-caeb-47b8-8bb6-63f3e417f611
Comparison order (numbers < text < logical, text case-insensitive):
https://support.microsoft.com/en-us/office/calculation-operators-and-precedence-in-excel-48be406d-4975-4d31-b2b8-7af9e0e2878a
"""

from __future__ import annotations

import pytest

import math

import numpy as np

from workbook_gen import xlmath as xm
from workbook_gen.expr import (Param, Text, Var, abs_, acos, and_, asin, atan, atan2, cos,
                               degrees, eq, gt, if_, iferror, iserror, lt, max_, min_, mod,
                               not_, or_, pi, power, radians, sign, sin, sqrt, tan, wrap)
from workbook_gen.expr.numeric import compile_numpy, compiled
from workbook_gen.expr.tree import Call
from workbook_gen.xlerror import ExcelError

X = [0.5, -2.0, 3.0, 0.0, 1e-3, -0.75]
Y = [2.0, 4.0, -1.5, 0.0, 7.0, 0.25]
N = len(X)


def _run(tree, params=None):
    cols = {"x": xm.array(np.array(X)), "y": xm.array(np.array(Y))}
    return compile_numpy(tree)(cols, params or {"p": 1.25}, N)


def _cells(result):
    """Each row as a float, a text or an ExcelError."""
    errs = result.errors()
    return [e if e is not None else v for v, e in zip(result.val.tolist(), errs)]


def _expect(tree, fn):
    """Row by row what ``fn(x, y)`` gives in Python (an ExcelError where Excel errs)."""
    got = _cells(_run(tree))
    want = [fn(x, y) for x, y in zip(X, Y)]
    for g, w, x, y in zip(got, want, X, Y):
        if isinstance(w, ExcelError):
            assert g == w, (x, y, g, w)
        else:
            assert not isinstance(g, ExcelError), (x, y, g)
            assert g == w or math.isclose(g, w, rel_tol=1e-15, abs_tol=1e-300), (x, y, g, w)


def test_arithmetic_is_ieee_with_excel_errors():
    x, y = Var("x"), Var("y")
    _expect(x + y * 2 - Param("p"), lambda a, b: a + b * 2 - 1.25)
    _expect(x / y, lambda a, b: ExcelError.DIV0 if b == 0 else a / b)
    _expect(-x, lambda a, b: -a + 0.0)  # Excel has no -0


def test_power_follows_excel():
    # 0^0 is #NUM!, 0^negative is #DIV/0!, a negative base with a fraction is #NUM!
    def ref(a, b):
        if a == 0 and b == 0:
            return ExcelError.NUM
        if a == 0 and b < 0:
            return ExcelError.DIV0
        if a < 0 and b != int(b):
            return ExcelError.NUM
        return math.pow(a, b)
    _expect(Var("x") ** Var("y"), ref)
    _expect(power(Var("x"), Var("y")), ref)


def test_smooth_functions_are_libm():
    x = Var("x")
    for node, fn in [(sin(x), math.sin), (cos(x), math.cos), (tan(x), math.tan),
                     (atan(x), math.atan), (abs_(x), abs), (radians(x), math.radians),
                     (degrees(x), math.degrees)]:
        _expect(node, lambda a, b, fn=fn: fn(a))
    _expect(sign(x), lambda a, b: float((a > 0) - (a < 0)))
    _expect(pi() * 1, lambda a, b: math.pi)


def test_domains_give_num():
    x = Var("x")
    _expect(sqrt(x), lambda a, b: ExcelError.NUM if a < 0 else math.sqrt(a))
    _expect(asin(Var("y")), lambda a, b: ExcelError.NUM if abs(b) > 1 else math.asin(b))
    _expect(acos(Var("y")), lambda a, b: ExcelError.NUM if abs(b) > 1 else math.acos(b))


def test_atan2_takes_x_first_and_errs_at_the_origin():
    # ATAN2(x_num, y_num) is the angle of the point (x, y): math.atan2(y, x)
    _expect(atan2(Var("x"), Var("y")),
            lambda a, b: ExcelError.DIV0 if a == 0 and b == 0 else math.atan2(b, a))


def test_mod_takes_the_divisors_sign():
    # MOD(n, d) = n - d*INT(n/d): MOD(3, -2) = -1, MOD(-3, 2) = 1 (Microsoft's examples)
    def ref(a, b):
        return ExcelError.DIV0 if b == 0 else a - b * math.floor(a / b)
    _expect(mod(Var("x"), Var("y")), ref)
    assert _cells(compile_numpy(mod(wrap(3.0), wrap(-2.0)))({}, {}, 1)) == [-1.0]
    assert _cells(compile_numpy(mod(wrap(-3.0), wrap(2.0)))({}, {}, 1)) == [1.0]


def test_if_takes_only_the_chosen_branchs_error():
    x, y = Var("x"), Var("y")
    _expect(if_(lt(x, y), x / y, y - x),
            lambda a, b: (ExcelError.DIV0 if b == 0 else a / b) if a < b else b - a)
    # IF without a third argument is FALSE where the condition is false (Microsoft's IF
    # page), not a number: trees refuse it rather than compute a 0
    with pytest.raises(ValueError, match="IF takes 3..3 arguments"):
        Call("IF", (gt(x, 0.0), x))


def test_iserror_iferror_not_and_or():
    x, y = Var("x"), Var("y")
    _expect(iserror(x / y), lambda a, b: float(b == 0))
    _expect(iferror(x / y, -1.0), lambda a, b: -1.0 if b == 0 else a / b)
    _expect(not_(x), lambda a, b: float(a == 0))
    _expect(and_(x, y), lambda a, b: float(a != 0 and b != 0))
    _expect(or_(x, y), lambda a, b: float(a != 0 or b != 0))
    # an error argument wins over AND's value
    _expect(and_(x / y, 0.0), lambda a, b: ExcelError.DIV0 if b == 0 else 0.0)


def test_min_max_and_the_leftmost_error():
    x, y = Var("x"), Var("y")
    _expect(min_(x, y, Param("p")), lambda a, b: min(a, b, 1.25))
    _expect(max_(x, y), lambda a, b: max(a, b))
    # both operands in error: the leftmost error is the result
    _expect(Call("MAX", (x / y, sqrt(-1.0 + 0 * x))),
            lambda a, b: ExcelError.DIV0 if b == 0 else ExcelError.NUM)


def test_comparisons_follow_excels_order_of_types():
    x = Var("x")
    # any number is less than any text; text compares case-insensitively
    _expect(lt(x, "a"), lambda a, b: 1.0)
    assert _cells(compile_numpy(eq(Text("Ok"), Text("oK")))({}, {}, 2)) == [1.0, 1.0]
    result = compile_numpy(lt(x, 1.0))({"x": xm.array(np.array([0.0, 2.0]))}, {}, 2)
    assert result.boolean and _cells(result) == [1.0, 0.0]


def test_text_that_is_not_a_number_is_value():
    # "2"+1 = 3 but "ok"+1 = #VALUE! (Excel converts numeric text in arithmetic)
    assert _cells(compile_numpy(Text("2") + 1.0)({}, {}, 1)) == [3.0]
    assert _cells(compile_numpy(Text("ok") + 1.0)({}, {}, 1)) == [ExcelError.VALUE]


def test_compiled_is_cached_and_gives_the_same_bits():
    tree = sin(Var("x")) * Var("y") + atan2(Var("y"), Var("x"))
    assert compiled(tree) is compiled(tree)
    cols = {"x": xm.array(np.array(X)), "y": xm.array(np.array(Y))}
    a, b = compiled(tree)(cols, {}, N), compile_numpy(tree)(cols, {}, N)
    assert np.array_equal(a.err, b.err)
    assert np.array_equal(np.nan_to_num(a.val).view(np.int64),
                          np.nan_to_num(b.val).view(np.int64))
