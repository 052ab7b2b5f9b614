"""Print a tree as ONE generated Python function over numpy arrays (``compiled``).

The same values and error codes as ``numeric.compile_numpy`` (the closure printer, the
reference), bit for bit, at a fraction of the cost per variant: the function is
generated once per tree and process (each distinct subtree computed once, ``np.errstate``
entered once per call, not per operation), and every operation first tries a plain
float path:

    where no operand has an error (and none is text), an operation computes exactly
    what its ``xlmath`` kernel computes (the same numpy or C-library call on the same
    values); when the result is all finite, that kernel would mark nothing, so its
    value (with -0 made +0, as ``kernels.finish`` does) is the kernel's, with no error.

Anything else (an operand with an error or text, a non-finite result, a domain or
division failure, a boolean compared with a number) goes to the ``xlmath`` function
itself: the kernels stay the one definition of Excel's semantics.  Internally a value is
``(val, err, boolean)`` with ``err`` None meaning "a float array with no error".
"""

from __future__ import annotations

import math
import re
from typing import Callable

import numpy as np

from .. import xlmath as xm
from ..xlmath import kernels
from .tree import Bin, Call, Neg, Node, Num, Param, Text, Var, children, walk

try:  # the C function (``np.count_nonzero`` is a Python wrapper around it)
    from numpy._core.multiarray import count_nonzero as _count
except ImportError:  # pragma: no cover - numpy < 2
    _count = np.count_nonzero

_isfinite = np.isfinite
_UINT8 = np.uint8


def _finite(v: np.ndarray) -> bool:
    return _count(_isfinite(v)) == v.size


def _light(a: xm.XArray) -> tuple:
    """An XArray as (val, err or None, boolean)."""
    if a.val.dtype != object and not _count(a.err):
        return a.val, None, a.boolean
    return a.val, a.err, a.boolean


def _heavy(a: tuple) -> xm.XArray:
    val, err, boolean = a
    return xm.XArray(val, np.zeros(val.shape, _UINT8) if err is None else err, boolean)


def _slow(fn, *args: tuple) -> tuple:
    """The ``xlmath`` function itself (errors, text, non-finite results); a scalar
    literal (``generate_set(..., scalars=True)``) becomes its column first."""
    if any(a[0].ndim == 0 for a in args):
        args = _columns(*args)
    return _light(fn(*(_heavy(a) for a in args)))


def _scalar(value: float) -> tuple:
    """A numeric literal as a numpy scalar (no column): numpy broadcasts it with the
    same float64 operation on every element, so the values are the column's."""
    return np.float64(value), None, False


def _columns(*args: tuple) -> list[tuple]:
    """The operands with every scalar literal made a column (as ``_const``)."""
    size = max((a[0].shape for a in args), key=len)
    return [(np.full(size, a[0]), a[1], a[2]) if a[0].ndim == 0 else a for a in args]



def _const(value, n: int) -> tuple:
    if isinstance(value, str):
        return _light(xm.const(value, n))
    return np.full(n, float(value)), None, False   # xm.const: no error, even for NaN


def _var(a: xm.XArray) -> tuple:
    return _light(a)


def _arith(op: str, fn):
    slow = {"+": xm.add, "-": xm.sub, "*": xm.mul, "/": xm.div}[op]

    def apply(a: tuple, b: tuple) -> tuple:
        # kernels.arith: first_error of two clean operands is clean; a division by zero
        # gives +-inf or NaN, so an all-finite result had no fresh #DIV/0! either
        if a[1] is None and b[1] is None:
            v = fn(a[0], b[0])
            if _finite(v):
                v += 0.0
                return v, None, False
        return _slow(slow, a, b)
    return apply


ADD, SUB, MUL, DIV = (_arith(op, fn) for op, fn in
                      (("+", np.add), ("-", np.subtract), ("*", np.multiply),
                       ("/", np.true_divide)))


def POW(a: tuple, b: tuple) -> tuple:
    """kernels.power where no negative base has a fractional exponent and every zero
    base has a positive exponent: the kernel's value is POW(x, y) (computed there only
    where the base is not 0, element by element) with 0 where the base is 0.  A scalar
    literal is made a column first: numpy's power has its own loop for a scalar
    exponent (x ^ 2 as x * x), which differs from pow in the last bit."""
    if a[0].ndim == 0 or b[0].ndim == 0:
        a, b = _columns(a, b)
    if a[1] is None and b[1] is None:
        x, y = a[0], b[0]
        if not _count((x < 0) & (np.floor(y) != y)):
            zero = x == 0
            if not _count(zero):
                v = kernels.POW(x, y)
                if _finite(v):
                    return v + 0.0, None, False
            elif not _count(zero & ~(y > 0)):
                v = np.where(zero, 0.0, kernels.POW(x, y))
                if _finite(v):
                    return v + 0.0, None, False
    return _slow(xm.power, a, b)


