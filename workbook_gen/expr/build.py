"""Readable constructors for tree nodes: ``sqrt(x)``, ``atan2(x, y)``, ``if_(c, a, b)``.

Names follow Excel.  ``atan2(x, y)`` takes x first, as Excel's ATAN2 does.
"""

from __future__ import annotations

from .tree import Bin, Call, Node, Operand, wrap


def _call(fn: str, *args: Operand | str) -> Node:
    return Call(fn, tuple(wrap(a) for a in args))


def sin(x: Operand) -> Node: return _call("SIN", x)
def cos(x: Operand) -> Node: return _call("COS", x)
def tan(x: Operand) -> Node: return _call("TAN", x)
def asin(x: Operand) -> Node: return _call("ASIN", x)
def acos(x: Operand) -> Node: return _call("ACOS", x)
def atan(x: Operand) -> Node: return _call("ATAN", x)
def sqrt(x: Operand) -> Node: return _call("SQRT", x)
def abs_(x: Operand) -> Node: return _call("ABS", x)
def sign(x: Operand) -> Node: return _call("SIGN", x)
def radians(x: Operand) -> Node: return _call("RADIANS", x)
def degrees(x: Operand) -> Node: return _call("DEGREES", x)
def pi() -> Node: return _call("PI")
def mod(n: Operand, d: Operand) -> Node: return _call("MOD", n, d)
def power(x: Operand, y: Operand) -> Node: return _call("POWER", x, y)
def iserror(x: Operand) -> Node: return _call("ISERROR", x)
def iferror(x: Operand, fallback: Operand | str) -> Node: return _call("IFERROR", x, fallback)
def not_(x: Operand) -> Node: return _call("NOT", x)
def and_(*xs: Operand) -> Node: return _call("AND", *xs)
def or_(*xs: Operand) -> Node: return _call("OR", *xs)
def min_(*xs: Operand) -> Node: return _call("MIN", *xs)
def max_(*xs: Operand) -> Node: return _call("MAX", *xs)


def atan2(x: Operand, y: Operand) -> Node:
    """Angle of the vector (x, y): Excel's ATAN2 takes x first."""
    return _call("ATAN2", x, y)


def if_(condition: Operand, then: Operand | str, otherwise: Operand | str) -> Node:
    return _call("IF", condition, then, otherwise)


def root(x: Operand) -> Node:
    """x^0.5: the square root of an assembly condition.

    Written as ``^0.5`` rather than SQRT because both Excel and LibreOffice give
    #NUM! for a negative base, whereas LibreOffice's SQRT(-1) gives #VALUE!:
    a row that cannot be assembled then shows the same error in both engines.
    """
    return Bin("^", wrap(x), wrap(0.5))


def _cmp(op: str):
    def build(a: Operand | str, b: Operand | str) -> Node:
        return Bin(op, wrap(a), wrap(b))
    build.__name__ = {"=": "eq", "<>": "ne", "<": "lt", ">": "gt", "<=": "le", ">=": "ge"}[op]
    return build


eq, ne, lt, gt, le, ge = (_cmp(op) for op in ("=", "<>", "<", ">", "<=", ">="))


def concat(a: Operand | str, b: Operand | str) -> Node:
    return Bin("&", wrap(a), wrap(b))
