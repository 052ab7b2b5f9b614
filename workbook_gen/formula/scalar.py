"""A plain cell-by-cell evaluator of a formula AST with Excel's semantics.

``evaluate(node, resolver)`` computes one cell. The resolver supplies cell values,
range values (2-D lists) and defined names; values are ``float | str | bool | None
| ExcelError``. Errors propagate, leftmost operand first. A function outside the
supported list gives ``#NAME?`` and is reported through ``on_unsupported`` (or
listed beforehand with :func:`unsupported_functions`), never raised.

This is the reference path: the vectorised evaluator must agree with it.
"""

from __future__ import annotations

from typing import Callable

from workbook_gen.formula.functions.availability import unavailable
from workbook_gen.formula import ast
from workbook_gen.formula import functions as fx
from workbook_gen.formula.functions.logical import lambdas
from workbook_gen.formula import values as xv
from workbook_gen.formula.resolver import Resolver
from workbook_gen.formula.values import Range, Ref, Value
from workbook_gen.formula.tokenizer import CELL_PARTS, column_number, split_sheet
from workbook_gen.xlerror import ExcelError

_COMPARISONS = {
    "=": lambda c: c == 0, "<>": lambda c: c != 0, "<": lambda c: c < 0,
    ">": lambda c: c > 0, "<=": lambda c: c <= 0, ">=": lambda c: c >= 0,
}



# The evaluator of array formulas (formula/arrays.py's ArrayEvaluator, a subclass of
# Evaluator below), for the functions that take array expressions without array entry
# (SUMPRODUCT(A1:A3*B1:B3)): arrays.py registers it when imported (the package imports
# it), so that this module needs nothing of the one built on it.
_ARRAY_EVALUATOR: list = []


def use_array_evaluator(cls) -> None:
    """Register the array-formula evaluator (called once, by formula/arrays.py)."""
    _ARRAY_EVALUATOR[:] = [cls]


class DictResolver(Resolver):
    """A resolver over dicts, for tests and small uses.

    ``cells`` maps ``"A1"`` or ``"Sheet!A1"`` to values (unqualified keys and
    references belong to ``sheet``); ``names`` maps names (any case) to values or
    2-D lists.
    """

    def __init__(self, cells: dict[str, Value] | None = None,
                 names: dict[str, Value | list] | None = None, sheet: str = "Sheet1"):
        self.sheet = sheet
        self.cells: dict[tuple[str, int, int], Value] = {}
        for key, value in (cells or {}).items():
            sheet_name, body = split_sheet(key)
            m = CELL_PARTS.fullmatch(body)
            if m is None:
                raise ValueError(f"not a cell address: {key!r}")
            self.cells[(sheet_name or sheet, int(m.group(4)), column_number(m.group(2)))] = value
        self.names = {k.upper(): v for k, v in (names or {}).items()}

    def cell(self, sheet, row, col):
        return self.cells.get((sheet or self.sheet, row, col))

    def name(self, name, sheet):
        return self.names.get(name.upper(), ExcelError.NAME)


def unsupported_functions(node: ast.Node) -> set[str]:
    """Names of the functions ``node`` calls that are outside the supported list."""
    return {n.name for n in ast.walk(node)
            if isinstance(n, ast.Func) and (n.name not in fx.SUPPORTED or (
                fx.REGISTRY[n.name].accepts is not None
                and not fx.REGISTRY[n.name].accepts(n.args)))}


def evaluate(node: ast.Node, resolver: Resolver, *, dialect: str = "excel",
             on_unsupported: Callable[[str], None] | None = None,
             cell: tuple[str, int, int] | None = None) -> Value:
    """The value of the formula ``node`` (an empty result counts as 0, as in Excel).

    ``dialect="libreoffice"`` applies LibreOffice's known deviations.
    ``on_unsupported(name)`` is called for each call of an unsupported function.
    ``cell`` is the formula's own ``(sheet, row, col)``: ROW(), COLUMN() and implicit
    intersection need it.
    """
    if dialect not in ("excel", "libreoffice"):
        raise ValueError(f"unknown dialect {dialect!r}")
    ev = Evaluator(resolver, dialect, on_unsupported, cell)
    result = ev.ctx.scalar(lambdas.final(ev.arg(node)))
    return 0.0 if result is None else result