def NEG(a: tuple) -> tuple:
    if a[1] is None:
        v = -a[0]
        if _finite(v):
            v += 0.0
            return v, None, False
    return _slow(xm.neg, a)


def _unary(name: str):
    fn, slow = kernels.UNARY[name], getattr(xm, {"ABS": "abs_"}.get(name, name.lower()))

    def apply(a: tuple) -> tuple:
        # kernels.unary: a domain failure or a trig argument past the limit is NaN there
        if a[1] is None:
            v = fn(a[0])
            if _finite(v):
                return v + 0.0, None, False
        return _slow(slow, a)
    return apply


UNARY = {name: _unary(name) for name in kernels.UNARY}


def ATAN2(a: tuple, b: tuple) -> tuple:
    if a[0].ndim == 0 or b[0].ndim == 0:   # as POW: the kernel's loop over two columns
        a, b = _columns(a, b)
    if a[1] is None and b[1] is None:
        x, y = a[0], b[0]
        if not _count((x == 0) & (y == 0)):
            v = kernels.ATAN2_YX(y, x)
            if _finite(v):
                return v + 0.0, None, False
    return _slow(xm.atan2, a, b)


def MOD(a: tuple, b: tuple) -> tuple:
    if a[1] is None and b[1] is None:
        x, y = a[0], b[0]
        v = x - y * np.floor(x / y)   # y = 0 makes it NaN: the slow path marks #DIV/0!
        if _finite(v):
            v += 0.0
            return v, None, False
    return _slow(xm.mod, a, b)


_COMPARE = {"=": np.equal, "<>": np.not_equal, "<": np.less, ">": np.greater,
            "<=": np.less_equal, ">=": np.greater_equal}


def _compare(op: str):
    fn = _COMPARE[op]

    def apply(a: tuple, b: tuple) -> tuple:
        if a[1] is None and b[1] is None and a[2] == b[2]:
            return np.asarray(fn(a[0], b[0]), dtype=float) + 0.0, None, True
        return _slow(lambda p, q: xm.compare(op, p, q), a, b)
    return apply


COMPARE = {op: _compare(op) for op in _COMPARE}


def IF(c: tuple, t: tuple, o: tuple) -> tuple:
    """xm.where with a clean condition and clean numeric branches."""
    if c[1] is None and t[1] is None and o[1] is None:
        v = np.where(c[0] != 0, t[0], o[0])
        if _finite(v):
            v += 0.0
            return v, None, t[2] and o[2]
    return _slow(xm.where, c, t, o)


def ISERROR(a: tuple) -> tuple:
    if a[1] is None and a[0].ndim:
        return np.zeros(a[0].shape), None, True
    return _slow(xm.iserror, a)


def NOT(a: tuple) -> tuple:
    if a[1] is None and a[0].ndim:
        return (a[0] == 0).astype(float) + 0.0, None, True
    return _slow(xm.not_, a)


def _logical(ufunc):
    def apply(*args: tuple) -> tuple:
        if any(a[0].ndim == 0 for a in args):
            args = _columns(*args)
        if all(a[1] is None for a in args):
            r = ufunc.reduce(np.array([a[0] != 0 for a in args]), axis=0)
            return r.astype(float) + 0.0, None, True
        return _slow(lambda *xs: xm.logical(ufunc, *xs), *args)
    return apply


def _extreme(ufunc):
    def apply(*args: tuple) -> tuple:
        if any(a[0].ndim == 0 for a in args):
            args = _columns(*args)
        if all(a[1] is None for a in args):
            v = ufunc.reduce(np.array([a[0] for a in args]), axis=0)
            if _finite(v):
                return v + 0.0, None, False
        return _slow(lambda *xs: xm.extreme(ufunc, *xs), *args)
    return apply


def IFERROR(a: tuple, b: tuple) -> tuple:
    return _slow(xm.iferror, a, b)


_BINARY = {"+": "ADD", "-": "SUB", "*": "MUL", "/": "DIV", "^": "POW"}
_CALLS = {"ATAN2": "ATAN2", "MOD": "MOD", "POWER": "POW", "IF": "IF", "ISERROR": "ISERROR",
          "NOT": "NOT", "IFERROR": "IFERROR", "AND": "AND", "OR": "OR", "MIN": "MIN",
          "MAX": "MAX"}
