"""Excel's arithmetic and functions over numpy arrays, with error masks.

The numeric kernels (``kernels.py``: which C-library or numpy function, the
domains, the error codes) are shared with the formula evaluator, so a cached
value and its recomputation come from the same bits.

A column of values is an ``XArray``: ``val`` (float64, or object for text)
and ``err`` (uint8, 0 = no error, else ``ExcelError.code``).  Errors
propagate as in Excel: the leftmost operand's error wins, and a fresh error
appears only where the operands had none.  Error entries hold NaN in ``val``.

This module knows nothing of mechanisms or xlsx files; it is the numeric
core shared by the tree printer (cached values) and the formula evaluator.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..xlerror import ExcelError
from . import kernels

NUM = ExcelError.NUM.code
DIV0 = ExcelError.DIV0.code
VALUE = ExcelError.VALUE.code


@dataclass(frozen=True, slots=True)
class XArray:
    val: np.ndarray
    err: np.ndarray
    boolean: bool = False  # TRUE/FALSE held as 1.0/0.0 (they compare above all numbers)

    @property
    def is_text(self) -> bool:
        return self.val.dtype == object

    def errors(self) -> list[ExcelError | None]:
        return [ExcelError.from_code(int(c)) if c else None for c in self.err]


def const(value: float | str, n: int) -> XArray:
    """A column of ``n`` copies of a literal."""
    if isinstance(value, str):
        val = np.full(n, value, dtype=object)
    else:
        val = np.full(n, float(value))
    return XArray(val, np.zeros(n, np.uint8))


def array(values: np.ndarray) -> XArray:
    values = np.asarray(values, dtype=float)
    return _finish(values, np.zeros(values.shape, np.uint8))


_first_error = kernels.first_error


def _finish(val: np.ndarray, err: np.ndarray, fresh: np.ndarray | None = None,
            code: int = NUM, boolean: bool = False) -> XArray:
    """Apply a fresh error ``code`` where ``fresh``; non-finite results are #NUM!;
    Excel has no negative zero (ATAN2(-60, -0) must be +pi)."""
    if val.dtype == object:
        err = err.copy()
        if fresh is not None:
            err[(err == 0) & fresh] = code
        return XArray(val, err, boolean)
    val, err = kernels.finish(val, err, fresh, code)
    return XArray(val, err, boolean)


def _num(a: XArray) -> tuple[np.ndarray, np.ndarray]:
    """Numeric view of an operand: text that is not a number is #VALUE!."""
    if not a.is_text:
        return a.val, a.err
    val = np.full(a.val.shape, np.nan)
    err = a.err.copy()
    for i, v in enumerate(a.val):
        if err[i]:
            continue
        try:
            val[i] = float(v) if v != "" else np.nan
        except (TypeError, ValueError):
            val[i] = np.nan
        if np.isnan(val[i]):
            err[i] = VALUE
    return val, err


def _arith(op: str):
    def apply(a: XArray, b: XArray) -> XArray:
        (x, ex), (y, ey) = _num(a), _num(b)
        return XArray(*kernels.arith(op, x, ex, y, ey))
    return apply


add, sub, mul, div = _arith("+"), _arith("-"), _arith("*"), _arith("/")
power = _arith("^")  # 0^0 and a negative base with a fraction: #NUM!; 0^-1: #DIV/0!


def neg(a: XArray) -> XArray:
    x, ex = _num(a)
    return _finish(-x, ex)


def _unary(name: str):
    def apply(a: XArray) -> XArray:
        x, ex = _num(a)
        return XArray(*kernels.unary(name, x, ex))
    apply.__name__ = name.lower()
    return apply


(sin, cos, tan, atan, abs_, sign, radians, degrees, asin, acos, sqrt) = (
    _unary(n) for n in ("SIN", "COS", "TAN", "ATAN", "ABS", "SIGN", "RADIANS", "DEGREES",
                        "ASIN", "ACOS", "SQRT"))


