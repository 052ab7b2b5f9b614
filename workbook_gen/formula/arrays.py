"""Array formulas ({=...} entered with Ctrl+Shift+Enter): Excel's array semantics.

In an array formula a reference is an array, not a value to intersect: operators apply
element by element (``A1:A3*B1:B3``), a function given an array where it takes one value
is applied to each element (``SIN(A1:A3)``, ``IF(A1:A3>0, ...)``), and functions that take
ranges (``SUM``, ``MATCH``, ``INDEX``) receive the arrays whole. Shapes broadcast as in
Excel: a single value or a one-row / one-column array stretches, a missing element of a
shorter array is #N/A. :func:`spread` lays the result over the formula's cells.
"""

from __future__ import annotations

from workbook_gen.formula.functions.availability import unavailable
from workbook_gen.formula import arraysfast, ast
from workbook_gen.formula import functions as fx
from workbook_gen.formula.functions.logical import lambdas
from workbook_gen.formula import values as xv
from workbook_gen.formula.scalar import Evaluator, use_array_evaluator
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

MAX_ELEMENTS = 1_000_000


def _shape(v) -> tuple[int, int]:
    return v.shape if isinstance(v, Range) else (1, 1)


def _multi(v) -> bool:
    """An array to map over: any array but a single cell's reference (an array of one,
    {1}, maps too: INDEX({2,3;4,5},{1}) is the one value 2, filling an array formula's
    cells, in Mac Excel 16's formulas__test.xlsx LOOKUP!AO54:AP54)."""
    return isinstance(v, Range) and (v.shape != (1, 1) or v.ref is None)


def element(v, i: int, j: int):
    """Element (i, j) of ``v`` broadcast to a larger shape (#N/A where it has none)."""
    if not isinstance(v, Range):
        return v
    rows, cols = v.shape
    if rows == 0 or cols == 0:
        return ExcelError.NA
    i = 0 if rows == 1 else i
    j = 0 if cols == 1 else j
    if i >= rows or j >= cols:
        return ExcelError.NA
    return v.rows[i][j]


def _broadcast(fn, values: list):
    """``fn(*elements)`` over the broadcast shape of ``values``, as an array Range."""
    shapes = [_shape(v) for v in values]
    rows = max(s[0] for s in shapes)
    cols = max(s[1] for s in shapes)
    if rows * cols > MAX_ELEMENTS:
        return ExcelError.NUM
    out = [[fn(*(element(v, i, j) for v in values)) for j in range(cols)]
           for i in range(rows)]
    return Range.array_of(out)


class ArrayEvaluator(Evaluator):
    """The scalar evaluator with array semantics (see the module doc)."""

    def arg(self, node: ast.Node):
        if isinstance(node, (ast.Unary, ast.Percent, ast.Binary)):
            return self.value(node)
        return super().arg(node)

    def value(self, node: ast.Node):
        if isinstance(node, ast.Binary):
            return self.binary(node)
        if isinstance(node, (ast.Unary, ast.Percent)):
            operand = self.arg(node.operand)
            if _multi(operand):
                one = (ast.Unary(node.op, ast.Missing()) if isinstance(node, ast.Unary)
                       else ast.Percent(ast.Missing()))
                return _broadcast(lambda x: self._scalar_op(one, x), [operand])
            return self._scalar_op(node, xv.scalar_of(operand))
        return super().value(node)

    def _scalar_op(self, node, x):
        if isinstance(node, ast.Unary):
            if node.op == "+":
                return x
            n = xv.to_number(x)
            return n if isinstance(n, ExcelError) else (-n + 0.0)
        n = xv.to_number(x)
        return n if isinstance(n, ExcelError) else n / 100.0

    def binary(self, node: ast.Binary):
        spine = []
        while isinstance(node, ast.Binary):
            spine.append(node)
            node = node.left
        acc = self.arg(node)
        for step in reversed(spine):
            right = self.arg(step.right)
            if _multi(acc) or _multi(right):
                fast = arraysfast.operate(step.op, acc if _multi(acc) else xv.scalar_of(acc),
                                          right if _multi(right) else xv.scalar_of(right),
                                          self.apply)
                acc = fast if fast is not None else _broadcast(
                    lambda a, b, op=step.op: self.apply(op, a, b), [acc, right])
            else:
                acc = self.apply(step.op, xv.scalar_of(acc), xv.scalar_of(right))
        return acc

    def func(self, node: ast.Func):
        entry = fx.REGISTRY.get(node.name)
        if entry is None or unavailable(node.name, node.prefix, self.dialect,
                                        self.ctx.workbook.stored):
            return super().func(node)
        if node.name in ("IF", "IFERROR", "IFNA"):
            return self._conditional(node)
        args = [None if entry.omitted and isinstance(a, ast.Missing) else self.arg(a)
                for a in node.args]
        if entry.lazy:  # IFS, SWITCH, CHOOSE, XLOOKUP...: mapped over element-wise but for
            # their range arguments (XLOOKUP's lookup and return arrays), when the first or a
            # scalar one (XLOOKUP's modes) is an array
            whole = [entry.kind(i) == "range" for i in range(len(args))]
            if not any(_multi(a) and (i == 0 or entry.kind(i) == "scalar")
                       for i, a in enumerate(args)):
                return fx.call(node.name, [lambda v=v: v for v in args], self.ctx)
            mapped = [i for i in range(len(args)) if not whole[i]]

            def each(*items):
                call = list(args)
                for i, item in zip(mapped, items):
                    call[i] = item
                result = fx.call(node.name, [lambda v=v: v for v in call], self.ctx)
                return xv.scalar_of(result) if isinstance(result, Range) else result
            return _broadcast(each, [args[i] for i in mapped])
        mapped = fx.registry.ARRAY_LIFTED.get(node.name)
        lifted = [i for i, a in enumerate(args) if _multi(a) and (
            entry.kind(i) == "scalar" or (mapped is not None and mapped(i)))]
        if not lifted:
            return fx.call(node.name, args, self.ctx)

        def one(*items):
            call = list(args)
            for i, item in zip(lifted, items):
                call[i] = item
            result = fx.call(node.name, call, self.ctx)
            return xv.scalar_of(result) if isinstance(result, Range) else result
        return _broadcast(one, [args[i] for i in lifted])

    def _conditional(self, node: ast.Func):
        args = node.args
        if node.name == "IF":
            if not 1 <= len(args) <= 3:
                return ExcelError.VALUE
            cond = self.arg(args[0])
            then = self.arg(args[1]) if len(args) > 1 else True
            other = self.arg(args[2]) if len(args) > 2 else False

            def pick(c, a, b):
                flag = xv.to_bool(c)
                if isinstance(flag, ExcelError):
                    return flag
                return a if flag else b
            if not (_multi(cond) or _multi(then) or _multi(other)):
                return pick(xv.scalar_of(cond), xv.scalar_of(then), xv.scalar_of(other))
            fast = _picked(cond, then, other)
            return fast if fast is not None else _broadcast(pick, [cond, then, other])
        if len(args) != 2:
            return ExcelError.VALUE
        value, fallback = self.arg(args[0]), self.arg(args[1])
        catch = ((lambda v: isinstance(v, ExcelError)) if node.name == "IFERROR"
                 else (lambda v: v is ExcelError.NA))

        def choose(v, f):
            return f if catch(v) else v
        if not (_multi(value) or _multi(fallback)):
            return choose(xv.scalar_of(value), xv.scalar_of(fallback))
        return _broadcast(choose, [value, fallback])


