"""The expression tree: the single source of truth of every formula.

A quantity of a mechanism is written once, in Python, with ordinary operators:

    x_B = l_AB * cos(radians(theta_1))

and the printers in this package turn that one tree into Excel formula text,
a numpy function (cached values, ``compute()``) and an mpmath function (the
high-precision reference of the formula).  The dependency graph that prunes a
scene's columns is read off the same trees (``variables``).

Nodes are immutable and hashable.  ``==`` is plain structural equality; Excel
comparisons are built with ``lt``/``le``/``eq``... so they cannot be confused.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Iterator, Union

Operand = Union["Node", float, int]


class Node:
    """Base of all tree nodes; arithmetic operators build bigger trees."""

    __slots__ = ()

    def __add__(self, other: Operand) -> Node:
        return Bin("+", self, wrap(other))

    def __radd__(self, other: Operand) -> Node:
        return Bin("+", wrap(other), self)

    def __sub__(self, other: Operand) -> Node:
        return Bin("-", self, wrap(other))

    def __rsub__(self, other: Operand) -> Node:
        return Bin("-", wrap(other), self)

    def __mul__(self, other: Operand) -> Node:
        return Bin("*", self, wrap(other))

    def __rmul__(self, other: Operand) -> Node:
        return Bin("*", wrap(other), self)

    def __truediv__(self, other: Operand) -> Node:
        return Bin("/", self, wrap(other))

    def __rtruediv__(self, other: Operand) -> Node:
        return Bin("/", wrap(other), self)

    def __pow__(self, other: Operand) -> Node:
        return Bin("^", self, wrap(other))

    def __rpow__(self, other: Operand) -> Node:
        return Bin("^", wrap(other), self)

    def __neg__(self) -> Node:
        return Neg(self)

    def __pos__(self) -> Node:
        return self


@dataclass(frozen=True, slots=True)
class Num(Node):
    """A non-negative numeric literal (negative numbers are ``Neg(Num)``)."""

    value: float

    def __post_init__(self) -> None:
        if not math.isfinite(self.value) or self.value < 0:
            raise ValueError(f"Num needs a finite value >= 0, got {self.value!r}")


@dataclass(frozen=True, slots=True)
class Text(Node):
    """A string literal (status texts, the empty string)."""

    value: str


@dataclass(frozen=True, slots=True)
class Param(Node):
    """A named parameter: a defined name in the workbook."""

    name: str


@dataclass(frozen=True, slots=True)
class Var(Node):
    """Another quantity of the same row (a Table column), or the input."""

    name: str


def _cached_hash(node, parts: tuple) -> int:
    """A composite node's hash, computed once: trees are hashed as cache keys (printed
    formulas, compiled functions) and would otherwise be walked at every look-up."""
    h = node._hash
    if h == 0:
        h = hash(parts) or 1
        object.__setattr__(node, "_hash", h)
    return h


@dataclass(frozen=True, slots=True)
class Neg(Node):
    operand: Node
    _hash: int = field(default=0, init=False, repr=False, compare=False)

    def __hash__(self) -> int:
        return _cached_hash(self, (Neg, self.operand))

    def __reduce__(self):  # not the cached hash: string hashes differ between processes
        return (Neg, (self.operand,))


BINARY_OPS = ("+", "-", "*", "/", "^", "&", "=", "<>", "<", ">", "<=", ">=")


@dataclass(frozen=True, slots=True)
class Bin(Node):
    op: str
    left: Node
    right: Node
    _hash: int = field(default=0, init=False, repr=False, compare=False)

    def __hash__(self) -> int:
        return _cached_hash(self, (Bin, self.op, self.left, self.right))

    def __reduce__(self):  # not the cached hash: string hashes differ between processes
        return (Bin, (self.op, self.left, self.right))

    def __post_init__(self) -> None:
        if self.op not in BINARY_OPS:
            raise ValueError(f"unknown operator {self.op!r}")


FUNCTIONS = {
    # name: (min args, max args)
    "SIN": (1, 1), "COS": (1, 1), "TAN": (1, 1), "ASIN": (1, 1), "ACOS": (1, 1),
    "ATAN": (1, 1), "ATAN2": (2, 2), "SQRT": (1, 1), "ABS": (1, 1), "SIGN": (1, 1),
    "PI": (0, 0), "RADIANS": (1, 1), "DEGREES": (1, 1), "MOD": (2, 2), "POWER": (2, 2),
    "IF": (3, 3), "AND": (1, 255), "OR": (1, 255), "NOT": (1, 1), "MIN": (1, 255),
    "MAX": (1, 255), "IFERROR": (2, 2), "ISERROR": (1, 1),
}


@dataclass(frozen=True, slots=True)
class Call(Node):
    fn: str
    args: tuple[Node, ...]
    _hash: int = field(default=0, init=False, repr=False, compare=False)

    def __hash__(self) -> int:
        return _cached_hash(self, (Call, self.fn, self.args))

    def __reduce__(self):  # not the cached hash: string hashes differ between processes
        return (Call, (self.fn, self.args))

    def __post_init__(self) -> None:
        if self.fn not in FUNCTIONS:
            raise ValueError(f"function {self.fn} is not supported in trees")
        lo, hi = FUNCTIONS[self.fn]
        if not lo <= len(self.args) <= hi:
            raise ValueError(f"{self.fn} takes {lo}..{hi} arguments, got {len(self.args)}")


def wrap(value: Operand | str) -> Node:
    """A node for ``value``: nodes pass through, numbers become literals."""
    if isinstance(value, Node):
        return value
    if isinstance(value, bool):
        raise TypeError("booleans are not tree literals")
    if isinstance(value, (int, float)):
        value = float(value)
        return Neg(Num(-value)) if value < 0 else Num(value)
    if isinstance(value, str):
        return Text(value)
    raise TypeError(f"cannot make a tree node of {value!r}")


def children(node: Node) -> tuple[Node, ...]:
    if isinstance(node, Neg):
        return (node.operand,)
    if isinstance(node, Bin):
        return (node.left, node.right)
    if isinstance(node, Call):
        return node.args
    return ()


def walk(node: Node) -> Iterator[Node]:
    """Every node of the tree, parents before children."""
    stack = [node]
    while stack:
        current = stack.pop()
        yield current
        stack.extend(reversed(children(current)))


@lru_cache(maxsize=8192)  # model selection asks for every tree's at every scene
def variables(node: Node) -> frozenset[str]:
    """Names of the quantities (columns) the tree refers to."""
    return frozenset(n.name for n in walk(node) if isinstance(n, Var))


def parameters(node: Node) -> frozenset[str]:
    """Names of the parameters the tree refers to."""
    return frozenset(n.name for n in walk(node) if isinstance(n, Param))


def substitute(node: Node, mapping: dict[str, Node]) -> Node:
    """The tree with each ``Var`` named in ``mapping`` replaced by its tree."""
    if isinstance(node, Var):
        return mapping.get(node.name, node)
    if isinstance(node, Neg):
        return Neg(substitute(node.operand, mapping))
    if isinstance(node, Bin):
        return Bin(node.op, substitute(node.left, mapping), substitute(node.right, mapping))
    if isinstance(node, Call):
        return Call(node.fn, tuple(substitute(a, mapping) for a in node.args))
    return node
