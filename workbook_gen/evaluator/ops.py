"""Operators and functions over blocks of rows, with the scalar evaluator's semantics.

A block value is a :class:`NumBlock` (numbers or booleans with error codes: the fast path
through :mod:`workbook_gen.xlmath.kernels`), an :class:`ObjBlock` (a list of arbitrary
values: every element is computed by the scalar functions of ``formula.functions``), or a
:class:`Const` (one value, or a Range, for every row). Whatever the fast path cannot
prove equal to the scalar path goes element by element, so the two paths agree by
construction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from workbook_gen.xlmath import kernels as k
from workbook_gen.evaluator.store import NumBlock, ObjBlock, error_codes, to_items, with_nan
from workbook_gen.formula import functions as fx
from workbook_gen.formula import values as xv
from workbook_gen.formula.functions import coerce
from workbook_gen.formula.functions.registry import arity_ok
from workbook_gen.formula.scalar import Evaluator  # Excel's binary operators, the reference
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

_APPLY = {d: Evaluator(None, d, None).apply for d in ("excel", "libreoffice")}
_CONTEXT = {d: fx.Context(d) for d in ("excel", "libreoffice")}
_ARITH = frozenset("+-*/^")
_COMPARE = {"=": np.equal, "<>": np.not_equal, "<": np.less, ">": np.greater,
            "<=": np.less_equal, ">=": np.greater_equal}


@dataclass(slots=True)
class Const:
    """The same value (or Range) in every row."""

    value: object


def cell_call(name: str, args: list, dialect: str = "excel", cell=None):
    """``fx.call`` with its result cleaned as the scalar evaluator cleans it (overflow in
    MOD and SUM is #NUM! inside the functions themselves, for both paths)."""
    ctx = _CONTEXT[dialect] if cell is None else fx.Context(dialect, cell)
    return clean(fx.call(name, args, ctx))


def clean(v):
    """As the scalar evaluator: float results lose -0 and become #NUM! if not finite."""
    if isinstance(v, float):
        return ExcelError.NUM if not math.isfinite(v) else (0.0 if v == 0 else v)
    return v


@dataclass(slots=True)
class RefObj:
    """Per-row function results of which some are references (INDEX(A:A,0)): used as one
    value, row i intersects its reference with cell ``(sheet, first + i, col)``."""

    items: list
    origin: tuple[str, int, int]


def scalar(v, n: int):
    """A value used where one value is expected: a Range keeps its single cell, a
    reference of a row's result is intersected with that row."""
    if isinstance(v, Const) and isinstance(v.value, Range):
        rng = v.value
        if rng.ref is not None and rng.shape != (1, 1):
            raise fx.RowDependent(rng.ref)  # implicit intersection: a value per row
        return Const(xv.scalar_of(rng))
    if isinstance(v, RefObj):
        sheet, first, col = v.origin
        out = []
        for i, x in enumerate(v.items):
            if isinstance(x, Range):
                x = fx.Context(cell=(sheet, first + i, col)).scalar(x)
            out.append(x)
        return ObjBlock(out)
    return v


def is_num(v) -> bool:
    return isinstance(v, NumBlock)


def _full(value, n: int) -> NumBlock | None:
    if isinstance(value, ExcelError):
        return NumBlock(np.full(n, np.nan), np.full(n, value.code, np.uint8))
    if isinstance(value, bool):
        return NumBlock(np.full(n, float(value)), np.zeros(n, np.uint8), True)
    if isinstance(value, (int, float)):
        return NumBlock(np.full(n, float(value)), np.zeros(n, np.uint8))
    return None


def as_num(v, n: int) -> NumBlock | None:
    """``v`` as a NumBlock if it holds only numbers (or only booleans) and errors."""
    if isinstance(v, NumBlock):
        return v
    if isinstance(v, Const):
        return _full(v.value, n)
    kinds = set(map(type, v.items))
    if kinds == {float}:  # (C loops: the usual block)
        return NumBlock(np.array(v.items, float), np.zeros(len(v.items), np.uint8), False)
    kinds.discard(ExcelError)
    if kinds <= {float, int} or kinds == {bool}:
        return NumBlock(np.array(with_nan(v.items), float), error_codes(v.items), kinds == {bool})
    return None


def items(v, n: int, as_ref: bool = False) -> list:
    """Per-row Python values; ``as_ref`` wraps each in a 1x1 Range (a cell reference)."""
    if isinstance(v, Const):
        return [v.value] * n
    if isinstance(v, RefObj):
        return v.items
    out = to_items(v) if isinstance(v, NumBlock) else v.items
    return [Range(((x,),)) for x in out] if as_ref else out


def _obj(values: list) -> ObjBlock:
    return ObjBlock(values)


# -- operators --------------------------------------------------------------------------

def binary(op: str, a, b, n: int, dialect: str = "excel"):
    apply = _APPLY[dialect]
    if isinstance(a, Const) and isinstance(b, Const):
        return Const(apply(op, a.value, b.value))
    if op != "&":
        x, y = as_num(a, n), as_num(b, n)
        exact = dialect == "excel" or not (op == "^" or x is None or y is None
                                           or x.boolean or y.boolean)
        if x is not None and y is not None and exact:  # else LibreOffice's ^ and booleans
            if op in _ARITH:
                return NumBlock(*k.arith(op, x.val, x.err, y.val, y.err))
            return _compare(op, x, y, n)
    if isinstance(a, Const) or isinstance(b, Const):  # one side varies: memoise on it
        left = isinstance(a, Const)
        varying = items(b, n) if left else items(a, n)
        const = (a if left else b).value
        keys = list(zip(map(type, varying), varying))  # (1, 1.0 and TRUE apart)
        try:
            memo = {key: apply(op, const, key[1]) if left else apply(op, key[1], const)
                    for key in set(keys)}
        except TypeError:  # an unhashable value: one by one
            return _obj([apply(op, p, q) for p, q in zip(items(a, n), items(b, n))])
        return _obj(list(map(memo.__getitem__, keys)))
    return _obj([apply(op, p, q) for p, q in zip(items(a, n), items(b, n))])


def _compare(op: str, x: NumBlock, y: NumBlock, n: int) -> NumBlock:
    err = k.first_error(x.err, y.err)
    if x.boolean == y.boolean:
        with np.errstate(all="ignore"):
            result = _COMPARE[op](x.val, y.val)
    else:  # numbers sort before booleans
        c = -1 if y.boolean else 1
        result = np.full(n, bool(_COMPARE[op](c, 0)))
    return NumBlock(np.where(err != 0, np.nan, result.astype(float)), err, True)


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
            return NumBlock(*k.finish(-x.val, x.err))
        return NumBlock(*k.arith("/", x.val, x.err, np.full(n, 100.0), np.zeros(n, np.uint8)))
    return _obj([_unary_scalar(op, v) for v in items(a, n)])


# -- functions --------------------------------------------------------------------------

def _range_reduce(name: str, rng: Range):
    """A constant range argument of MIN/MAX: None (no numbers), its extreme, or an error."""
    xs = coerce.numbers([rng])
    if isinstance(xs, ExcelError):
        return xs
    return (min(xs) if name == "MIN" else max(xs)) if xs else None


def _fast_args(entry, args: list, refs: list, n: int, dialect: str) -> list[NumBlock] | None:
    """The arguments as NumBlocks when the fast path is exact for them, else None."""
    out = []
    skip_booleans = entry.range_numbers and dialect == "excel"
    for a, is_ref in zip(args, refs):
        if isinstance(a, Const) and isinstance(a.value, Range):
            rng = a.value
            if rng.shape == (1, 1) and isinstance(rng.rows[0][0], (float, ExcelError)):
                a = Const(rng.rows[0][0])
            elif entry.name in ("MIN", "MAX") and rng.shape != (1, 1):
                reduced = _range_reduce(entry.name, rng)
                if reduced is None:
                    continue
                a = Const(reduced)
            else:
                return None
        x = as_num(a, n)
        if x is None or (x.boolean and is_ref and skip_booleans):
            return None
        out.append(x)
    return out


def call(name: str, args: list, refs: list, n: int, dialect: str = "excel",
         origin: tuple[str, int, int] | None = None):
    """The eager function ``name`` on block arguments (``refs``: which are references):
    the registry's vectorised form where it is exact, else the scalar form per row."""
    entry = fx.REGISTRY[name]
    if entry.vector is not None and arity_ok(entry, len(args)) and (
            dialect == "excel" or name not in fx.dialect.NUMERIC_DEVIATIONS):
        xs = _fast_args(entry, args, refs, n, dialect)
        if xs is not None:
            if not xs:  # every argument a constant range without numbers
                return Const(cell_call(name, [a.value for a in args], dialect))
            val, err, boolean = entry.vector([(x.val, x.err) for x in xs], n)
            return NumBlock(val, err, boolean)
    if not args:
        return Const(cell_call(name, [], dialect))
    columns = [items(a, n, as_ref=(r is True)) for a, r in zip(args, refs)]
    if origin is None:
        out = [cell_call(name, list(row), dialect) for row in zip(*columns)]
    else:
        sheet, first, col = origin
        out = [cell_call(name, list(row), dialect, (sheet, first + i, col))
               for i, row in enumerate(zip(*columns))]
    if origin is not None and any(isinstance(x, Range) for x in out):
        return RefObj(out, origin)
    return _obj(out)


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
        return NumBlock(val, err, x.boolean)
    # per row, in C loops: object arrays hold the very values (text, numbers, ranges)
    out = np.where(pick, np.fromiter(items(then, n), object, n),
                   np.fromiter(items(other, n), object, n))
    for i in np.flatnonzero(cerr).tolist():
        out[i] = ExcelError.from_code(int(cerr[i]))
    return _obj(out.tolist())