_NAMESPACE = {
    "np": np, "_errstate": np.errstate, "_const": _const, "_var": _var, "_heavy": _heavy,
    "_scalar": _scalar,
    "ADD": ADD, "SUB": SUB, "MUL": MUL, "DIV": DIV, "POW": POW, "NEG": NEG,
    "UNARY": UNARY, "COMPARE": COMPARE, "ATAN2": ATAN2, "MOD": MOD, "IF": IF,
    "ISERROR": ISERROR, "NOT": NOT, "IFERROR": IFERROR,
    "AND": _logical(np.logical_and), "OR": _logical(np.logical_or),
    "MIN": _extreme(np.minimum), "MAX": _extreme(np.maximum),
}


_PI = Call("PI", ())


def _two_columns(node: Node) -> bool:
    return (isinstance(node, Bin) and node.op == "^") or (
        isinstance(node, Call) and node.fn in ("POWER", "ATAN2"))


def _negative_zero(tree: Node) -> bool:
    return any(isinstance(k, Num) and math.copysign(1.0, k.value) < 0 for k in walk(tree))


def _print(tree: Node, names: dict | None = None, lines: list | None = None,
           scalars: bool = False) -> tuple[list[str], list[Node] | None, str]:
    """One line per distinct subtree, children first: the lines, the subtrees in order
    (None where a tree holds a -0 literal: see below) and the root's name.  ``names``
    and ``lines``: those of trees printed before into the same function (a Var whose
    name is in ``names`` reads that local)."""
    names = {} if names is None else names
    lines = [] if lines is None else lines
    nodes: list[Node] = []
    # Equal subtrees are computed once; Num(0.0) == Num(-0.0) but their columns differ
    # in sign, so a tree holding a -0 literal is printed without sharing.
    negative_zero = _negative_zero(tree)
    key = id if negative_zero else (lambda node: node)
    varies: dict[Node, bool] = {}

    def varying(node: Node) -> bool:
        """Whether ``node`` reads a column (its value is a column, never a scalar)."""
        known = varies.get(node)
        if known is None:
            known = isinstance(node, (Var, Param, Text)) or any(map(varying, children(node)))
            varies[node] = known
        return known

    def emit(node: Node, scalar: bool = False) -> str:
        # ``scalar``: a literal operand of an operation that also reads a column (numpy
        # broadcasts it; every operation's result is still a column)
        literal = scalar and (isinstance(node, Num) or node == _PI)
        found = names.get(("scalar", key(node)) if literal else key(node))
        if found is not None:
            return found
        # POW and ATAN2 take two columns (see POW): their literals are columns, made
        # once per call of the function like any shared subtree
        inner = scalars and varying(node) and not _two_columns(node)
        args = [emit(k, inner) for k in children(node)]
        if literal:
            expr = f"_scalar({'np.pi' if node == _PI else repr(node.value)})"
        elif isinstance(node, (Num, Text)):
            expr = f"_const({node.value!r}, n)"
        elif isinstance(node, Param):
            expr = f"_const(params[{node.name!r}], n)"
        elif isinstance(node, Var):
            expr = f"_var(cols[{node.name!r}])"
        elif isinstance(node, Neg):
            expr = f"NEG({args[0]})"
        elif isinstance(node, Bin) and node.op in _BINARY:
            expr = f"{_BINARY[node.op]}({args[0]}, {args[1]})"
        elif isinstance(node, Bin) and node.op in COMPARE:
            expr = f"COMPARE[{node.op!r}]({args[0]}, {args[1]})"
        elif isinstance(node, Bin):
            raise NotImplementedError("text concatenation is not used in trees")
        elif node.fn == "PI":
            expr = "_const(np.pi, n)"
        elif node.fn in kernels.UNARY:
            expr = f"UNARY[{node.fn!r}]({args[0]})"
        else:
            expr = f"{_CALLS[node.fn]}({', '.join(args)})"
        name = f"t{len(lines)}"
        names[("scalar", key(node)) if literal else key(node)] = name
        nodes.append(node)
        lines.append(f"        {name} = {expr}")
        return name

    last = emit(tree)
    return lines, (None if negative_zero else nodes), last


def source(tree: Node) -> str:
    """The generated function's text."""
    if isinstance(tree, Var):  # the column itself, as compile_numpy gives it
        return f"def f(cols, params, n):\n    return cols[{tree.name!r}]\n"
    lines, _, last = _print(tree)
    return ("def f(cols, params, n):\n    with _errstate(all='ignore'):\n"
            + "\n".join(lines) + f"\n    return _heavy({last})\n")


