"""LAMBDA, LET and the functions that call a LAMBDA: SCAN, REDUCE, MAP, BYROW, BYCOL,
MAKEARRAY (Excel 365; Microsoft lists them as logical functions). Excel saves their parameters as ``_xlpm.name``.

``LAMBDA(x, y, body)`` evaluates to a :class:`Closure`; the functions given one call it
with values, and the body is evaluated by the formula's own evaluator (so inside an array
formula operators stay element-wise) with the parameters bound: a name bound by LAMBDA
or LET is looked up before the workbook's defined names (:func:`bound`). A LAMBDA left
as a cell's value is ``#CALC!``, as in Excel. LAMBDA and LET are evaluated by
:func:`special` (they need their argument trees); the others are registered functions.

A defined name holding a LAMBDA is called by its name (``=WEEK(A1)``, ``=CAL_MONTH(1)``):
:func:`named` builds the LAMBDA in the calling evaluator, with none of the caller's
LAMBDA or LET names bound (the name's formula sees only the workbook's names), and
applies it to the arguments evaluated where the call is written.
"""

from __future__ import annotations

from workbook_gen.formula import ast
from workbook_gen.formula.functions.callables import Closure, Function
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

SPECIAL = frozenset({"LAMBDA", "LET"})
MAX_CALLS = 100_000  # elements a LAMBDA is applied to in one call (MAKEARRAY(1e6, 1e6, ...))


def bound(evaluator, node: ast.Name):
    """The value a LAMBDA or LET gave the name (or the function ``_xleta.NAME``), or
    None when it is not bound."""
    if node.sheet is None and node.name[:7].upper() == "_XLETA.":
        return Function(node.name[7:].upper(), evaluator)
    names = getattr(evaluator, "bound", None)
    if not names or node.sheet is not None:
        return None
    return names.get(node.name.upper())


def named(evaluator, node: ast.Func):
    """The call ``NAME(args)`` of a defined name holding a LAMBDA, or None when no name
    visible from the calling sheet holds one (an unknown function)."""
    tree = evaluator.ctx.workbook.name_node(node.name)
    while isinstance(tree, ast.Paren):
        tree = tree.inner
    if not (isinstance(tree, ast.Func) and tree.name == "LAMBDA"):
        return None
    saved = getattr(evaluator, "bound", None)
    evaluator.bound = None
    try:
        fn = special(evaluator, tree)
    finally:
        evaluator.bound = saved
    if not isinstance(fn, Closure):
        return fn
    return fn(*(evaluator.arg(a) for a in node.args))


def final(value):
    """A formula's value: a LAMBDA left uncalled is #CALC!."""
    return ExcelError.CALC if isinstance(value, (Closure, Function)) else value


def _param(node: ast.Node) -> str | None:
    return node.name.upper() if isinstance(node, ast.Name) and node.sheet is None else None


def special(evaluator, node: ast.Func):
    """LAMBDA(params..., body) or LET(name, value, ..., body)."""
    args = node.args
    env = dict(getattr(evaluator, "bound", None) or {})
    if node.name == "LAMBDA":
        params = [_param(a) for a in args[:-1]]
        if not args or None in params or len(set(params)) != len(params):
            return ExcelError.VALUE
        return Closure(params, args[-1], evaluator, env)
    if len(args) < 3 or len(args) % 2 == 0:  # LET
        return ExcelError.VALUE
    saved = getattr(evaluator, "bound", None)
    try:
        for name_node, value_node in zip(args[:-1:2], args[1:-1:2]):
            name = _param(name_node)
            if name is None:
                return ExcelError.VALUE
            evaluator.bound = env
            env = {**env, name: evaluator.arg(value_node)}
        evaluator.bound = env
        return evaluator.arg(args[-1])
    finally:
        evaluator.bound = saved


# -- the functions that call a LAMBDA (registered: arguments arrive evaluated) ----------------

def _rows(v) -> list[list] | ExcelError:
    if isinstance(v, ExcelError):
        return v
    if isinstance(v, Range):
        return [list(r) for r in v.rows]
    return [[v]]


