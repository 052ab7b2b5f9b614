"""The magnitudes a tree's arithmetic cancels, row by row: its rounding noise is about
eps times this (the Summary's tie threshold; docs/workbook.md, Summary).

    m(a +- b) = m(a) + m(b)     m(a * b) = |b| m(a) + |a| m(b)
    m(a / b)  = m(a) / |b| + |a| m(b) / b^2     m(f(a)) = |f'(a)| m(a) + |f(a)|

Quantities and parameters a tree reads count at their own size.  A shaking force of
a balanced four-bar, sum m_i a_i = 1e-16 N from terms near 1 N, has m near 1 N.
"""

from __future__ import annotations

from typing import Mapping

import numpy as np

from .. import xlmath as xm
from functools import lru_cache

from . import fastnum
from .numeric import compiled
from .tree import Bin, Call, Neg, Node, Num, Param, Var, children

_DERIVATIVE = {
    "SIN": np.cos, "COS": lambda a: -np.sin(a), "TAN": lambda a: 1.0 / np.cos(a) ** 2,
    "ASIN": lambda a: 1.0 / np.sqrt(1.0 - a * a), "ACOS": lambda a: 1.0 / np.sqrt(1.0 - a * a),
    "ATAN": lambda a: 1.0 / (1.0 + a * a), "SQRT": lambda a: 0.5 / np.sqrt(a),
    "ABS": np.ones_like, "SIGN": np.zeros_like,
    "RADIANS": lambda a: np.full_like(a, np.pi / 180.0),
    "DEGREES": lambda a: np.full_like(a, 180.0 / np.pi),
}


def magnitude(node: Node, columns: Mapping[str, xm.XArray], params: Mapping[str, float],
              n: int, shared: "_Values | None" = None) -> np.ndarray:
    """Per row, the magnitude of what ``node`` adds and cancels (NaN where an error).
    ``shared``: a ``scope(columns, params, n)`` over which several trees that share
    subtrees are measured, each subtree once."""
    values = _Values(columns, params, n) if shared is None else shared
    measured = values.measured.get(node)
    if measured is not None:
        with np.errstate(all="ignore"):
            return np.abs(measured)
    values.prime(node)
    printed = None if values.primed is None else _printed(node)
    with np.errstate(all="ignore"):
        if printed is not None:
            g, nodes = printed
            return np.abs(g([values.primed[k] for k in nodes]))
        return np.abs(_m(node, values))


_ABS_OF_VALUE = "_abs(v[{i}])"


def _source(nodes: list[Node]) -> str:
    """``_magnitude`` printed for each distinct subtree (``nodes``, children first): the
    same numpy expressions, in the same order, over the subtrees' values ``v``."""
    index = {node: i for i, node in enumerate(nodes)}
    lines = []
    for i, node in enumerate(nodes):
        k = [index[c] for c in children(node)]
        text = _ABS_OF_VALUE.format(i=i)
        if isinstance(node, Neg):
            text = f"m{k[0]}"
        elif isinstance(node, Bin):
            ma, mb, a, b = f"m{k[0]}", f"m{k[1]}", f"v[{k[0]}]", f"v[{k[1]}]"
            if node.op in ("+", "-"):
                text = f"{ma} + {mb}"
            elif node.op == "*":
                text = f"_abs({b}) * {ma} + _abs({a}) * {mb}"
            elif node.op == "/":
                text = f"{ma} / _abs({b}) + _abs({a}) * {mb} / ({b} * {b})"
            elif node.op == "^" and isinstance(node.right, Num):
                text = f"_abs({b} * _power({a}, {b} - 1)) * {ma} + _abs(_power({a}, {b}))"
        elif isinstance(node, Call):
            if node.fn == "IF" and len(node.args) == 3:
                text = f"_where(v[{k[0]}] != 0, m{k[1]}, m{k[2]})"
            elif node.fn in _DERIVATIVE:
                text = f"_abs(_D[{node.fn!r}](v[{k[0]}])) * m{k[0]} + " + text
            elif node.fn == "ATAN2":
                x, y, mx, my = f"v[{k[0]}]", f"v[{k[1]}]", f"m{k[0]}", f"m{k[1]}"
                text = f"(_abs({y}) * {mx} + _abs({x}) * {my}) / ({x} * {x} + {y} * {y}) + " + text
            elif node.fn in ("MIN", "MAX"):
                text = f"_max([{', '.join(f'm{j}' for j in k)}], axis=0)"
        lines.append(f"    m{i} = {text}")
    return "def g(v):\n" + "\n".join(lines) + f"\n    return m{len(nodes) - 1}\n"


