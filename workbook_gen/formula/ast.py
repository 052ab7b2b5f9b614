"""Immutable nodes of a parsed Excel formula, and the two reference transforms.

Nodes are frozen dataclasses, so a tree is hashable and can be shared. Cell
coordinates are 1-based (``A1`` is ``col=1, row=1``). Explicit parentheses are
kept as :class:`Paren` nodes so that printing gives back the text exactly.

* :func:`r1c1` and the printer's ``to_relative`` give a formula's R1C1 text seen from one cell: formulas of a
  column that differ only by row have the same key and can be compiled once.
* :func:`shift` moves the relative references of a tree, as Excel does when it
  expands a shared formula or a formula is copied down.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from workbook_gen.xlerror import ExcelError

MAX_ROW = 1_048_576
MAX_COL = 16_384  # XFD

# Excel's operator precedence as binding powers (higher binds tighter); shared by
# the parser and the printer. Unary minus binds tighter than %, % than ^.
INFIX_POWER = {
    "=": 10, "<>": 10, "<": 10, ">": 10, "<=": 10, ">=": 10,
    "&": 20,
    "+": 30, "-": 30,
    "*": 40, "/": 40,
    "^": 50,  # left-associative: 2^3^2 is (2^3)^2
}
PERCENT_POWER = 60
PREFIX_POWER = 70


@dataclass(frozen=True, slots=True)
class Number:
    """A numeric literal; ``text`` is the literal as written (``1E-05``, ``.5``)."""

    value: float
    text: str = ""


@dataclass(frozen=True, slots=True)
class String:
    """A text literal (``value`` has the doubled quotes undone)."""

    value: str


@dataclass(frozen=True, slots=True)
class Bool:
    value: bool


@dataclass(frozen=True, slots=True)
class ErrorLit:
    error: ExcelError


@dataclass(frozen=True, slots=True)
class Missing:
    """An omitted function argument, as in ``IF(A1,,1)``."""


@dataclass(frozen=True, slots=True)
class CellRef:
    """A single-cell reference; ``sheet`` is the unquoted sheet name or None."""

    sheet: str | None
    col: int
    row: int
    col_abs: bool = False
    row_abs: bool = False


@dataclass(frozen=True, slots=True)
class RangeRef:
    """A rectangular range; the corners are CellRefs with ``sheet=None``.

    ``whole`` is "col" for ``A:B`` (rows 1..MAX_ROW, absolute) and "row" for ``2:3``
    (columns 1..MAX_COL, absolute); evaluators bound such ranges by the used range."""

    sheet: str | None
    first: CellRef
    last: CellRef
    whole: str = ""


@dataclass(frozen=True, slots=True)
class Sheets3D:
    """A 3-D reference ``Sheet1:Sheet3!A1:B2``: ``ref`` (sheet None) on every sheet from
    ``sheet`` to ``sheet2`` in workbook order."""

    sheet: str
    sheet2: str
    ref: "CellRef | RangeRef"


@dataclass(frozen=True, slots=True)
class RefOp:
    """A reference operator: ``:`` (range of two references, ``INDEX(..):INDEX(..)``),
    ``" "`` (intersection) or ``,`` (union, inside parentheses)."""

    op: str
    left: "Node"
    right: "Node"


@dataclass(frozen=True, slots=True)
class Array:
    """An array constant ``{1,2;3,4}``: rows of Number/String/Bool/ErrorLit nodes."""

    rows: tuple[tuple["Node", ...], ...]


@dataclass(frozen=True, slots=True)
class StructRef:
    """A structured reference ``Table1[Amount]``, ``[@x]``: ``table`` ("" for the table
    holding the formula) and ``spec``, the bracketed text as written. The evaluator
    resolves it to cells with the workbook's table definitions."""

    table: str
    spec: str


@dataclass(frozen=True, slots=True)
class Name:
    """A defined name, as written (names are case-insensitive in Excel)."""

    name: str
    sheet: str | None = None


@dataclass(frozen=True, slots=True)
class Func:
    """A function call; ``name`` is upper-case without the ``_xlfn.`` style prefix."""

    name: str
    args: tuple["Node", ...]
    prefix: str = ""


