"""Terms common to several residual trees, factored out into columns of their own.

The templates write each closure residual as one tree over Table columns and
parameters, rebuilding what they check from the input (the crank pin from
theta_1, the rod point from the pin and the needle): printed whole, the sewing
machine's residuals averaged 381 characters and the longest 1,666, with the
same subtrees many times over.  ``common_terms`` takes the subtree whose
sharing saves the most formula text, makes it a term (a column of the Checks
sheet the residuals refer to), and repeats while a term still saves enough.

This is sound for the workbook: a term's cell is ``IF(status="ok", subtree,
"n/a")`` and the residuals refer to it only in their ``"ok"`` branch, where the
cell holds the subtree's value, the same double the inline subtree gives (the
same operations on the same operands, in Excel, LibreOffice and numpy).  The
trees stay the single source: terms are read off them, never written by hand.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass
from functools import lru_cache

from ..expr import Node, Var
from ..expr.excel import format_number
from ..expr.tree import Bin, Call, Neg, Num, Param, Text, substitute

#: Formula characters a term must save per row (its own cell costs some).
MIN_SAVING = 60
_REF = 4      # a term reference on the same sheet, e.g. ``AB12``
_REMOTE = 11  # a Table reference, e.g. ``Table!AB12``
_GUARD = 30   # ``IF(Table!AC8="ok",...,"n/a")``


@dataclass(frozen=True)
class Term:
    name: str
    expr: Node  # over Table columns, parameters and other terms


def term_name(i: int) -> str:
    """``term 1`` ...: a space keeps it apart from every quantity name."""
    return f"term {i}"


@lru_cache(maxsize=256)
def common_terms(trees: tuple[Node, ...]) -> tuple[tuple[Term, ...], tuple[Node, ...]]:
    """The terms in evaluation order (each after the terms it refers to), and the
    trees rewritten over them."""
    forest = list(trees)
    terms: list[Term] = []
    while True:
        shapes = _Shapes()
        counts: Counter[int] = Counter()
        for tree in forest + [t.expr for t in terms]:
            shapes.count(tree, counts)
        best, saving = None, MIN_SAVING - 1
        for key, count in counts.items():
            if count < 2 or not shapes.rows[key]:
                continue
            size = shapes.size[key]
            gain = (count - 1) * size - count * _REF - _GUARD
            if gain > saving:
                best, saving = key, gain
        if best is None:
            break
        name = term_name(len(terms) + 1)
        node = shapes.node[best]
        replace = _Replace(shapes, best, Var(name))
        forest = [replace(tree) for tree in forest]
        terms = [Term(t.name, replace(t.expr)) for t in terms]
        terms.append(Term(name, replace.inside(node)))
    ordered = _in_order(terms)  # numbered again in that order, left to right on the sheet
    names = {t.name: Var(term_name(i)) for i, t in enumerate(ordered, start=1)}
    return (tuple(Term(names[t.name].name, substitute(t.expr, names)) for t in ordered),
            tuple(substitute(tree, names) for tree in forest))


class _Shapes:
    """Structural keys of subtrees (equal trees, equal key), their printed size
    and whether they depend on the row (refer to a column)."""

    def __init__(self) -> None:
        self.ids: dict[tuple, int] = {}
        self.size: dict[int, int] = {}
        self.rows: dict[int, bool] = {}
        self.node: dict[int, Node] = {}
        self._memo: dict[int, int] = {}  # id(node) -> key; the trees are alive meanwhile

    def key(self, node: Node) -> int:
        found = self._memo.get(id(node))
        if found is not None:
            return found
        if isinstance(node, Bin):
            kids = (self.key(node.left), self.key(node.right))
            sig: tuple = ("B", node.op, kids)
            size, rows = len(node.op) + 2, False
        elif isinstance(node, Neg):
            kids = (self.key(node.operand),)
            sig, size, rows = ("N", kids), 1, False
        elif isinstance(node, Call):
            kids = tuple(self.key(a) for a in node.args)
            sig, size, rows = ("C", node.fn, kids), len(node.fn) + 1 + len(kids), False
        else:
            kids = ()
            sig, size, rows = _leaf(node)
        k = self.ids.setdefault(sig, len(self.ids))
        if k not in self.size:
            self.size[k] = size + sum(self.size[c] for c in kids)
            self.rows[k] = rows or any(self.rows[c] for c in kids)
            self.node[k] = node
        self._memo[id(node)] = k
        return k

    def count(self, node: Node, counts: Counter) -> None:
        """Every position of every subtree that could be a term."""
        stack = [node]
        while stack:
            current = stack.pop()
            if isinstance(current, (Bin, Neg, Call)):
                counts[self.key(current)] += 1
                stack.extend(_children(current))


def _leaf(node: Node) -> tuple[tuple, int, bool]:
    if isinstance(node, Var):
        term = node.name.startswith("term ")
        return ("V", node.name), (_REF if term else _REMOTE), True
    if isinstance(node, Param):
        return ("P", node.name), len(node.name), False
    if isinstance(node, Num):
        return ("#", node.value), len(format_number(node.value)), False
    if isinstance(node, Text):
        return ("T", node.value), len(node.value) + 2, False
    raise TypeError(f"unknown node {node!r}")


def _children(node: Node) -> tuple[Node, ...]:
    if isinstance(node, Bin):
        return (node.left, node.right)
    if isinstance(node, Neg):
        return (node.operand,)
    return node.args


class _Replace:
    """Rebuild trees with every occurrence of one subtree replaced by a reference."""

    def __init__(self, shapes: _Shapes, key: int, ref: Var):
        self.shapes, self.target, self.ref = shapes, key, ref

    def __call__(self, node: Node) -> Node:
        if isinstance(node, (Bin, Neg, Call)) and self.shapes.key(node) == self.target:
            return self.ref
        return self.inside(node)

    def inside(self, node: Node) -> Node:
        """``node`` with its children rebuilt (the node itself is kept)."""
        if isinstance(node, Bin):
            left, right = self(node.left), self(node.right)
            same = left is node.left and right is node.right
            return node if same else Bin(node.op, left, right)
        if isinstance(node, Neg):
            operand = self(node.operand)
            return node if operand is node.operand else Neg(operand)
        if isinstance(node, Call):
            args = tuple(self(a) for a in node.args)
            return node if all(a is b for a, b in zip(args, node.args)) else Call(node.fn, args)
        return node


def _refs(node: Node) -> set[str]:
    out, stack = set(), [node]
    while stack:
        current = stack.pop()
        if isinstance(current, Var) and current.name.startswith("term "):
            out.add(current.name)
        elif isinstance(current, (Bin, Neg, Call)):
            stack.extend(_children(current))
    return out


def _in_order(terms: list[Term]) -> list[Term]:
    """Each term after the terms it refers to (they form no cycle: a term refers
    only to subtrees of itself)."""
    by_name = {t.name: t for t in terms}
    done: set[str] = set()
    out: list[Term] = []

    def visit(term: Term) -> None:
        if term.name in done:
            return
        done.add(term.name)
        for name in sorted(_refs(term.expr), key=lambda n: int(n.split()[1])):
            visit(by_name[name])
        out.append(term)

    for term in terms:
        visit(term)
    return out
