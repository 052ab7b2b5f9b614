"""Compile a formula, as seen from the first row of a column block, to a numpy function.

``compile_block(node, sheet, col, first, last)`` returns a :class:`Block` whose
``run(env)`` gives every row's value at once. The formula's references are classified:
- a row-relative cell reference is an array slice of another column (``env.block``);
- any sub-expression that is the same for every row (literals, ``$``-rows, defined
  names, absolute ranges and everything built only from them) is computed once by the
  scalar evaluator and broadcast;
- relative ranges and references into the block's own rows are refused
  (:class:`NotVectorizable`): the caller evaluates those cells one by one.
Numbers and errors go through :mod:`workbook_gen.xlmath.kernels` (bit-identical to the scalar path);
blocks holding text, booleans or empties fall back per element to the scalar
functions (``formula.functions``), so the semantics are the scalar evaluator's.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from workbook_gen.evaluator.ops import (
    Const, NumBlock, binary, call, choose, is_num, scalar, to_bool_mask, unary,
)
from workbook_gen.evaluator.store import NumBlock, value_scale
from workbook_gen.formula import ast
from workbook_gen.formula import functions as fx
from workbook_gen.formula.functions.math.subtotal import READS_LAYOUT
from workbook_gen.formula.values import to_bool


class NotVectorizable(Exception):
    """This formula must be evaluated cell by cell."""


def _ref_sensitive(name: str) -> bool:
    """Does the function treat a reference argument unlike its value (SUM skips text)?"""
    entry = fx.REGISTRY.get(name)
    return entry is not None and any(k in ("range", "ref") for k in entry.kinds)


@dataclass
class Env:
    """What a compiled block reads: ``block(sheet, col, first, last)`` and ``const(node)``."""

    n: int
    block: Callable
    const: Callable
    dialect: str = "excel"


@dataclass
class Block:
    sheet: str
    col: int
    first: int
    last: int
    run: Callable[[Env], object]         # -> NumBlock | ObjBlock | Const (scalar_of'd)
    scale: Callable[[Env], np.ndarray]   # operand scale per row


def row_invariant(node: ast.Node) -> bool:
    """True when every reference in ``node`` has an absolute row and nothing reads the
    row of the calling cell (ROW())."""
    for n in ast.walk(node):
        if isinstance(n, ast.CellRef) and not n.row_abs:
            return False
        if isinstance(n, ast.RangeRef) and not (n.first.row_abs and n.last.row_abs):
            return False
        if isinstance(n, ast.Func) and n.name == "ROW" and not n.args:
            return False
    return True


def _multi_row(node: ast.Node) -> bool:
    return isinstance(node, ast.RangeRef) and node.first.row != node.last.row


def intersects(node: ast.Node) -> bool:
    """Does a multi-row range stand where one value is expected (implicit intersection:
    its value depends on the row of the calling cell)?"""
    if _multi_row(node):
        return True
    for n in ast.walk(node):
        if isinstance(n, (ast.Unary, ast.Percent, ast.Binary, ast.Paren)):
            if any(_multi_row(ch) for ch in ast.children(n)):
                return True
        elif isinstance(n, ast.Func):
            entry = fx.REGISTRY.get(n.name)
            if entry is not None and any(
                    _multi_row(a) and entry.kind(i) in ("scalar", "lazy")
                    for i, a in enumerate(n.args)):
                return True
    return False


def compile_block(node: ast.Node, sheet: str, col: int, first: int, last: int,
                  sheet_of: Callable[[str], str] = lambda s: s) -> Block:
    """Compile ``node`` (the formula of row ``first``) for rows ``first..last`` of a column."""
    if intersects(node):
        raise NotVectorizable("implicit intersection")
    c = _Compiler(sheet, col, first, last, sheet_of)
    fn, _ = c.compile(node)

    def run(env: Env):
        return scalar(fn(env), env.n)
    return Block(sheet, col, first, last, run, c.scale_fn(node))


class _Compiler:
    def __init__(self, sheet, col, first, last, sheet_of):
        self.sheet, self.col, self.first, self.last = sheet, col, first, last
        self.sheet_of = sheet_of

    # -- leaves -------------------------------------------------------------------------
    def _slice(self, ref: ast.CellRef):
        sheet = self.sheet if ref.sheet is None else self.sheet_of(ref.sheet)
        if "]" in sheet:  # another workbook (no sheet name holds "]")
            raise NotVectorizable("external reference")
        a, b = ref.row, ref.row + (self.last - self.first)
        if sheet == self.sheet and ref.col == self.col and a <= self.last and b >= self.first:
            raise NotVectorizable("reads its own block")
        return sheet, ref.col, a, b

    def compile(self, node: ast.Node):
        """``(fn, is_ref)``: fn(env) -> NumBlock | ObjBlock | Const; is_ref True, False or
        'maybe'."""
        is_ref = isinstance(node, (ast.CellRef, ast.RangeRef, ast.Name))
        if row_invariant(node):
            return (lambda env: Const(env.const(node))), is_ref
        if isinstance(node, ast.CellRef):
            where = self._slice(node)
            return (lambda env: env.block(*where)), True
        if isinstance(node, ast.RangeRef):
            raise NotVectorizable("relative range")
        if isinstance(node, ast.Paren):
            return self.compile(node.inner)
        if isinstance(node, ast.Unary):
            fn, _ = self.compile(node.operand)
            return (lambda env: unary(node.op, scalar(fn(env), env.n), env.n)), False
        if isinstance(node, ast.Percent):
            fn, _ = self.compile(node.operand)
            return (lambda env: unary("%", scalar(fn(env), env.n), env.n)), False
        if isinstance(node, ast.Binary):
            return self._binary(node), False
        if isinstance(node, ast.Func):
            return self._func(node)
        raise NotVectorizable(type(node).__name__)

    def _binary(self, node: ast.Binary):
        spine = []  # left-deep chains iterated, never recursed
        while isinstance(node, ast.Binary):
            spine.append(node)
            node = node.left
        left, _ = self.compile(node)
        steps = [(s.op, self.compile(s.right)[0]) for s in reversed(spine)]

        def run(env):
            acc = scalar(left(env), env.n)
            for op, right in steps:
                acc = binary(op, acc, scalar(right(env), env.n), env.n, env.dialect)
            return acc
        return run

    def _func(self, node: ast.Func):
        name = node.name
        entry = fx.REGISTRY.get(name)
        if entry is None:  # unknown, or a defined name's LAMBDA: the cell-by-cell path
            raise NotVectorizable(f"{name} is not a built-in function")
        if name in ("IF", "IFERROR"):
            return self._lazy(node)
        if name in READS_LAYOUT:  # hidden rows, nested subtotals: the cell-by-cell path
            raise NotVectorizable(f"{name} reads the sheet's layout")
        if name in ("INDIRECT", "OFFSET"):  # a reference per row: the cell-by-cell path
            raise NotVectorizable(f"{name} gives a reference")  # (#REF! per row otherwise:
            # poi__StructuredRefs-lots-with-lookups.xlsx, INDIRECT("A"&ROW(...)-1))
        if entry.lazy:
            raise NotVectorizable(f"{name} is evaluated lazily, cell by cell")
        if entry.omitted and any(isinstance(a, ast.Missing) for a in node.args):
            raise NotVectorizable(f"{name} with an omitted argument")
        if name in ("ROW", "COLUMN") and len(node.args) <= 1:
            return self._position(node)
        if any(entry.kind(i) == "ref" and not row_invariant(a) for i, a in enumerate(node.args)):
            raise NotVectorizable(f"{name} reads a reference that moves with the row")
        args = [self.compile(a) for a in node.args]
        refs = [r for _, r in args]
        if _ref_sensitive(name) and "maybe" in refs:
            raise NotVectorizable(f"{name} of a conditional reference")
        fns = [f for f, _ in args]
        origin = (self.sheet, self.first, self.col)
        return (lambda env: call(name, [f(env) for f in fns], refs, env.n, env.dialect,
                                 origin)), False

    def _position(self, node: ast.Func):
        """ROW() / COLUMN() of the calling cell or of a row-relative cell reference."""
        if node.args and not isinstance(node.args[0], ast.CellRef):
            raise NotVectorizable(f"{node.name} of a range")
        ref = node.args[0] if node.args else None
        if node.name == "COLUMN":
            value = float(self.col if ref is None else ref.col)
            return (lambda env: Const(value)), False
        top = self.first if ref is None else ref.row
        return (lambda env: NumBlock(np.arange(top, top + env.n, dtype=float),
                                np.zeros(env.n, np.uint8))), False

    def _lazy(self, node: ast.Func):
        args = [self.compile(a) for a in node.args]
        fns = [f for f, _ in args]
        maybe = "maybe" if any(r for _, r in args[1:]) else False
        if node.name == "IFERROR":
            if len(fns) != 2:
                return (lambda env: Const(fx.ExcelError.VALUE)), False
            return (lambda env: _iferror(fns[0], fns[1], env)), maybe
        if not 1 <= len(fns) <= 3:
            return (lambda env: Const(fx.ExcelError.VALUE)), False
        then = fns[1] if len(fns) > 1 else (lambda env: Const(True))
        other = fns[2] if len(fns) > 2 else (lambda env: Const(False))
        return (lambda env: _if(fns[0], then, other, env)), maybe

    # -- operand scale --------------------------------------------------------------------
    def scale_fn(self, node: ast.Node):
        """Per row, the largest magnitude among the numeric leaves of the formula."""
        fixed: list[ast.Node] = []
        sliced = []
        literal = 0.0
        for n in ast.walk(node):
            if isinstance(n, ast.Number):
                literal = max(literal, abs(n.value))
            elif isinstance(n, ast.CellRef) and not n.row_abs:
                sliced.append(self._slice(n))
            elif isinstance(n, (ast.CellRef, ast.RangeRef, ast.Name)):
                fixed.append(n)

        def scale(env):
            out = np.full(env.n, literal)
            for n in fixed:
                out = np.maximum(out, value_scale(env.const(n)))
            for where in sliced:
                out = np.maximum(out, block_scale(env.block(*where)))
            return out
        return scale


def block_scale(b) -> np.ndarray:
    if isinstance(b, NumBlock):
        return np.where(b.err == 0, np.abs(b.val), 0.0)
    return np.array([0.0 if v is None or type(v) is str else value_scale(v)  # (text: 0)
                     for v in b.items])


def _if(cond_fn, then_fn, other_fn, env):
    cond = scalar(cond_fn(env), env.n)
    if isinstance(cond, Const):
        c = to_bool(cond.value)
        if isinstance(c, fx.ExcelError):
            return Const(c)
        return (then_fn if c else other_fn)(env)
    pick, cerr = to_bool_mask(cond, env.n)
    take = pick & (cerr == 0)
    then = scalar(then_fn(env), env.n) if take.any() else Const(False)
    drop = ~pick & (cerr == 0)
    other = scalar(other_fn(env), env.n) if drop.any() else Const(False)
    return choose(pick, cerr, then, other, env.n)


def _iferror(value_fn, fallback_fn, env):
    value = scalar(value_fn(env), env.n)
    if isinstance(value, Const):
        return fallback_fn(env) if isinstance(value.value, fx.ExcelError) else value
    if is_num(value):
        bad = value.err != 0
    else:
        bad = np.array([isinstance(v, fx.ExcelError) for v in value.items], bool)
    if not bad.any():
        return value
    fallback = scalar(fallback_fn(env), env.n)
    return choose(~bad, np.zeros(env.n, np.uint8), value, fallback, env.n)

