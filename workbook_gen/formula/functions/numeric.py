"""Numeric arguments for the functions computed by mpmath: each argument converted to a
number (or the first error returned), the computation at :data:`DPS` digits, the result a
safe float; and COMBIN's and PERMUT's whole-number pair. Shared by the statistical,
engineering, math and financial families."""

from __future__ import annotations

import mpmath

from workbook_gen.formula.functions import coerce as c
from workbook_gen.xlerror import ExcelError

DPS = 30


def args_of(*vs, booleans: bool = True):
    """Scalar arguments as numbers (booleans and numeric text convert), or the first error.
    ``booleans=False``: a boolean is #VALUE!, as in the engineering functions that came
    from Excel's Analysis ToolPak (formulas test.xlsx: BESSELI(TRUE,1), ERF(TRUE))."""
    out = []
    for v in vs:
        if not booleans and isinstance(v, bool):
            return ExcelError.VALUE
        x = c.to_number(v)
        if isinstance(x, ExcelError):
            return x
        out.append(x)
    return out


def flag(v):
    return c.to_bool(v)


def numeric(fn):
    """Wrap ``fn(*floats)`` -> float | ExcelError: arguments converted, mpmath at DPS digits,
    the result a safe float."""
    def wrapped(ctx, *vs):
        xs = args_of(*vs)
        if isinstance(xs, ExcelError):
            return xs
        with mpmath.workdps(DPS):
            try:
                r = fn(*xs)
            except (ValueError, ZeroDivisionError, OverflowError):
                return ExcelError.NUM
        return r if isinstance(r, ExcelError) else c.result(float(r))
    return wrapped


def with_flag(fn, dialect: bool = False):
    """As :func:`numeric` where the last argument is a boolean (cumulative, tails...);
    ``dialect``: ``fn`` also takes ``dialect=`` ("excel" or "libreoffice")."""
    def wrapped(ctx, *vs):
        *vals, last = vs
        b = flag(last)
        if isinstance(b, ExcelError):
            return b
        xs = args_of(*vals)
        if isinstance(xs, ExcelError):
            return xs
        with mpmath.workdps(DPS):
            try:
                r = fn(*xs, b, dialect=ctx.dialect) if dialect else fn(*xs, b)
            except (ValueError, ZeroDivisionError, OverflowError):
                return ExcelError.NUM
        return r if isinstance(r, ExcelError) else c.result(float(r))
    return wrapped


def choices(count):
    """COMBIN and PERMUT: ``count(n, r)`` of whole n and r; #NUM! unless 0 <= r <= n."""
    def scalar(ctx, n, r):
        n, r = c.integer(n), c.integer(r)
        bad = c.first_error((n, r))
        if bad is not None:
            return bad
        return ExcelError.NUM if n < 0 or r < 0 or r > n else c.result(float(count(n, r)))
    return scalar
