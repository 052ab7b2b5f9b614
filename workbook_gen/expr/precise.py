"""Print a tree as an mpmath function: the formula at high precision.

``compile_mpmath(tree)`` returns ``f(values, params) -> mpf | ExcelError``,
evaluated in the caller's ``mpmath.mp`` precision.  It is the formula's own
high-precision value (for the float64 against precision study), not the
independent reference of the mechanics, which lives in ``reference``.
"""

from __future__ import annotations

from typing import Callable, Mapping

import mpmath

from ..xlerror import ExcelError
from .tree import Bin, Call, Neg, Node, Num, Param, Text, Var

Value = "mpmath.mpf | str | ExcelError"
Compiled = Callable[[Mapping[str, object], Mapping[str, object]], object]


class _Error(Exception):
    def __init__(self, error: ExcelError):
        self.error = error


def _domain(ok: bool, error: ExcelError = ExcelError.NUM) -> None:
    if not ok:
        raise _Error(error)


def _div(x, y):
    _domain(y != 0, ExcelError.DIV0)
    return x / y


def _pow(x, y):
    _domain(not (x == 0 and y == 0))
    _domain(not (x == 0 and y < 0), ExcelError.DIV0)
    _domain(not (x < 0 and mpmath.floor(y) != y))
    return mpmath.power(x, y)


def _atan2(x, y):
    _domain(not (x == 0 and y == 0), ExcelError.DIV0)
    return mpmath.atan2(y, x)


def _sqrt(x):
    _domain(x >= 0)
    return mpmath.sqrt(x)


def _asin(x):
    _domain(-1 <= x <= 1)
    return mpmath.asin(x)


def _acos(x):
    _domain(-1 <= x <= 1)
    return mpmath.acos(x)


def _mod(n, d):
    _domain(d != 0, ExcelError.DIV0)
    return n - d * mpmath.floor(n / d)


_FUNCS = {
    "SIN": mpmath.sin, "COS": mpmath.cos, "TAN": mpmath.tan, "ATAN": mpmath.atan,
    "ASIN": _asin, "ACOS": _acos, "SQRT": _sqrt, "ABS": abs, "SIGN": mpmath.sign,
    "RADIANS": lambda x: x * mpmath.pi / 180, "DEGREES": lambda x: x * 180 / mpmath.pi,
    "ATAN2": _atan2, "MOD": _mod, "POWER": _pow, "PI": lambda: +mpmath.pi,
    "MIN": min, "MAX": max, "NOT": lambda x: int(not x),
    "AND": lambda *a: int(all(a)), "OR": lambda *a: int(any(a)),
}
_BIN = {"+": lambda x, y: x + y, "-": lambda x, y: x - y, "*": lambda x, y: x * y,
        "/": _div, "^": _pow, "=": lambda x, y: int(x == y), "<>": lambda x, y: int(x != y),
        "<": lambda x, y: int(x < y), ">": lambda x, y: int(x > y),
        "<=": lambda x, y: int(x <= y), ">=": lambda x, y: int(x >= y)}


def _eval(node: Node, values, params):
    if isinstance(node, Num):
        return mpmath.mpf(node.value)
    if isinstance(node, Text):
        return node.value
    if isinstance(node, Param):
        return mpmath.mpf(params[node.name])
    if isinstance(node, Var):
        value = values[node.name]
        if isinstance(value, ExcelError):
            raise _Error(value)
        return value
    if isinstance(node, Neg):
        return -_eval(node.operand, values, params)
    if isinstance(node, Bin):
        return _BIN[node.op](_eval(node.left, values, params), _eval(node.right, values, params))
    if isinstance(node, Call):
        if node.fn == "IF":
            branch = 1 if _eval(node.args[0], values, params) else 2
            if branch == 2 and len(node.args) == 2:
                return 0
            return _eval(node.args[branch], values, params)
        if node.fn in ("ISERROR", "IFERROR"):
            try:
                value = _eval(node.args[0], values, params)
            except _Error:
                return 1 if node.fn == "ISERROR" else _eval(node.args[1], values, params)
            return 0 if node.fn == "ISERROR" else value
        return _FUNCS[node.fn](*(_eval(a, values, params) for a in node.args))
    raise TypeError(f"cannot evaluate {node!r}")


def compile_mpmath(node: Node) -> Compiled:
    def evaluate(values, params):
        try:
            return _eval(node, values, params)
        except _Error as exc:
            return exc.error
    return evaluate
