"""A scene's trees compiled for many variants at once (``--summary-only``).

The rows of a block of ``V`` variants are held flattened, variant after variant
(``V * n`` elements).  Before compiling with the one numpy printer
(``expr.numeric.compile_numpy``) the trees are rewritten, without changing a single
operation on any element:

- a subtree that reads parameters only (``l_BE / l_BC``, ``omega_1 ^ 2``) is computed
  once per variant (``V`` elements) and repeated over that variant's rows;
- a subtree that several columns share (``x_E - x_F``) is computed once per block.

Each element still goes through the same ``xlmath`` operations in the same order as
in ``tabulate.evaluate``, so the numbers are the workbooks' cached values, bit for bit.
"""

from __future__ import annotations

from collections import Counter
from typing import Mapping

import numpy as np

from .. import xlmath as xm
from ..expr import Bin, Call, Neg, Node, Num, Param, Text, Var
from ..expr import fastnum
from ..expr.numeric import Compiled, compile_numpy
from ..expr.tree import children
from ..pruning import select
from ..scene import Scene

_HIDDEN = "\x00"  # prefix of names no quantity can have


def _rebuild(node: Node, kids: list[Node]) -> Node:
    if isinstance(node, Neg):
        return Neg(kids[0])
    if isinstance(node, Bin):
        return Bin(node.op, kids[0], kids[1])
    if isinstance(node, Call):
        return Call(node.fn, tuple(kids))
    return node


class Plan:
    """Compiled steps: per-variant ones (parameters, derived values, parameter-only
    subtrees), then per-row ones (shared subtrees and the Table's columns, in order)."""

    def __init__(self, scene: Scene):
        template = scene.template
        self.model = select(template, scene.outputs)
        self.input = template.input.name
        self.parameters = tuple(p.name for p in template.parameters)
        self.derived = [(d.name, compile_numpy(_param_vars(d.expr))) for d in template.derived]
        self._variant_steps: list[tuple[str, Compiled]] = []
        self._row_steps: list[tuple[str, Compiled]] = []
        self._repeat: set[str] = set()        # variant-level names the rows read
        self._hoisted: dict[Node, str] = {}
        self._rowdep: dict[Node, bool] = {}
        roots = [(q.name, q.expr) for q in self.model.columns] + [("\x00status", template.status)]
        self._shared = Counter()
        for _, tree in roots:
            self._count(tree)
        for name, tree in roots:
            self._row_steps.append((name, self._rewrite(tree, top=True)))
        # every per-row step as one generated function (fastnum: the same bits as
        # compile_numpy, each distinct subtree and literal once per block)
        self._rows = fastnum.generate_set(tuple(self._row_steps), scalars=True)

    # -- rewriting ---------------------------------------------------------------------
    def _is_rowdep(self, node: Node) -> bool:
        known = self._rowdep.get(node)
        if known is None:
            known = isinstance(node, Var) or any(self._is_rowdep(c) for c in children(node))
            self._rowdep[node] = known
        return known

    def _count(self, node: Node) -> None:
        if isinstance(node, (Num, Text, Param, Var)):
            return
        self._shared[node] += 1
        if self._shared[node] == 1:
            for child in children(node):
                self._count(child)

    def _name(self, node: Node, steps: list, tree: Node) -> str:
        name = self._hoisted.get(node)
        if name is None:
            name = f"{_HIDDEN}{len(self._hoisted)}"
            self._hoisted[node] = name
            steps.append((name, tree if steps is self._row_steps else compile_numpy(tree)))
        return name

    def _rewrite(self, node: Node, top: bool = False) -> Node:
        if isinstance(node, (Num, Text, Var)):
            return node
        if isinstance(node, Param):
            self._repeat.add(_HIDDEN + "p:" + node.name)
            return Var(_HIDDEN + "p:" + node.name)
        if not self._is_rowdep(node):
            name = self._name(node, self._variant_steps, _param_vars(node))
            self._repeat.add(name)
            return Var(name)
        if node in self._hoisted:
            return Var(self._hoisted[node])
        rewritten = _rebuild(node, [self._rewrite(c) for c in children(node)])
        if self._shared[node] > 1 and not top:
            return Var(self._name(node, self._row_steps, rewritten))
        return rewritten

    # -- evaluation --------------------------------------------------------------------
    def parameters_of(self, values: Mapping[str, np.ndarray], count: int) -> dict[str, np.ndarray]:
        """The parameters with the template's derived values, per variant (NaN where a
        derived value is an error, as ``compute.derived_values`` holds it)."""
        params = {name: np.asarray(values[name], dtype=float) for name in self.parameters}
        for name, fn in self.derived:
            params[name] = fn(_columns(params), {}, count).val
        return params

    def evaluate(self, params: Mapping[str, np.ndarray], inputs: np.ndarray, count: int
                 ) -> tuple[dict[str, xm.XArray], xm.XArray]:
        """The Table's columns (flattened ``count * len(inputs)``) and the status."""
        n = len(inputs)
        variant = _columns(params)
        for name, fn in self._variant_steps:
            variant[name] = fn(variant, {}, count)
        rows: dict[str, xm.XArray] = {}
        for name in self._repeat:
            source = variant[name]
            rows[name] = xm.XArray(np.repeat(source.val, n), np.repeat(source.err, n),
                                   source.boolean)
        rows[self.input] = xm.array(np.tile(inputs, count))
        rows.update(self._rows(rows, {}, count * n))
        status = rows.pop("\x00status")
        return rows, status


def _param_vars(node: Node) -> Node:
    """The tree with each parameter read from a per-variant column."""
    if isinstance(node, Param):
        return Var(_HIDDEN + "p:" + node.name)
    kids = children(node)
    return _rebuild(node, [_param_vars(c) for c in kids]) if kids else node


def _columns(params: Mapping[str, np.ndarray]) -> dict[str, xm.XArray]:
    out = {}
    for name, value in params.items():
        key = name if name.startswith(_HIDDEN) else _HIDDEN + "p:" + name
        val = np.asarray(value, dtype=float)
        out[key] = xm.XArray(val, np.zeros(val.shape, np.uint8))
    return out