def _clean(x: float | ExcelError) -> float | ExcelError:
    """#NUM! for inf/NaN; no negative zero (Excel has none)."""
    if isinstance(x, ExcelError):
        return x
    x = xv.checked(x)
    return 0.0 if x == 0 else x


# functions whose arguments Excel evaluates as arrays even outside an array formula
# (AGGREGATE: its array form, 14-19; the reference form refuses an array, math/subtotal.py)
ARRAY_ARGUMENTS = frozenset({"SUMPRODUCT", "MMULT", "TRANSPOSE", "MDETERM", "MINVERSE",
                             "AGGREGATE"})


class Evaluator:
    """Excel's semantics for one formula AST: ``arg`` keeps references as Ranges,
    ``value`` gives a scalar, ``apply`` is a binary operator on two values."""

    def __init__(self, resolver: Resolver, dialect: str, on_unsupported,
                 cell: tuple[str, int, int] | None = None):
        self.resolver = resolver
        self.dialect = dialect
        self.on_unsupported = on_unsupported
        self.ctx = fx.Context(dialect, cell, resolver, self.parse_ref)

    def parse_ref(self, text: str) -> Ref | Range | ExcelError | None:
        """INDIRECT's text as a reference (A1 style, sheet-qualified, or a defined name)."""
        from workbook_gen.errors import FormulaSyntaxError
        from workbook_gen.formula.parser import parse

        try:
            node = parse(text.strip())
        except FormulaSyntaxError:
            return None
        if isinstance(node, (ast.CellRef, ast.RangeRef)):
            if node.sheet is not None and "]" not in node.sheet and (
                    self.ctx.workbook.sheet_count()
                    and self.ctx.workbook.sheet_number(node.sheet) is None):
                return ExcelError.REF  # no such sheet (Excel and LibreOffice alike)
            return self.reference(node)
        if isinstance(node, ast.Name):
            value = self.arg(node)
            return value if isinstance(value, Range) and value.ref is not None else None
        return None

    @staticmethod
    def reference(node: ast.CellRef | ast.RangeRef) -> Ref:
        if isinstance(node, ast.CellRef):
            return Ref(node.sheet, node.row, node.col, node.row, node.col)
        r1, r2 = sorted((node.first.row, node.last.row))
        c1, c2 = sorted((node.first.col, node.last.col))
        return Ref(node.sheet, r1, c1, r2, c2)

    def arg(self, node: ast.Node) -> Value | Range:
        """Value of ``node``; references stay Ranges (functions need to know)."""
        if isinstance(node, ast.CellRef):
            value = self.resolver.cell(node.sheet, node.row, node.col)
            if type(value) is float:
                value += 0.0  # a cell never holds -0 in Excel (a file may say "-0")
            return Range.of([[value]], self.reference(node))
        if isinstance(node, ast.RangeRef):
            ref = self.reference(node)
            value = self.resolver.range(node.sheet, ref.row1, ref.col1, ref.row2, ref.col2)
            return (value if isinstance(value, Range) else Range.of(value)).with_ref(ref)
        if isinstance(node, ast.Name):
            value = lambdas.bound(self, node)  # a LAMBDA's parameter or a LET's name
            if value is not None:
                return value
            value = self.resolver.name(node.name, node.sheet)
            return Range.of(value) if isinstance(value, list) else value
        if isinstance(node, ast.Func):
            if node.name in lambdas.SPECIAL:
                return lambdas.special(self, node)
            return self.func(node)
        if isinstance(node, (ast.Array, ast.RefOp, ast.Sheets3D, ast.StructRef)):
            from workbook_gen.formula import refops
            return refops.evaluate(self, node)
        return self.value(node)

    def value(self, node: ast.Node) -> Value:
        if isinstance(node, ast.Number):
            return node.value
        if isinstance(node, (ast.String, ast.Bool)):
            return node.value
        if isinstance(node, ast.ErrorLit):
            return node.error
        if isinstance(node, ast.Missing):
            return 0.0
        if isinstance(node, ast.Paren):
            return self.arg(node.inner)
        if isinstance(node, ast.Unary):
            v = self.ctx.scalar(self.arg(node.operand))
            if node.op == "+":
                return v
            x = xv.to_number(v)
            return x if isinstance(x, ExcelError) else _clean(-x)
        if isinstance(node, ast.Percent):
            x = xv.to_number(self.ctx.scalar(self.arg(node.operand)))
            return x if isinstance(x, ExcelError) else _clean(x / 100.0)
        if isinstance(node, ast.Binary):
            return self.binary(node)
        return self.ctx.scalar(self.arg(node))

    def binary(self, node: ast.Binary) -> Value:
        # Walk the left spine without recursion: A1+A2+...+A2000 is a left-deep tree.
        spine = []
        while isinstance(node, ast.Binary):
            spine.append(node)
            node = node.left
        acc = self.ctx.scalar(self.arg(node))
        for step in reversed(spine):
            acc = self.apply(step.op, acc, self.ctx.scalar(self.arg(step.right)))
        return acc

    def apply(self, op: str, left: Value, right: Value) -> Value:
        """Excel's binary operator ``op`` on two evaluated operands."""
        if self.dialect == "libreoffice":  # no boolean type: TRUE is the number 1
            left = float(left) if isinstance(left, bool) else left
            right = float(right) if isinstance(right, bool) else right
        if op in _COMPARISONS:
            c = xv.compare(left, right)
            return c if isinstance(c, ExcelError) else _COMPARISONS[op](c)
        if op == "&":
            a, b = xv.to_text(left), xv.to_text(right)
            for v in (a, b):
                if isinstance(v, ExcelError):
                    return v
            return a + b
        a = xv.to_number(left)
        if isinstance(a, ExcelError):
            return a
        b = xv.to_number(right)
        if isinstance(b, ExcelError):
            return b
        if op == "+":
            return _clean(a + b)
        if op == "-":
            return _clean(a - b)
        if op == "*":
            return _clean(a * b)
        if op == "/":
            return ExcelError.DIV0 if b == 0 else _clean(a / b)
        if self.dialect == "libreoffice":
            deviation = fx.libreoffice_result("^", (a, b))
            if deviation is not None:
                return deviation
        return _clean(fx.power(a, b))

    def func(self, node: ast.Func) -> Value | Range:
        entry = fx.REGISTRY.get(node.name)
        if entry is not None and unavailable(node.name, node.prefix, self.dialect,
                                             self.ctx.workbook.stored):
            entry = None  # a future function without its _xlfn. prefix: an unknown name
        if entry is None:
            called = lambdas.named(self, node)  # a defined name holding a LAMBDA
            if called is not None:
                return _clean(called) if isinstance(called, float) else called
            if self.on_unsupported is not None:
                self.on_unsupported(node.name)
            return ExcelError.NAME
        if entry.lazy:
            args = [lambda a=a: self.arg(a) for a in node.args]
        elif node.name in ARRAY_ARGUMENTS:  # SUMPRODUCT(A1:A3*B1:B3) needs no Ctrl+Shift+Enter
            inner = _ARRAY_EVALUATOR[0](self.resolver, self.dialect, self.on_unsupported,
                                        self.ctx.cell)
            args = [inner.arg(a) for a in node.args]
        else:
            args = [self.arg(a) for a in node.args]
        if entry.omitted:  # the function tells an omitted argument from a 0
            args = [None if isinstance(n, ast.Missing) else a for n, a in zip(node.args, args)]
        result = fx.call(node.name, args, self.ctx)
        return _clean(result) if isinstance(result, float) else result
