"""The reciprocal trigonometric functions: COT, CSC, SEC and their hyperbolic forms, ACOT,
ACOTH."""

from __future__ import annotations

import math

from workbook_gen.formula.functions.numeric import numeric
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError


def _recip(fn, limit=2 ** 27):
    def f(x):
        if abs(x) >= limit:
            return ExcelError.NUM
        d = fn(x)
        return ExcelError.DIV0 if d == 0 else 1 / d
    return numeric(f)


register("COT", 1, 1)(_recip(math.tan))
register("CSC", 1, 1)(_recip(math.sin))
register("SEC", 1, 1)(_recip(math.cos))
register("COTH", 1, 1)(_recip(math.tanh, float("inf")))
register("CSCH", 1, 1)(_recip(math.sinh, float("inf")))
register("SECH", 1, 1)(_recip(math.cosh, float("inf")))
register("ACOT", 1, 1)(numeric(lambda x: math.pi / 2 - math.atan(x)))
register("ACOTH", 1, 1)(numeric(
    lambda x: ExcelError.NUM if abs(x) <= 1 else 0.5 * math.log((x + 1) / (x - 1))))
