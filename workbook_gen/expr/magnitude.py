"""The magnitudes a tree's arithmetic cancels, row by row: its rounding noise is about
eps times this (the Summary's tie threshold; SPEC 5).

    m(a +- b) = m(a) + m(b)     m(a * b) = |b| m(a) + |a| m(b)
    m(a / b)  = m(a) / |b| + |a| m(b) / b^2     m(f(a)) = |f'(a)| m(a) + |f(a)|

Quantities and parameters a tree reads count at their own size.  A shaking force of
a balanced four-bar, sum m_i a_i = 1e-16 N from terms near 1 N, has m near 1 N.
"""

from __future__ import annotations

from typing import Mapping

import numpy as np

from .. import xlmath as xm
from .numeric import compile_numpy
from .tree import Bin, Call, Neg, Node, Num, Param, Var

_DERIVATIVE = {
    "SIN": np.cos, "COS": lambda a: -np.sin(a), "TAN": lambda a: 1.0 / np.cos(a) ** 2,
    "ASIN": lambda a: 1.0 / np.sqrt(1.0 - a * a), "ACOS": lambda a: 1.0 / np.sqrt(1.0 - a * a),
    "ATAN": lambda a: 1.0 / (1.0 + a * a), "SQRT": lambda a: 0.5 / np.sqrt(a),
    "ABS": np.ones_like, "SIGN": np.zeros_like,
    "RADIANS": lambda a: np.full_like(a, np.pi / 180.0),
    "DEGREES": lambda a: np.full_like(a, 180.0 / np.pi),
}


def magnitude(node: Node, columns: Mapping[str, xm.XArray], params: Mapping[str, float],
              n: int) -> np.ndarray:
    """Per row, the magnitude of what ``node`` adds and cancels (NaN where an error)."""
    with np.errstate(all="ignore"):
        return np.abs(_m(node, columns, params, n))


def _value(node: Node, columns, params, n) -> np.ndarray:
    result = compile_numpy(node)(columns, params, n)
    return np.where(result.err != 0, np.nan, np.asarray(result.val, dtype=float)) \
        if not result.is_text else np.zeros(n)


def _m(node: Node, columns, params, n) -> np.ndarray:
    if isinstance(node, (Num, Param, Var)):
        return np.abs(_value(node, columns, params, n))
    if isinstance(node, Neg):
        return _m(node.operand, columns, params, n)
    if isinstance(node, Bin):
        ma, mb = _m(node.left, columns, params, n), _m(node.right, columns, params, n)
        a, b = _value(node.left, columns, params, n), _value(node.right, columns, params, n)
        if node.op in ("+", "-"):
            return ma + mb
        if node.op == "*":
            return np.abs(b) * ma + np.abs(a) * mb
        if node.op == "/":
            return ma / np.abs(b) + np.abs(a) * mb / (b * b)
        if node.op == "^" and isinstance(node.right, Num):
            return np.abs(b * np.power(a, b - 1)) * ma + np.abs(np.power(a, b))
        return np.abs(_value(node, columns, params, n))
    if isinstance(node, Call):
        if node.fn == "IF" and len(node.args) == 3:
            cond = _value(node.args[0], columns, params, n)
            return np.where(cond != 0, _m(node.args[1], columns, params, n),
                            _m(node.args[2], columns, params, n))
        if node.fn in _DERIVATIVE:
            a = _value(node.args[0], columns, params, n)
            return (np.abs(_DERIVATIVE[node.fn](a)) * _m(node.args[0], columns, params, n)
                    + np.abs(_value(node, columns, params, n)))
        if node.fn == "ATAN2":
            x, y = (_value(arg, columns, params, n) for arg in node.args)
            mx, my = (_m(arg, columns, params, n) for arg in node.args)
            return (np.abs(y) * mx + np.abs(x) * my) / (x * x + y * y) + np.abs(
                _value(node, columns, params, n))
        if node.fn in ("MIN", "MAX"):
            return np.max([_m(arg, columns, params, n) for arg in node.args], axis=0)
    return np.abs(_value(node, columns, params, n))
