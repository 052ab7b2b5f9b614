"""expr/precise.py: the mpmath printer evaluates a tree at the caller's precision (50
digits here; the columns it reads are mpf, as the 50-digit reference makes them) as
mpmath does the same arithmetic directly, and with Excel's domain
errors: SQRT of a negative, ASIN beyond 1, x/0, 0^0, ATAN2(0,0), MOD(x,0)."""

from __future__ import annotations

import random

import mpmath
import pytest

from workbook_gen.expr import Param, Var
from workbook_gen.expr import build as b
from workbook_gen.expr.precise import compile_mpmath
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)
X, Y, K = Var("x"), Var("y"), Param("k")


def test_fifty_digits_as_mpmath():
    tree = b.atan2(X, Y) * K + b.sqrt(b.abs_(X)) - b.sin(b.radians(Y)) / (1 + X * X) \
        + b.power(b.abs_(Y) + 1, K) + b.mod(X, 0.7)
    f = compile_mpmath(tree)
    with mpmath.workdps(50):
        for _ in range(50):
            x, y, k = (RNG.uniform(-5, 5) for _ in range(3))
            mx, my, mk = mpmath.mpf(x), mpmath.mpf(y), mpmath.mpf(k)
            got = f({"x": mx, "y": my}, {"k": k})   # columns arrive as mpf, parameters float
            want = (mpmath.atan2(my, mx) * mk + mpmath.sqrt(abs(mx))
                    - mpmath.sin(my * mpmath.pi / 180) / (1 + mx * mx)
                    + mpmath.power(abs(my) + 1, mk) + (mx - mpmath.mpf(0.7)
                                                       * mpmath.floor(mx / mpmath.mpf(0.7))))
            assert abs(got - want) <= mpmath.mpf(10) ** -45 * max(1, abs(want)), (x, y, k)


@pytest.mark.parametrize("tree, values, error", [
    (b.sqrt(X), {"x": -1.0}, ExcelError.NUM),
    (b.asin(X), {"x": 1.5}, ExcelError.NUM),
    (X / Y, {"x": 1.0, "y": 0.0}, ExcelError.DIV0),
    (b.power(X, Y), {"x": 0.0, "y": 0.0}, ExcelError.NUM),
    (b.atan2(X, Y), {"x": 0.0, "y": 0.0}, ExcelError.DIV0),
    (b.mod(X, Y), {"x": 3.0, "y": 0.0}, ExcelError.DIV0),
    (b.sqrt(X) + 1, {"x": -4.0}, ExcelError.NUM),            # the error travels up
])
def test_excels_errors(tree, values, error):
    with mpmath.workdps(50):
        assert compile_mpmath(tree)(values, {}) == error
    assert compile_mpmath(b.iferror(tree, 7))(values, {}) == 7