def _compile_g(text: str):
    scope = {"_abs": np.abs, "_power": np.power, "_where": np.where, "_max": np.max,
             "_D": _DERIVATIVE}
    exec(compile(text, "<magnitude>", "exec"), scope)
    return scope["g"]


@lru_cache(maxsize=256)
def _printed_set(trees: tuple[Node, ...]):
    """The values of all subtrees of ``trees`` (each distinct one once) and ``g(values)``
    -> each tree's magnitude before the final abs, as ``_printed`` gives it."""
    generated = fastnum.generate_subtrees_of(trees)
    if generated is None:
        return None
    f, nodes, roots = generated
    text = _source(nodes).rsplit("\n    return ", 1)[0]
    text += "\n    return (" + "".join(f"m{r}, " for r in roots) + ")\n"
    return f, nodes, _compile_g(text)


@lru_cache(maxsize=1024)
def _printed(tree: Node):
    """``g(values) -> magnitude`` of ``tree`` (before the final abs) and the subtrees
    whose values it takes, in order; None where a tree holds a -0 literal."""
    generated = _subtrees(tree)
    if generated is None:
        return None
    nodes = generated[1]
    return _compile_g(_source(nodes)), nodes


def scope(columns: Mapping[str, xm.XArray], params: Mapping[str, float], n: int) -> "_Values":
    """The values and magnitudes of the subtrees measured over these columns, kept."""
    return _Values(columns, params, n)


class _Scope(Mapping):
    """The columns, with the values of a node's children under placeholder names."""

    def __init__(self, local: dict, columns: Mapping):
        self.local, self.columns = local, columns

    def __getitem__(self, name):
        found = self.local.get(name)
        return self.columns[name] if found is None else found

    def __iter__(self):
        return iter({**self.columns, **self.local})

    def __len__(self):
        return len(self.local) + len(self.columns)


#: Every subtree's value of a tree by one generated function (the same bits as
#: ``compile_numpy(subtree)``), once per tree in a process.
_subtrees = lru_cache(maxsize=1024)(fastnum.generate_subtrees)

_PLACEHOLDERS = tuple(Var(f"\x00{i}") for i in range(256))
_compiled = compiled


def _shell(node: Node) -> Node:
    """``node`` with its children replaced by placeholders: evaluated over its children's
    values it gives what the whole subtree gives (compile_numpy is compositional)."""
    if isinstance(node, Neg):
        return Neg(_PLACEHOLDERS[0])
    if isinstance(node, Bin):
        return Bin(node.op, _PLACEHOLDERS[0], _PLACEHOLDERS[1])
    return Call(node.fn, _PLACEHOLDERS[:len(node.args)])


