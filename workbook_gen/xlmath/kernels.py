"""Excel's operators and math functions over float arrays with uint8 error codes.

The vector path must give the same bits as the scalar reference (``formula.scalar``),
which uses Python's ``math`` (the C library). numpy's ufuncs are used for a function
only where they give the same bits as the C library on a probe run at import
(usually sin, cos, sqrt, atan2); elsewhere (pow, tan, asin, ... on builds with SIMD
versions) the C library function is mapped over the array. Error codes follow
``xlmath``: 0 is no error, else ``ExcelError.code``; error entries hold NaN.
Shared by ``xlmath`` (cached values) and the formula evaluator.
"""

from __future__ import annotations

import math

import numpy as np

from workbook_gen.xlerror import TRIG_LIMIT, ExcelError

NUM = ExcelError.NUM.code
DIV0 = ExcelError.DIV0.code
# TRIG_LIMIT (xlerror.py): SIN, COS, TAN give #NUM! from there on (scalar ones too)


def _safe(fn):
    def call(*xs):
        try:
            return fn(*xs)
        except (OverflowError, ValueError):
            return math.nan
    return call


def _probe_points() -> np.ndarray:
    rng = np.random.default_rng(20240601)
    return np.concatenate([rng.uniform(-1, 1, 2000), rng.uniform(-50, 50, 2000),
                           rng.standard_normal(2000) * 10.0 ** rng.uniform(-8, 8, 2000)])


def _exact(np_fn, py_fn, arity: int):
    """``np_fn`` if it matches ``py_fn`` bit for bit on the probe, else ``py_fn`` mapped."""
    mapped = np.frompyfunc(_safe(py_fn), arity, 1)

    def by_libm(*xs):
        if xs[0].size == 0:
            return np.empty(0)
        with np.errstate(all="ignore"):
            return mapped(*xs).astype(float)

    p = _probe_points()
    args = (p,) if arity == 1 else (np.abs(p), p[::-1] / 7.0)
    with np.errstate(all="ignore"):
        fast = np_fn(*args)
    # Only finite results count: ``finish`` makes inf and NaN alike #NUM! (numpy's pow
    # overflows to inf where math.pow raises), so they need not agree there.
    slow = by_libm(*args)
    fast, slow = (np.where(np.isfinite(v), v, np.nan) for v in (fast, slow))
    same = np.array_equal(fast, slow, equal_nan=True)
    return np_fn if same else by_libm


SIN = _exact(np.sin, math.sin, 1)
COS = _exact(np.cos, math.cos, 1)
TAN = _exact(np.tan, math.tan, 1)
ASIN = _exact(np.arcsin, math.asin, 1)
ACOS = _exact(np.arccos, math.acos, 1)
ATAN = _exact(np.arctan, math.atan, 1)
SQRT = _exact(np.sqrt, math.sqrt, 1)
POW = _exact(np.power, math.pow, 2)
ATAN2_YX = _exact(np.arctan2, math.atan2, 2)


# ``np.count_nonzero`` is a C call; ``ndarray.any()`` goes through Python (numpy's
# _methods), several times the cost on the short columns of a workbook.
_count = np.count_nonzero


def first_error(*errs: np.ndarray) -> np.ndarray:
    """Per element, the error of the leftmost operand that has one (a new array)."""
    if len(errs) == 2 and not _count(errs[0]):  # the common case: a clean left operand
        return errs[1].astype(np.uint8)
    out = errs[-1].copy()
    for e in reversed(errs[:-1]):
        out = np.where(e != 0, e, out)
    return out.astype(np.uint8)


def finish(val: np.ndarray, err: np.ndarray, fresh=None, code: int = NUM):
    """Fresh ``code`` where ``fresh`` and no earlier error; inf/NaN -> #NUM!; no -0."""
    if (fresh is None or not _count(fresh)) and not _count(err) \
            and _count(np.isfinite(val)) == val.size:
        return val + 0.0, err.copy()  # nothing to mark: the same values and codes
    err = err.copy()
    if fresh is not None:
        err[(err == 0) & fresh] = code
    err[(err == 0) & ~np.isfinite(val)] = NUM
    return np.where(err != 0, np.nan, val + 0.0), err