def _compile(text: str) -> Callable:
    scope = dict(_NAMESPACE)
    exec(compile(text, "<tree>", "exec"), scope)
    return scope["f"]


def generate(tree: Node) -> Callable:
    """``f(columns, params, n) -> XArray``, as ``numeric.compile_numpy(tree)``."""
    return _compile(source(tree))


def generate_subtrees(tree: Node) -> tuple[Callable, list[Node]] | None:
    """``f(columns, params, n)`` -> the (val, err or None, boolean) of every distinct
    subtree of ``tree``, in the order of the list returned with it (each as
    ``compile_numpy(subtree)`` gives it); None for a tree holding a -0 literal."""
    found = generate_subtrees_of((tree,))
    return None if found is None else found[:2]


def generate_subtrees_of(trees: tuple[Node, ...]) -> tuple[Callable, list[Node], list[int]] | None:
    """``generate_subtrees`` over several trees at once (the distinct subtrees of all of
    them, each once), and the index of each tree's root in the list."""
    names: dict = {}
    lines: list[str] = []
    nodes: list[Node] = []
    roots = []
    for tree in trees:
        _, new, last = _print(tree, names, lines)
        if new is None:
            return None
        nodes += new
        roots.append(int(last[1:]))
    listed = ", ".join(f"t{i}" for i in range(len(nodes)))
    return _compile("def f(cols, params, n):\n    with _errstate(all='ignore'):\n"
                    + "\n".join(lines) + f"\n    return ({listed},)\n"), nodes, roots


def _one_by_one(named: tuple[tuple[str, Node], ...]) -> Callable:
    each = [(name, generate(tree)) for name, tree in named]

    def f(cols, params, n):
        cols, out = dict(cols), {}
        for name, tree_f in each:
            out[name] = cols[name] = tree_f(cols, params, n)
        return out
    return f


def generate_set(named: tuple[tuple[str, Node], ...], scalars: bool = False) -> Callable:
    """``f(columns, params, n) -> {name: XArray}`` for trees evaluated in order, each as
    ``numeric.compile_numpy(tree)(columns, params, n)`` gives it with the results of the
    trees before it added to ``columns`` under their names: one function for a whole
    set (a scene's Table columns, the Checks' terms and residuals), each distinct
    subtree once.  (Tree by tree where a -0 literal or a name read before it is given
    would make sharing subtrees wrong.)  ``scalars``: numeric literals are numpy scalars
    that numpy broadcasts, not columns of ``n`` copies (the same bits, less memory
    traffic; every result is still a column)."""
    if any(_negative_zero(tree) for _, tree in named):
        return _one_by_one(named)
    names: dict = {}
    lines: list[str] = []
    results = []
    for name, tree in named:
        if Var(name) in names:   # read from the columns before: shared subtrees would lie
            return _one_by_one(named)
        if isinstance(tree, Var) and Var(tree.name) not in names:
            given = f"cols[{tree.name!r}]"   # the column itself, as compile_numpy gives it
            results.append((name, given))
            lines.append(f"        t{len(lines)} = _var({given})")
            names[Var(name)] = f"t{len(lines) - 1}"
            continue
        _, _, last = _print(tree, names, lines, scalars)
        results.append((name, f"_heavy({last})"))
        names[Var(name)] = last
    out = ", ".join(f"{n!r}: {r}" for n, r in results)
    if scalars:
        lines = _freeing(lines, {r[len("_heavy("):-1] for _, r in results})
    return _compile("def f(cols, params, n):\n    with _errstate(all='ignore'):\n"
                    + "\n".join(lines) + f"\n        return {{{out}}}\n")


_LOCAL = re.compile(r"\bt(\d+)\b")


def _freeing(lines: list[str], kept: set[str]) -> list[str]:
    """The lines with each local that is not a result deleted after its last reader
    (a block's columns are large: they go back to the allocator as soon as they can)."""
    last: dict[str, int] = {}
    for i, line in enumerate(lines):
        for match in _LOCAL.finditer(line):
            last[match.group(0)] = i
    after: dict[int, list[str]] = {}
    for name, i in last.items():
        if name not in kept:
            after.setdefault(i, []).append(name)
    out = []
    for i, line in enumerate(lines):
        out.append(line)
        if i in after:
            out.append(f"        del {', '.join(sorted(after[i]))}")
    return out
