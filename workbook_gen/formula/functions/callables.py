"""Functions as values: a LAMBDA's closure, and a worksheet function named where a LAMBDA
is expected (``BYROW(A1:C2, SUM)``).  TYPE tells them (128) and the lambda helpers call
them."""

from __future__ import annotations

from workbook_gen.formula import ast
from workbook_gen.formula.functions.calling import call
from workbook_gen.formula.functions.registry import REGISTRY
from workbook_gen.xlerror import ExcelError


class Closure:
    """A LAMBDA's parameters and body, with the names bound where it was written."""

    def __init__(self, params: list[str], body: ast.Node, evaluator, env: dict):
        self.params, self.body, self.evaluator, self.env = params, body, evaluator, env

    def __call__(self, *values):
        if len(values) != len(self.params):
            return ExcelError.VALUE
        ev = self.evaluator
        saved = getattr(ev, "bound", None)
        ev.bound = {**self.env, **dict(zip(self.params, values))}
        try:
            result = ev.arg(self.body)
        finally:
            ev.bound = saved
        return result


class Function:
    """A function named where a LAMBDA is expected (``BYROW(A1:C2, SUM)``, saved as
    ``_xleta.SUM``): called with the values as its arguments."""

    def __init__(self, name: str, evaluator):
        self.name, self.evaluator = name, evaluator

    def __call__(self, *values):
        if self.name not in REGISTRY or REGISTRY[self.name].lazy:
            return ExcelError.NAME if self.name not in REGISTRY else ExcelError.VALUE
        return call(self.name, list(values), self.evaluator.ctx)
