"""Print a tree as Excel formula text.

Parentheses are placed by Excel's precedence (unary minus binds tighter than
``^``; ``^`` is left-associative) so that the text parses back to the same
tree: a right operand of equal precedence is always parenthesised, because
``a-(b-c)`` and ``(a+b)+c`` must keep their order of evaluation.

``RowTemplate`` prints a tree once and renders it for any row number, so a
column of thousands of cells costs one print and a ``join`` per cell.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from .tree import Bin, Call, Neg, Node, Num, Param, Text, Var

# Higher binds tighter.  Atoms (literals, references, calls) are 9.
_PRECEDENCE = {"=": 1, "<>": 1, "<": 1, ">": 1, "<=": 1, ">=": 1, "&": 2,
               "+": 3, "-": 3, "*": 4, "/": 4, "^": 5}
_NEG = 7
_ATOM = 9


class Row:
    """Marker for 'the row number of the cell being written' in a template, plus
    ``offset`` (a reference from another sheet whose rows start elsewhere)."""

    __slots__ = ("offset",)

    def __init__(self, offset: int = 0):
        self.offset = offset

    def __repr__(self) -> str:
        return f"ROW{self.offset:+d}" if self.offset else "ROW"


ROW = Row()
Piece = str | Row
# Where a quantity is placed: its name -> the pieces of its cell reference (not the
# formula evaluator's Resolver, formula/resolver.py, which reads cells and names).
PlaceOf = Callable[[str], tuple[Piece, ...]]


def format_number(value: float) -> str:
    """Shortest text that reads back as exactly ``value`` (Excel style exponent)."""
    if value == int(value) and abs(value) < 1e15:
        return str(int(value))
    text = repr(value)
    if "e" in text:
        mantissa, exponent = text.split("e")
        sign = "-" if exponent.startswith("-") else "+"
        text = f"{mantissa}E{sign}{exponent.lstrip('+-').zfill(2)}"
    return text


def _precedence(node: Node) -> int:
    if isinstance(node, Bin):
        return _PRECEDENCE[node.op]
    if isinstance(node, Neg):
        return _NEG
    return _ATOM


def _pieces(node: Node, resolve: PlaceOf, out: list[Piece]) -> None:
    if isinstance(node, Num):
        out.append(format_number(node.value))
    elif isinstance(node, Text):
        out.append('"' + node.value.replace('"', '""') + '"')
    elif isinstance(node, Param):
        out.append(node.name)
    elif isinstance(node, Var):
        out.extend(resolve(node.name))
    elif isinstance(node, Neg):
        out.append("-")
        _operand(node.operand, _precedence(node.operand) < _NEG, resolve, out)
    elif isinstance(node, Bin):
        p = _PRECEDENCE[node.op]
        # (-x)^2, not -x^2: the same in Excel (unary minus binds tighter), clearer to read.
        left_parens = _precedence(node.left) < p or (node.op == "^" and isinstance(node.left, Neg))
        _operand(node.left, left_parens, resolve, out)
        out.append(node.op)
        _operand(node.right, _precedence(node.right) <= p, resolve, out)
    elif isinstance(node, Call):
        out.append(node.fn + "(")
        for i, arg in enumerate(node.args):
            if i:
                out.append(",")
            _pieces(arg, resolve, out)
        out.append(")")
    else:
        raise TypeError(f"cannot print {node!r}")


def _operand(node: Node, parenthesise: bool, resolve: PlaceOf, out: list[Piece]) -> None:
    if parenthesise:
        out.append("(")
    _pieces(node, resolve, out)
    if parenthesise:
        out.append(")")


@dataclass(frozen=True)
class RowTemplate:
    """A formula printed once, with slots for the row number."""

    parts: tuple[str, ...]  # text between row slots; len(parts) == slots + 1
    offsets: tuple[int, ...] = ()  # per slot, added to the row; () when all are 0

    def render(self, row: int) -> str:
        """The formula text (with leading '=') for worksheet row ``row`` (1-based)."""
        if not self.offsets:
            return str(row).join(self.parts)
        out = [self.parts[0]]
        for offset, part in zip(self.offsets, self.parts[1:]):
            out.append(str(row + offset))
            out.append(part)
        return "".join(out)


def row_template(node: Node, resolve: PlaceOf) -> RowTemplate:
    pieces: list[Piece] = ["="]
    _pieces(node, resolve, pieces)
    parts: list[str] = [""]
    offsets: list[int] = []
    for piece in pieces:
        if isinstance(piece, Row):
            parts.append("")
            offsets.append(piece.offset)
        else:
            parts[-1] += piece
    return RowTemplate(tuple(parts), tuple(offsets) if any(offsets) else ())


def to_excel(node: Node, resolve: Callable[[str], str] | None = None) -> str:
    """Formula text (with leading '=') with each quantity printed by ``resolve``."""
    def fixed(name: str) -> tuple[Piece, ...]:
        if resolve is None:
            raise ValueError(f"no cell reference for quantity {name!r}")
        return (resolve(name),)
    return row_template(node, fixed).render(0)
