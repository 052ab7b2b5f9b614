"""Print a tree as a numpy function (Excel semantics, error masks).

``compile_numpy(tree)`` returns ``f(columns, params, n) -> XArray`` where
``columns`` maps quantity names to XArrays of the rows and ``params`` maps
parameter names to floats.  Used for the cached values and ``compute()``.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Callable, Mapping

import numpy as np

from .. import xlmath as xm
from . import fastnum
from .tree import Bin, Call, Neg, Node, Num, Param, Text, Var

Columns = Mapping[str, xm.XArray]
Params = Mapping[str, float]
Compiled = Callable[[Columns, Params, int], xm.XArray]

_BINARY = {"+": xm.add, "-": xm.sub, "*": xm.mul, "/": xm.div, "^": xm.power}
_UNARY = {"SIN": xm.sin, "COS": xm.cos, "TAN": xm.tan, "ASIN": xm.asin, "ACOS": xm.acos,
          "ATAN": xm.atan, "SQRT": xm.sqrt, "ABS": xm.abs_, "SIGN": xm.sign,
          "RADIANS": xm.radians, "DEGREES": xm.degrees, "NOT": xm.not_,
          "ISERROR": xm.iserror}
_PAIR = {"ATAN2": xm.atan2, "MOD": xm.mod, "POWER": xm.power, "IFERROR": xm.iferror}
_MANY = {"AND": lambda *a: xm.logical(np.logical_and, *a),
         "OR": lambda *a: xm.logical(np.logical_or, *a),
         "MIN": lambda *a: xm.extreme(np.minimum, *a),
         "MAX": lambda *a: xm.extreme(np.maximum, *a)}


def compile_numpy(node: Node) -> Compiled:
    if isinstance(node, Num):
        value = node.value
        return lambda cols, params, n: xm.const(value, n)
    if isinstance(node, Text):
        text = node.value
        return lambda cols, params, n: xm.const(text, n)
    if isinstance(node, Param):
        name = node.name
        return lambda cols, params, n: xm.const(params[name], n)
    if isinstance(node, Var):
        name = node.name
        return lambda cols, params, n: cols[name]
    if isinstance(node, Neg):
        operand = compile_numpy(node.operand)
        return lambda cols, params, n: xm.neg(operand(cols, params, n))
    if isinstance(node, Bin):
        left, right = compile_numpy(node.left), compile_numpy(node.right)
        if node.op in _BINARY:
            fn = _BINARY[node.op]
            return lambda cols, params, n: fn(left(cols, params, n), right(cols, params, n))
        if node.op == "&":
            raise NotImplementedError("text concatenation is not used in trees")
        op = node.op
        return lambda cols, params, n: xm.compare(op, left(cols, params, n),
                                                  right(cols, params, n))
    if isinstance(node, Call):
        return _compile_call(node)
    raise TypeError(f"cannot compile {node!r}")


def _compile_call(node: Call) -> Compiled:
    args = [compile_numpy(a) for a in node.args]
    fn = node.fn
    if fn == "PI":
        return lambda cols, params, n: xm.const(np.pi, n)
    if fn == "IF":
        # always three (expr/tree.py): Excel's IF(c, x) is FALSE where c is false, not 0
        cond, then, otherwise = args
        return lambda cols, params, n: xm.where(cond(cols, params, n), then(cols, params, n),
                                                otherwise(cols, params, n))
    if fn in _UNARY:
        f1, a = _UNARY[fn], args[0]
        return lambda cols, params, n: f1(a(cols, params, n))
    if fn in _PAIR:
        f2, a, b = _PAIR[fn], args[0], args[1]
        return lambda cols, params, n: f2(a(cols, params, n), b(cols, params, n))
    fm = _MANY[fn]
    return lambda cols, params, n: fm(*(a(cols, params, n) for a in args))


#: The tree as one generated function (``fastnum``: the same bits as ``compile_numpy``,
#: which stays the reference), once per tree in a process (trees are hashable, their
#: hash cached): a batch evaluates the same template's trees for every variant.
compiled = lru_cache(maxsize=4096)(fastnum.generate)

#: Trees evaluated in order, each seeing those before it as columns (``fastnum.generate_set``:
#: one generated function for a scene's Table columns, or the Checks' terms and residuals).
compiled_set = lru_cache(maxsize=256)(fastnum.generate_set)