def _on_valid(fn, mask: np.ndarray, *xs: np.ndarray) -> np.ndarray:
    """``fn`` applied only where ``mask`` (NaN elsewhere): the C library path is slow."""
    out = np.full(mask.shape, np.nan)
    if mask.all():
        return fn(*xs)
    if mask.any():
        out[mask] = fn(*(x[mask] for x in xs))
    return out


def arith(op: str, x, ex, y, ey):
    """``+ - * / ^`` with Excel's errors (leftmost error first)."""
    err = first_error(ex, ey)
    with np.errstate(all="ignore"):
        if op == "+":
            return finish(x + y, err)
        if op == "-":
            return finish(x - y, err)
        if op == "*":
            return finish(x * y, err)
        if op == "/":
            return finish(x / y, err, y == 0, DIV0)
        return power(x, y, err)


def power(x, y, err):
    """Excel's ^: 0^0 #NUM!, 0^negative #DIV/0!, negative^fraction #NUM!."""
    with np.errstate(all="ignore"):
        zero = x == 0
        err = err.copy()
        err[(err == 0) & zero & (y < 0)] = DIV0
        err[(err == 0) & ((zero & (y == 0)) | ((x < 0) & (np.floor(y) != y)))] = NUM
        ok = err == 0
        val = _on_valid(POW, ok & ~zero, x, y)
        val = np.where(zero & ok, 0.0, val)
    return finish(val, err)


def _trig(fn):
    def apply(x):
        return _on_valid(fn, np.abs(x) < TRIG_LIMIT, x)
    return apply


def _domain(fn, lo, hi):
    def apply(x):
        return _on_valid(fn, (x >= lo) & (x <= hi), x)
    return apply


UNARY = {
    "SIN": _trig(SIN), "COS": _trig(COS), "TAN": _trig(TAN),
    "ASIN": _domain(ASIN, -1.0, 1.0), "ACOS": _domain(ACOS, -1.0, 1.0),
    "ATAN": ATAN, "SQRT": _domain(SQRT, 0.0, math.inf),
    "ABS": np.abs, "SIGN": np.sign,
    "RADIANS": lambda x: x * (math.pi / 180.0),   # as math.radians
    "DEGREES": lambda x: x * (180.0 / math.pi),   # as math.degrees
}


def unary(name: str, x, ex):
    """One-argument math function; a domain failure (NaN) becomes #NUM!."""
    with np.errstate(all="ignore"):
        x = np.where(ex != 0, 0.0, x)
        return finish(UNARY[name](x), ex)


def atan2(x, ex, y, ey):
    """Excel's ATAN2(x, y): x first; (0, 0) is #DIV/0!."""
    err = first_error(ex, ey)
    err[(err == 0) & (x == 0) & (y == 0)] = DIV0
    return finish(_on_valid(ATAN2_YX, err == 0, y, x), err)


def mod(x, ex, y, ey):
    """MOD(n, d) = n - d*INT(n/d)."""
    with np.errstate(all="ignore"):
        return finish(x - y * np.floor(x / y), first_error(ex, ey), y == 0, DIV0)


def fsum_rows(vals: list[np.ndarray], err: np.ndarray) -> np.ndarray:
    """Row-wise ``math.fsum`` (correctly rounded, as SUM in the scalar path)."""
    if len(vals) <= 2:
        return vals[0] + vals[1] if len(vals) == 2 else vals[0] + 0.0
    out = np.full(err.shape, np.nan)
    rows = np.stack(vals, axis=1)
    for i in np.flatnonzero(err == 0):
        try:
            out[i] = math.fsum(rows[i])
        except OverflowError:
            out[i] = np.nan
    return out