def _picked(cond, then, other):
    """IF over an array of booleans (a comparison's result, ``IF(C2:C9="ok", F2:F9)``)
    with branches that are arrays of its shape or single values: what ``_broadcast``
    gives, row by row without its per-element calls; None for anything else."""
    if not (isinstance(cond, Range) and _multi(cond)):
        return None
    shape = cond.shape
    if shape[0] * shape[1] > MAX_ELEMENTS or any(
            isinstance(b, Range) and b.shape != shape for b in (then, other)):
        return None
    if any(type(flag) is not bool for row in cond.rows for flag in row):
        return None
    cols = shape[1]
    then_rows = then.rows if isinstance(then, Range) else [(then,) * cols] * shape[0]
    other_rows = other.rows if isinstance(other, Range) else [(other,) * cols] * shape[0]
    return Range.array_of([[a if flag else b for flag, a, b in zip(flags, yes, no)]
                           for flags, yes, no in zip(cond.rows, then_rows, other_rows)])


def evaluate_array(node: ast.Node, resolver, dialect: str, cell) -> object:
    """The value of an array formula: a value or an array Range."""
    return lambdas.final(ArrayEvaluator(resolver, dialect, None, cell).arg(node))


# functions of one value that Excel applies to each cell of a range broadcast to the
# array formula's area, #N/A where the range has no cell: beyond it they show f(#N/A)
# (Mac Excel 16, formulas__test.xlsx INFORMATION!AW7: {=ISERR(C7:Q7)} is FALSE there)
_PADDED = frozenset({"ISERR", "ISERROR", "ISNA", "ISBLANK", "ISNUMBER", "ISTEXT",
                     "ISNONTEXT", "ISLOGICAL"})


def beyond(node, dialect: str = "excel"):
    """What an array formula shows beyond its result's shape: #N/A, or f(#N/A) for one of
    the functions above applied to one range."""
    while isinstance(node, ast.Paren):
        node = node.inner
    if dialect == "excel" and isinstance(node, ast.Func) and node.name in _PADDED \
            and len(node.args) == 1:
        return fx.call(node.name, [ExcelError.NA], fx.Context(dialect))
    return ExcelError.NA


def spread(value, rows: int, cols: int, pad=ExcelError.NA) -> list[list]:
    """The values an array formula shows in its ``rows`` x ``cols`` cells (a reference
    read only up to the used range is empty beyond it, not #N/A; ``pad`` beyond the
    value's shape: ``beyond``)."""
    if isinstance(value, Range) and value.shape == (1, 1):
        value = value.rows[0][0]
    ref = getattr(value, "ref", None)
    full = (ref.row2 - ref.row1 + 1, ref.col2 - ref.col1 + 1) if ref is not None else None
    shape = value.shape if isinstance(value, Range) else (1, 1)
    out = []
    for i in range(rows):
        row = []
        for j in range(cols):
            v = element(value, i, j)
            if v is ExcelError.NA and full is not None and _within(value, full, i, j):
                v = None
            elif pad is not ExcelError.NA and ((shape[0] > 1 and i >= shape[0])
                                               or (shape[1] > 1 and j >= shape[1])):
                v = pad
            row.append(0.0 if v is None else v)
        out.append(row)
    return out


def _within(value: Range, full: tuple[int, int], i: int, j: int) -> bool:
    rows, cols = value.shape
    i = 0 if full[0] == 1 else i
    j = 0 if full[1] == 1 else j
    return i < full[0] and j < full[1] and (i >= rows or j >= cols)


use_array_evaluator(ArrayEvaluator)