@dataclass(frozen=True, slots=True)
class Unary:
    op: str  # "-" or "+"
    operand: "Node"


@dataclass(frozen=True, slots=True)
class Percent:
    operand: "Node"


@dataclass(frozen=True, slots=True)
class Binary:
    op: str  # + - * / ^ & = <> < > <= >=
    left: "Node"
    right: "Node"


@dataclass(frozen=True, slots=True)
class Paren:
    inner: "Node"


Node = (Number | String | Bool | ErrorLit | Missing | CellRef | RangeRef | Name | Func
        | Unary | Percent | Binary | Paren | Sheets3D | RefOp | Array | StructRef)


def children(node: Node) -> tuple[Node, ...]:
    """The direct sub-expressions of ``node``."""
    if isinstance(node, Func):
        return node.args
    if isinstance(node, (Unary, Percent)):
        return (node.operand,)
    if isinstance(node, Binary):
        return (node.left, node.right)
    if isinstance(node, Paren):
        return (node.inner,)
    if isinstance(node, RefOp):
        return (node.left, node.right)
    return ()


def walk(node: Node):
    """Every node of the tree, parents before children."""
    stack = [node]
    while stack:
        current = stack.pop()
        yield current
        stack.extend(reversed(children(current)))


def map_refs(node: Node, fn) -> Node:
    """A copy of ``node`` where every CellRef / RangeRef ``r`` is replaced by ``fn(r)``."""
    if isinstance(node, (CellRef, RangeRef)):
        return fn(node)
    if isinstance(node, Func):
        return dataclasses.replace(node, args=tuple(map_refs(a, fn) for a in node.args))
    if isinstance(node, (Unary, Percent)):
        return dataclasses.replace(node, operand=map_refs(node.operand, fn))
    if isinstance(node, Binary):
        spine = []  # left spine, iterated: long operator chains must not recurse
        while isinstance(node, Binary):
            spine.append(node)
            node = node.left
        result = map_refs(node, fn)
        for step in reversed(spine):
            result = Binary(step.op, result, map_refs(step.right, fn))
        return result
    if isinstance(node, Paren):
        return Paren(map_refs(node.inner, fn))
    if isinstance(node, RefOp):
        return RefOp(node.op, map_refs(node.left, fn), map_refs(node.right, fn))
    if isinstance(node, Sheets3D):
        moved = fn(node.ref)
        return moved if isinstance(moved, ErrorLit) else Sheets3D(node.sheet, node.sheet2, moved)
    return node


def _shift_cell(ref: CellRef, drow: int, dcol: int) -> CellRef | None:
    row = ref.row if ref.row_abs else ref.row + drow
    col = ref.col if ref.col_abs else ref.col + dcol
    if not (1 <= row <= MAX_ROW and 1 <= col <= MAX_COL):
        return None
    return dataclasses.replace(ref, row=row, col=col)


def shift(node: Node, drow: int, dcol: int) -> Node:
    """Move relative references by ``drow`` rows and ``dcol`` columns.

    Absolute parts (``$``) stay. A reference pushed off the sheet becomes ``#REF!``,
    as in Excel.
    """
    def move(ref):
        if isinstance(ref, CellRef):
            moved = _shift_cell(ref, drow, dcol)
            return ErrorLit(ExcelError.REF) if moved is None else moved
        first = _shift_cell(ref.first, drow, dcol)
        last = _shift_cell(ref.last, drow, dcol)
        if first is None or last is None:
            return ErrorLit(ExcelError.REF)
        return RangeRef(ref.sheet, first, last, ref.whole)
    return map_refs(node, move)


def r1c1(ref: CellRef, base_row: int, base_col: int) -> str:
    """The R1C1 text of one cell reference seen from cell (base_row, base_col)."""
    def part(letter, value, absolute, base):
        if absolute:
            return f"{letter}{value}"
        offset = value - base
        return letter if offset == 0 else f"{letter}[{offset}]"
    return part("R", ref.row, ref.row_abs, base_row) + part("C", ref.col, ref.col_abs, base_col)
