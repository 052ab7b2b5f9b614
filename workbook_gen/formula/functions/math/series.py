"""MULTINOMIAL, SERIESSUM and SEQUENCE (Excel 365: an array of evenly spaced numbers)."""

from __future__ import annotations

import math

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.arrayargs import (
    MAX_CELLS, OMITTED, array_result, whole_arg, whole_args,
)
from workbook_gen.formula.functions.numeric import args_of
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError


@register("MULTINOMIAL", 1, -1, "range")
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


@register("SERIESSUM", 4, 4, ("scalar", "scalar", "scalar", "range"))
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


@register("SEQUENCE", 1, 4)
def _sequence(ctx, rows, cols=OMITTED, start=OMITTED, step=OMITTED):
    n = whole_args(whole_arg(rows, 1), whole_arg(cols, 1))
    if isinstance(n, ExcelError):
        return n
    first = 1.0 if start is OMITTED else c.number(start)
    by = 1.0 if step is OMITTED else c.number(step)
    for v in (first, by):
        if isinstance(v, ExcelError):
            return v
    r, k = n
    if r < 1 or k < 1:
        return ExcelError.CALC if r == 0 or k == 0 else ExcelError.VALUE
    if r * k > MAX_CELLS:
        return ExcelError.NUM
    return array_result([[first + by * (i * k + j) for j in range(k)] for i in range(r)])