def atan2(a: XArray, b: XArray) -> XArray:
    """Excel's ATAN2(x, y): the angle of (x, y); ATAN2(0, 0) is #DIV/0!."""
    (x, ex), (y, ey) = _num(a), _num(b)
    return XArray(*kernels.atan2(x, ex, y, ey))


def mod(a: XArray, b: XArray) -> XArray:
    """Excel's MOD: n - d*INT(n/d), with the sign of the divisor."""
    (x, ex), (y, ey) = _num(a), _num(b)
    return XArray(*kernels.mod(x, ex, y, ey))


def compare(op: str, a: XArray, b: XArray) -> XArray:
    """Excel's comparison: numbers < text < booleans; text compares case-insensitively."""
    err = _first_error(a.err, b.err)
    ops = {"=": np.equal, "<>": np.not_equal, "<": np.less, ">": np.greater,
           "<=": np.less_equal, ">=": np.greater_equal}
    fn = ops[op]
    if a.is_text or b.is_text:
        result = [bool(fn(_Key(x, a.boolean), _Key(y, b.boolean))) if not (ex or ey) else False
                  for x, y, ex, ey in zip(a.val, b.val, a.err, b.err)]
    elif a.boolean != b.boolean:  # a boolean against a number: the type decides
        rank = (int(a.boolean) > int(b.boolean)) - (int(a.boolean) < int(b.boolean))
        result = np.full(a.val.shape, bool(fn(rank, 0)))
    else:
        with np.errstate(all="ignore"):
            result = fn(a.val, b.val)
    return _finish(np.asarray(result, dtype=float), err, boolean=True)


class _Key:
    """Excel's order of values: numbers before text; text compares case-insensitively."""

    __slots__ = ("rank", "value")

    def __init__(self, value: object, boolean: bool = False):
        if isinstance(value, str):
            self.rank, self.value = 1, value.casefold()
        else:
            self.rank, self.value = (2 if boolean else 0), float(value)

    def __eq__(self, other): return (self.rank, self.value) == (other.rank, other.value)
    def __ne__(self, other): return not self == other
    def __lt__(self, other): return (self.rank, self.value) < (other.rank, other.value)
    def __gt__(self, other): return other < self
    def __le__(self, other): return not other < self
    def __ge__(self, other): return not self < other



def where(cond: XArray, then: XArray, otherwise: XArray) -> XArray:
    """IF: the chosen branch's value and error; an error condition wins."""
    c, ec = _num(cond)
    pick = (c != 0) & (ec == 0)
    if then.is_text or otherwise.is_text:
        val = np.where(pick, then.val.astype(object), otherwise.val.astype(object))
    else:
        val = np.where(pick, then.val, otherwise.val)
    err = np.where(ec != 0, ec, np.where(pick, then.err, otherwise.err)).astype(np.uint8)
    if val.dtype == object:
        val[err != 0] = None
        return XArray(val, err)
    return _finish(val, err, boolean=then.boolean and otherwise.boolean)


def iserror(a: XArray) -> XArray:
    return XArray((a.err != 0).astype(float), np.zeros(a.err.shape, np.uint8), True)


def iferror(a: XArray, fallback: XArray) -> XArray:
    bad = XArray((a.err == 0).astype(float), np.zeros(a.err.shape, np.uint8))
    return where(bad, a, fallback)


def logical(fn, *args: XArray) -> XArray:
    """AND / OR over row-aligned arguments."""
    vals = [_num(a) for a in args]
    err = _first_error(*(e for _, e in vals))
    result = fn.reduce(np.array([v != 0 for v, _ in vals]), axis=0)
    return _finish(result.astype(float), err, boolean=True)


def not_(a: XArray) -> XArray:
    x, ex = _num(a)
    return _finish((x == 0).astype(float), ex, boolean=True)


def extreme(fn, *args: XArray) -> XArray:
    """MIN / MAX over row-aligned arguments."""
    vals = [_num(a) for a in args]
    err = _first_error(*(e for _, e in vals))
    return _finish(fn.reduce(np.array([v for v, _ in vals]), axis=0), err)