def _one(v):
    """A LAMBDA's result where one value is needed (a 1x1 array is its value)."""
    if isinstance(v, Range):
        return v.rows[0][0] if v.shape == (1, 1) else ExcelError.CALC
    if isinstance(v, (Closure, Function)):
        return ExcelError.CALC
    return v


def _element(v):
    return 0.0 if v is None else v


def _calls(fn, count: int):
    if not isinstance(fn, (Closure, Function)):
        return ExcelError.VALUE
    if count > MAX_CALLS:
        return ExcelError.NUM
    return None


def _folded(array, fn) -> list[list] | ExcelError:
    """The rows SCAN and REDUCE fold ``fn`` over, or the error that stops them."""
    rows = _rows(array)
    if isinstance(rows, ExcelError):
        return rows
    bad = _calls(fn, sum(len(r) for r in rows))
    return rows if bad is None else bad


@register("LAMBDA", 1, 254, "lazy")
def _lambda(ctx, *args):  # evaluated by special(); reached only through fx.call
    return ExcelError.CALC


@register("LET", 3, 253, "lazy")
def _let(ctx, *args):
    return ExcelError.CALC


@register("SCAN", 3, 3, "range")
def _scan(ctx, initial, array, fn):
    rows = _folded(array, fn)
    if isinstance(rows, ExcelError):
        return rows
    acc = initial  # (an array too: the LAMBDA decides what to make of it)
    out = []
    for row in rows:
        line = []
        for x in row:
            acc = _one(fn(_element(acc), _element(x)))
            line.append(acc)
        out.append(line)
    return Range.array_of(out)


@register("REDUCE", 3, 3, "range")
def _reduce(ctx, initial, array, fn):
    rows = _folded(array, fn)
    if isinstance(rows, ExcelError):
        return rows
    acc = initial  # (an array too: the LAMBDA decides what to make of it)
    for row in rows:
        for x in row:
            acc = fn(_element(acc), _element(x))
            if isinstance(acc, (Closure, Function)):
                return ExcelError.CALC
    return acc


@register("MAP", 2, 254, "range")
def _map(ctx, *args):
    fn, arrays = args[-1], [_rows(a) for a in args[:-1]]
    for a in arrays:
        if isinstance(a, ExcelError):
            return a
    shape = (len(arrays[0]), len(arrays[0][0]) if arrays[0] else 0)
    if any((len(a), len(a[0]) if a else 0) != shape for a in arrays):
        return ExcelError.VALUE
    bad = _calls(fn, shape[0] * shape[1])
    if bad is not None:
        return bad
    return Range.array_of([[_one(fn(*(_element(a[i][j]) for a in arrays)))
                            for j in range(shape[1])] for i in range(shape[0])])


def _by(array, fn, by_row: bool):
    rows = _rows(array)
    if isinstance(rows, ExcelError):
        return rows
    lines = rows if by_row else [list(c) for c in zip(*rows)]
    bad = _calls(fn, len(lines))
    if bad is not None:
        return bad
    values = [_one(fn(Range.array_of([[_element(x) for x in line]] if by_row
                                      else [[_element(x)] for x in line])))
              for line in lines]
    return Range.array_of([[v] for v in values] if by_row else [values])


@register("BYROW", 2, 2, "range")
def _byrow(ctx, array, fn):
    return _by(array, fn, True)


@register("BYCOL", 2, 2, "range")
def _bycol(ctx, array, fn):
    return _by(array, fn, False)


@register("MAKEARRAY", 3, 3, ("scalar", "scalar", "range"))
def _makearray(ctx, rows, cols, fn):
    from workbook_gen.formula.functions import coerce
    if isinstance(rows, str) or isinstance(cols, str):
        return ExcelError.VALUE
    n, m = coerce.number(rows), coerce.number(cols)
    for v in (n, m):
        if isinstance(v, ExcelError):
            return v
    n, m = int(n), int(m)
    if n < 1 or m < 1:
        return ExcelError.VALUE
    bad = _calls(fn, n * m)
    if bad is not None:
        return bad
    return Range.array_of([[_one(fn(float(i), float(j))) for j in range(1, m + 1)]
                           for i in range(1, n + 1)])
