"""The rounding noise of a Table column: the magnitudes its formulas cancelled
(docs/audit.md, How cells are compared).

A value computed in float64 carries an absolute rounding error of about
``eps * m``, where ``m`` is not the value's own size but the size of what the
formula added, multiplied and cancelled on the way to it.  ``alpha_2 =
(w^2 n h + w u v) / h^2`` of a rod as long as the crank is 0 in exact
arithmetic and about 1e-13 in floating point: noise of terms near 100, not a
value.  The reference comparison measures a column's error against the larger of
its magnitude and this noise, so that rounding noise is never a disagreement.

``m`` is a first-order running error bound, propagated along the formula's tree
and from cell to cell (a cell read by a formula brings its own ``m``; along a
Newton chain it doubles per step, which NOISE_ULPS leaves far below an unconverged
iterate's error):

    m(a +- b) = m(a) + m(b)              m(a * b) = |b| m(a) + |a| m(b)
    m(a / b)  = m(a)/|b| + |a| m(b)/b^2  m(a ^ n) = |n a^(n-1)| m(a)
    m(f(a))   = |f'(a)| m(a) + |f(a)|    (SIN, COS, SQRT, ATAN2, ...)

Only formulas of a column that are the same in relative form are handled (one
tree, evaluated over all rows as numpy arrays); anything else gives ``None`` and
the comparison falls back to the column's magnitude.
"""

from __future__ import annotations

from typing import Callable

import re

import numpy as np

from ..cellref import row_col
from ..errors import WorkbookGenError
from ..evaluator.store import floats_where, type_mask
from ..formula import ast, parse
from ..formula.printer import to_relative
from ..cellref import column_letters

_NUMBER_TYPES = frozenset({int, float, np.float64})


def numbers_or_nan(values: list) -> np.ndarray:
    """The numbers among ``values`` (not booleans), NaN for any other value: C loops."""
    return floats_where(values, type_mask(values, _NUMBER_TYPES))

_DIGITS = re.compile(r"[0-9]+")
Pair = tuple[np.ndarray, np.ndarray]  # values, noise magnitudes


class _Unsupported(Exception):
    pass


INPUT = "input"  # column_tree of a column whose first data row holds no formula


def column_tree(sheet, rows: range, col: int):
    """The one formula tree of a Table column's rows (from the formula text alone), INPUT
    for an input column; raises _Unsupported (or a parse error) if it has no single tree."""
    first = sheet.cell(rows.start, col)
    if first is None or not first.has_formula:
        return INPUT
    texts = []
    cells, letters = sheet.cells, column_letters(col)  # sheet.cell, quicker
    source_of = sheet.formula_source
    for row in rows:
        cell = cells.get(f"{letters}{row}")
        if cell is not None and cell.formula is not None:  # formula_source's first case
            texts.append((cell.formula, cell.ref))
            continue
        source = source_of(cell) if cell is not None else None
        if source is None:
            raise _Unsupported
        texts.append(source)
    # One tree for the column: the same text but for numbers on every row (cheap),
    # and the same relative form on the first and last rows (exact).
    # (one substitution over all texts: formula text never holds a NUL)
    if len(set(_DIGITS.sub("#", "\0".join(text for text, _ in texts)).split("\0"))) != 1:
        raise _Unsupported
    trees = [ast.shift(parse(text), *_offset(origin, row, col))
             for (text, origin), row in ((texts[0], rows.start),
                                         (texts[-1], rows.stop - 1))]
    if to_relative(trees[0], rows.start, col) != to_relative(
            trees[1], rows.stop - 1, col):
        raise _Unsupported
    return trees[0]


def column_trees(sheet, rows: range, cols=None) -> dict:
    """column_tree of every column of the sheet (or of ``cols``), None where it has none
    (ahead of ColumnNoise, e.g. in another process)."""
    out = {}
    for col in range(1, sheet.max_col + 1) if cols is None else cols:
        try:
            out[col] = column_tree(sheet, rows, col)
        except (_Unsupported, WorkbookGenError, ArithmeticError, ValueError, TypeError):
            out[col] = None
    return out


