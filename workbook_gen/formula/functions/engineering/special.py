"""The error function and the steps: ERF, ERF.PRECISE, ERFC (.PRECISE) by mpmath at 30
digits, rounded to a float; DELTA, GESTEP."""

from __future__ import annotations

import operator

import mpmath

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.numeric import DPS, args_of, numeric
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError


@register("ERF", 1, 2)
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


register("ERF.PRECISE", 1, 1)(_no_bool(numeric(mpmath.erf)))
register("ERFC", 1, 1, aliases=("ERFC.PRECISE",))(_no_bool(numeric(mpmath.erfc)))


def _step(name, test):
    """DELTA (1 where a = b) and GESTEP (1 where a >= b); b is 0 by default."""
    def scalar(ctx, a, b=0.0):
        if isinstance(a, bool) or isinstance(b, bool):
            return ExcelError.VALUE  # no booleans (formulas test.xlsx ENGINEERING!Y20, Y25)
        x, y = c.to_number(a), c.to_number(b)
        for v in (x, y):
            if isinstance(v, ExcelError):
                return v
        return 1.0 if test(x, y) else 0.0
    register(name, 1, 2)(scalar)


_step("DELTA", operator.eq)
_step("GESTEP", operator.ge)
