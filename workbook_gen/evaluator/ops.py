"""Operators and functions over blocks of rows, with the scalar evaluator's semantics.

A block value is a :class:`Num` (numbers or booleans with error codes: the fast path
through :mod:`workbook_gen.xlmath.kernels`), an :class:`Obj` (a list of arbitrary values: every element is
computed by the scalar functions of ``formula.functions``), or a :class:`Const` (one
value, or a Range, for every row). Whatever the fast path cannot prove equal to the
scalar path goes element by element, so the two paths agree by construction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from workbook_gen.xlmath import kernels as k
from workbook_gen.evaluator.store import Num, Obj, to_items
from workbook_gen.formula import functions as fx
from workbook_gen.formula import values as xv
from workbook_gen.formula.scalar import Evaluator  # Excel's binary operators, the reference
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

_APPLY = Evaluator(None, "excel", None).apply
_ARITH = frozenset("+-*/^")
_COMPARE = {"=": np.equal, "<>": np.not_equal, "<": np.less, ">": np.greater,
            "<=": np.less_equal, ">=": np.greater_equal}
_MATH2 = {"ATAN2": lambda x, ex, y, ey: k.atan2(x, ex, y, ey), "MOD": k.mod,
          "POWER": lambda x, ex, y, ey: k.power(x, y, k.first_error(ex, ey))}


@dataclass(slots=True)
class Const:
    """The same value (or Range) in every row."""

    value: object


def cell_call(name: str, args: list):
    """``fx.call`` with its result cleaned as the scalar evaluator cleans it (overflow in
    MOD and SUM is #NUM! inside the functions themselves, for both paths)."""
    return clean(fx.call(name, args))


def clean(v):
    """As the scalar evaluator: float results lose -0 and become #NUM! if not finite."""
    if isinstance(v, float):
        return ExcelError.NUM if not math.isfinite(v) else (0.0 if v == 0 else v)
    return v


def scalar(v, n: int):
    """A value used where one value is expected: a Range keeps its single cell."""
    if isinstance(v, Const) and isinstance(v.value, Range):
        return Const(xv.scalar_of(v.value))
    return v


def is_num(v) -> bool:
    return isinstance(v, Num)


def _full(value, n: int) -> Num | None:
    if isinstance(value, ExcelError):
        return Num(np.full(n, np.nan), np.full(n, value.code, np.uint8))
    if isinstance(value, bool):
        return Num(np.full(n, float(value)), np.zeros(n, np.uint8), True)
    if isinstance(value, (int, float)):
        return Num(np.full(n, float(value)), np.zeros(n, np.uint8))
    return None


def as_num(v, n: int) -> Num | None:
    """``v`` as a Num block if it holds only numbers (or only booleans) and errors."""
    if isinstance(v, Num):
        return v
    if isinstance(v, Const):
        return _full(v.value, n)
    kinds = {type(x) for x in v.items}
    kinds.discard(ExcelError)
    if kinds <= {float, int} or kinds == {bool}:
        boolean = kinds == {bool}
        val = np.array([np.nan if isinstance(x, ExcelError) else float(x) for x in v.items])
        err = np.array([x.code if isinstance(x, ExcelError) else 0 for x in v.items], np.uint8)
        return Num(val, err, boolean)
    return None


def items(v, n: int, as_ref: bool = False) -> list:
    """Per-row Python values; ``as_ref`` wraps each in a 1x1 Range (a cell reference)."""
    if isinstance(v, Const):
        return [v.value] * n
    out = to_items(v) if isinstance(v, Num) else v.items
    return [Range(((x,),)) for x in out] if as_ref else out


def _obj(values: list) -> Obj:
    return Obj(values)


# -- operators --------------------------------------------------------------------------

def binary(op: str, a, b, n: int):
    if isinstance(a, Const) and isinstance(b, Const):
        return Const(_APPLY(op, a.value, b.value))
    if op != "&":
        x, y = as_num(a, n), as_num(b, n)
        if x is not None and y is not None:
            if op in _ARITH:
                return Num(*k.arith(op, x.val, x.err, y.val, y.err))
            return _compare(op, x, y, n)
    if isinstance(a, Const) or isinstance(b, Const):  # one side varies: memoise on it
        memo: dict = {}
        out = []
        for p, q in zip(items(a, n), items(b, n)):
            key = (type(p), p, type(q), q)
            if key not in memo:
                memo[key] = _APPLY(op, p, q)
            out.append(memo[key])
        return _obj(out)
    return _obj([_APPLY(op, p, q) for p, q in zip(items(a, n), items(b, n))])


def _compare(op: str, x: Num, y: Num, n: int) -> Num:
    err = k.first_error(x.err, y.err)
    if x.boolean == y.boolean:
        with np.errstate(all="ignore"):
            result = _COMPARE[op](x.val, y.val)
    else:  # numbers sort before booleans
        c = -1 if y.boolean else 1
        result = np.full(n, bool(_COMPARE[op](c, 0)))
    return Num(np.where(err != 0, np.nan, result.astype(float)), err, True)


def _unary_scalar(op: str, v):
    if op == "+":
        return v
    x = xv.to_number(v)
    if isinstance(x, ExcelError):
        return x
    return clean(-x) if op == "-" else clean(x / 100.0)


def unary(op: str, a, n: int):
    """Prefix ``-``/``+`` and postfix ``%``."""
    if op == "+":
        return a
    if isinstance(a, Const):
        return Const(_unary_scalar(op, a.value))
    x = as_num(a, n)
    if x is not None:
        if op == "-":
            return Num(*k.finish(-x.val, x.err))
        return Num(*k.arith("/", x.val, x.err, np.full(n, 100.0), np.zeros(n, np.uint8)))
    return _obj([_unary_scalar(op, v) for v in items(a, n)])


# -- functions --------------------------------------------------------------------------

def _range_reduce(name: str, rng: Range):
    """A constant range argument of MIN/MAX: None (no numbers), its extreme, or an error."""
    xs = fx._aggregate_numbers([rng])
    if isinstance(xs, ExcelError):
        return xs
    return (min(xs) if name == "MIN" else max(xs)) if xs else None


def _fast_args(name: str, args: list, refs: list, n: int) -> list[Num] | None:
    """The arguments as Num blocks when the fast path is exact for them, else None."""
    out = []
    for a, is_ref in zip(args, refs):
        if isinstance(a, Const) and isinstance(a.value, Range):
            rng = a.value
            if rng.shape == (1, 1) and isinstance(rng.rows[0][0], (float, ExcelError)):
                a = Const(rng.rows[0][0])
            elif name in ("MIN", "MAX") and rng.shape != (1, 1):
                reduced = _range_reduce(name, rng)
                if reduced is None:
                    continue
                a = Const(reduced)
            else:
                return None
        x = as_num(a, n)
        if x is None or (x.boolean and is_ref and name in ("MIN", "MAX", "SUM")):
            return None
        out.append(x)
    return out


def call(name: str, args: list, refs: list, n: int):
    """The eager function ``name`` on block arguments (``refs``: which are references)."""
    xs = _fast_args(name, args, refs, n)
    if xs is not None:
        result = _fast_call(name, xs, len(args), n)
        if result is not None:
            return result
    if not args:
        return Const(cell_call(name, []))
    columns = [items(a, n, as_ref=(r is True)) for a, r in zip(args, refs)]
    return _obj([cell_call(name, list(row)) for row in zip(*columns)])


def _fast_call(name: str, xs: list[Num], nargs: int, n: int):
    if name in k.UNARY and nargs == 1 == len(xs):
        return Num(*k.unary(name, xs[0].val, xs[0].err))
    if name in _MATH2 and nargs == 2 == len(xs):
        (a, b) = xs
        return Num(*_MATH2[name](a.val, a.err, b.val, b.err))
    if name == "NOT" and nargs == 1:
        x = xs[0]
        return Num(np.where(x.err != 0, np.nan, (x.val == 0).astype(float)), x.err, True)
    if name == "ISERROR" and nargs == 1:
        return Num((xs[0].err != 0).astype(float), np.zeros(n, np.uint8), True)
    if name in ("AND", "OR") and xs and len(xs) == nargs:
        err = k.first_error(*(x.err for x in xs))
        truth = np.array([x.val != 0 for x in xs])
        val = truth.all(axis=0) if name == "AND" else truth.any(axis=0)
        return Num(np.where(err != 0, np.nan, val.astype(float)), err, True)
    if name in ("MIN", "MAX", "SUM") and nargs:
        if not xs:
            return Const(0.0)
        err = k.first_error(*(x.err for x in xs))
        vals = [x.val for x in xs]
        if name == "SUM":
            val = k.fsum_rows(vals, err)
        else:
            val = (np.minimum if name == "MIN" else np.maximum).reduce(np.array(vals), axis=0)
        return Num(*k.finish(val, err))
    return None


def to_bool_mask(cond, n: int) -> tuple[np.ndarray, np.ndarray]:
    """IF's condition per row: (true?, error code)."""
    x = as_num(cond, n)
    if x is not None:
        return (x.val != 0) & (x.err == 0), x.err
    bools = [xv.to_bool(v) for v in items(cond, n)]
    err = np.array([b.code if isinstance(b, ExcelError) else 0 for b in bools], np.uint8)
    return np.array([b is True for b in bools], bool), err


def choose(pick: np.ndarray, cerr: np.ndarray, then, other, n: int):
    """Per row: ``then`` where ``pick``, else ``other``; a condition error wins."""
    x, y = as_num(then, n), as_num(other, n)
    if x is not None and y is not None and x.boolean == y.boolean:
        err = np.where(cerr != 0, cerr, np.where(pick, x.err, y.err)).astype(np.uint8)
        val = np.where(err != 0, np.nan, np.where(pick, x.val, y.val))
        return Num(val, err, x.boolean)
    out = []
    for e, p, a, b in zip(cerr.tolist(), pick.tolist(), items(then, n), items(other, n)):
        out.append(ExcelError.from_code(e) if e else (a if p else b))
    return _obj(out)