class _Values:
    """Each subtree's value, computed once from its children's (not the subtree again at
    every level), as ``compile_numpy(subtree)`` gives it."""

    def __init__(self, columns, params, n):
        self.columns, self.params, self.n = columns, params, n
        self.memo: dict[int, tuple[Node, xm.XArray]] = {}
        self.floats: dict[int, tuple[Node, np.ndarray]] = {}   # __call__'s, by node id
        self.primed: dict[Node, np.ndarray] | None = {}   # prime()'s, by subtree
        self.magnitudes: dict[int, tuple[Node, np.ndarray]] = {}   # _m's
        self.measured: dict[Node, np.ndarray] = {}   # measure()'s, before the abs

    def measure(self, trees: tuple[Node, ...]) -> None:
        """The magnitudes of all ``trees`` at once, each distinct subtree once (kept for
        ``magnitude``); nothing where a tree holds a -0 literal."""
        printed = _printed_set(trees)
        if printed is None:
            return
        f, nodes, g = printed
        floats = []
        for val, err, _ in f(self.columns, self.params, self.n):
            if val.dtype == object:
                floats.append(np.zeros(self.n))
            else:
                floats.append(val if err is None else np.where(err != 0, np.nan, val))
        with np.errstate(all="ignore"):
            for tree, m in zip(trees, g(floats)):
                self.measured.setdefault(tree, m)

    def prime(self, tree: Node) -> None:
        """Every subtree's value of ``tree``, in one call of its generated function."""
        if self.primed is None or tree in self.primed:
            return
        generated = _subtrees(tree)
        if generated is None:  # a -0 literal, equal to 0 as a key: subtree by subtree
            self.primed = None
            return
        f, nodes = generated
        for node, (val, err, _) in zip(nodes, f(self.columns, self.params, self.n)):
            if val.dtype == object:
                value = np.zeros(self.n)
            elif err is None:
                value = val
            else:
                value = np.where(err != 0, np.nan, val)
            self.primed.setdefault(node, value)

    def xarray(self, node: Node) -> xm.XArray:
        found = self.memo.get(id(node))
        if found is not None:
            return found[1]
        kids = children(node)
        if kids:
            local = {p.name: self.xarray(k) for p, k in zip(_PLACEHOLDERS, kids)}
            value = _compiled(_shell(node))(_Scope(local, self.columns), self.params, self.n)
        else:
            value = _compiled(node)(self.columns, self.params, self.n)
        self.memo[id(node)] = (node, value)  # the node kept alive: its id stays its own
        return value

    def __call__(self, node: Node) -> np.ndarray:
        found = self.floats.get(id(node))
        if found is not None:
            return found[1]
        value = None if self.primed is None else self.primed.get(node)
        if value is None:
            result = self.xarray(node)
            value = np.where(result.err != 0, np.nan, np.asarray(result.val, dtype=float)) \
                if not result.is_text else np.zeros(self.n)
        self.floats[id(node)] = (node, value)  # the node kept alive: its id stays its own
        return value


def _m(node: Node, value: _Values) -> np.ndarray:
    """The magnitude of ``node``, once per subtree (a tree shares subtrees)."""
    found = value.magnitudes.get(id(node))
    if found is not None:
        return found[1]
    m = _magnitude(node, value)
    value.magnitudes[id(node)] = (node, m)
    return m


def _magnitude(node: Node, value: _Values) -> np.ndarray:
    if isinstance(node, (Num, Param, Var)):
        return np.abs(value(node))
    if isinstance(node, Neg):
        return _m(node.operand, value)
    if isinstance(node, Bin):
        ma, mb = _m(node.left, value), _m(node.right, value)
        a, b = value(node.left), value(node.right)
        if node.op in ("+", "-"):
            return ma + mb
        if node.op == "*":
            return np.abs(b) * ma + np.abs(a) * mb
        if node.op == "/":
            return ma / np.abs(b) + np.abs(a) * mb / (b * b)
        if node.op == "^" and isinstance(node.right, Num):
            return np.abs(b * np.power(a, b - 1)) * ma + np.abs(np.power(a, b))
        return np.abs(value(node))
    if isinstance(node, Call):
        if node.fn == "IF" and len(node.args) == 3:
            cond = value(node.args[0])
            return np.where(cond != 0, _m(node.args[1], value), _m(node.args[2], value))
        if node.fn in _DERIVATIVE:
            a = value(node.args[0])
            return (np.abs(_DERIVATIVE[node.fn](a)) * _m(node.args[0], value)
                    + np.abs(value(node)))
        if node.fn == "ATAN2":
            x, y = (value(arg) for arg in node.args)
            mx, my = (_m(arg, value) for arg in node.args)
            return (np.abs(y) * mx + np.abs(x) * my) / (x * x + y * y) + np.abs(value(node))
        if node.fn in ("MIN", "MAX"):
            return np.max([_m(arg, value) for arg in node.args], axis=0)
    return np.abs(value(node))