class ColumnNoise:
    """``of(col)``: the noise magnitude of every data row of a Table column (None:
    formulas this module does not follow).

    ``values(col)`` gives the recomputed column (rows 2..last), ``name_value(name)``
    a defined name's number (None if it is not one)."""

    def __init__(self, sheet, rows: range, values: Callable[[int], list],
                 name_value: Callable[[str], float | None], trees: dict | None = None):
        self.sheet, self.rows = sheet, rows
        self._values, self._name_value = values, name_value
        self._trees = trees or {}  # col -> column_tree's result computed ahead (None: none)
        self._memo: dict[int, np.ndarray | None] = {}
        self._numbers_memo: dict[int, np.ndarray] = {}

    def of(self, col: int) -> np.ndarray | None:
        if col not in self._memo:
            self._memo[col] = None  # a reference back to it (a cycle) gives no estimate
            try:
                self._memo[col] = self._column(col)
            except (_Unsupported, WorkbookGenError, ArithmeticError, ValueError, TypeError):
                pass
        return self._memo[col]

    def _column(self, col: int) -> np.ndarray | None:
        if col in self._trees:
            tree = self._trees[col]
            if tree is None:
                raise _Unsupported
        else:
            tree = column_tree(self.sheet, self.rows, col)
        if isinstance(tree, str):  # INPUT (equal, not the same object, from another process)
            return np.abs(self._numbers(col))  # an input column: exact as given
        with np.errstate(all="ignore"):
            _, noise = self._eval(tree, self.rows.start)
        return np.broadcast_to(np.abs(noise), (len(self.rows),)).copy()

    def _numbers(self, col: int) -> np.ndarray:
        """The column's numbers (NaN elsewhere); the same array at every call."""
        if col not in self._numbers_memo:
            self._numbers_memo[col] = numbers_or_nan(self._values(col))
        return self._numbers_memo[col]

    # -- the tree, over all rows at once ------------------------------------------------
    def _eval(self, node, base_row: int) -> Pair:
        if isinstance(node, ast.Paren):
            return self._eval(node.inner, base_row)
        if isinstance(node, ast.Number):
            return np.float64(node.value), np.float64(abs(node.value))
        if isinstance(node, ast.Bool):
            return np.float64(node.value), np.float64(0.0)
        if isinstance(node, ast.CellRef):
            if node.sheet is not None and node.sheet != self.sheet.name or node.row_abs:
                raise _Unsupported
            if node.row != base_row:
                raise _Unsupported  # only same-row references (the Table's rule)
            noise = self.of(node.col)
            if noise is None:
                raise _Unsupported
            return self._numbers(node.col), noise
        if isinstance(node, ast.Name):
            value = self._name_value(node.name)
            if value is None:
                raise _Unsupported
            return np.float64(value), np.float64(abs(value))
        if isinstance(node, ast.Unary):
            a, m = self._eval(node.operand, base_row)
            return (-a if node.op == "-" else a), m
        if isinstance(node, ast.Binary):
            return self._binary(node, base_row)
        if isinstance(node, ast.Func):
            return self._func(node, base_row)
        raise _Unsupported

    def _binary(self, node: ast.Binary, base_row: int) -> Pair:
        (a, ma), (b, mb) = self._eval(node.left, base_row), self._eval(node.right, base_row)
        op = node.op
        if op in ("+", "-"):
            return (a + b if op == "+" else a - b), ma + mb
        if op == "*":
            return a * b, np.abs(b) * ma + np.abs(a) * mb
        if op == "/":
            return a / b, ma / np.abs(b) + np.abs(a) * mb / (b * b)
        if op == "^":
            value = np.power(a, b)
            if _exact(node.right):  # a literal exponent (^2, ^0.5) is exact
                mb = 0.0
            by_exponent = np.where(mb == 0, 0.0, np.abs(value * np.log(np.abs(a))) * mb)
            return value, np.abs(b * np.power(a, b - 1)) * ma + by_exponent + np.abs(value)
        if op in ("=", "<>", "<", ">", "<=", ">="):
            compare = {"=": np.equal, "<>": np.not_equal, "<": np.less, ">": np.greater,
                       "<=": np.less_equal, ">=": np.greater_equal}[op]
            return compare(a, b).astype(float), np.float64(0.0)
        raise _Unsupported

    def _func(self, node: ast.Func, base_row: int) -> Pair:
        name = node.name
        if name == "PI":
            return np.float64(np.pi), np.float64(np.pi)
        if name == "IF":
            if len(node.args) != 3:
                raise _Unsupported
            cond, _ = self._eval(node.args[0], base_row)
            (a, ma), (b, mb) = (self._eval(x, base_row) for x in node.args[1:])
            take = cond != 0
            return np.where(take, a, b), np.where(take, ma, mb)
        args = [self._eval(x, base_row) for x in node.args]
        if name in _UNARY and len(args) == 1:
            (a, m), (f, df) = args[0], _UNARY[name]
            value = f(a)
            return value, np.abs(df(a)) * m + np.abs(value)
        if name in ("ATAN2", "MOD", "POWER", "MIN", "MAX") and len(args) == 2:
            (x, mx), (y, my) = args
            if name == "ATAN2":  # Excel's ATAN2(x, y)
                value, r2 = np.arctan2(y, x), x * x + y * y
                return value, (np.abs(y) * mx + np.abs(x) * my) / r2 + np.abs(value)
            if name == "MOD":
                return x - y * np.floor(x / y), mx + np.abs(np.floor(x / y)) * my
            if name == "POWER":
                return self._binary(ast.Binary("^", node.args[0], node.args[1]), base_row)
            pick = (x <= y) if name == "MIN" else (x >= y)
            return np.where(pick, x, y), np.maximum(mx, my)
        raise _Unsupported


def _exact(node) -> bool:
    while isinstance(node, ast.Paren):
        node = node.inner
    return isinstance(node, ast.Number)


def _offset(origin: str, row: int, col: int) -> tuple[int, int]:
    """Rows and columns from a shared formula's master ``origin`` to (row, col)."""
    r, c = row_col(origin)
    return row - r, col - c


_UNARY = {
    "SIN": (np.sin, np.cos),
    "COS": (np.cos, lambda a: -np.sin(a)),
    "TAN": (np.tan, lambda a: 1.0 / np.cos(a) ** 2),
    "ASIN": (np.arcsin, lambda a: 1.0 / np.sqrt(1.0 - a * a)),
    "ACOS": (np.arccos, lambda a: -1.0 / np.sqrt(1.0 - a * a)),
    "ATAN": (np.arctan, lambda a: 1.0 / (1.0 + a * a)),
    "SQRT": (np.sqrt, lambda a: 0.5 / np.sqrt(a)),
    "ABS": (np.abs, lambda a: np.ones_like(a)),
    "SIGN": (np.sign, lambda a: np.zeros_like(a)),
    "RADIANS": (np.radians, lambda a: np.full_like(a, np.pi / 180.0)),
    "DEGREES": (np.degrees, lambda a: np.full_like(a, 180.0 / np.pi)),
}
