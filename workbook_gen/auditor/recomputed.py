"""The audit's value of every cell of a workbook: recomputed for a formula cell, the
file's for a constant (``Recomputed``), what the reference model's check and the
LibreOffice comparison read; and the scalar evaluator's view of it
(``RecomputedResolver``), to re-evaluate a cell in LibreOffice's dialect."""

from __future__ import annotations

from collections.abc import Callable, Mapping

from ..errors import FormulaSyntaxError
from ..evaluator import Evaluation
from ..formula.parser import parse_name
from ..formula.resolver import Resolver
from ..formula.scalar import evaluate as evaluate_scalar
from ..xlerror import ExcelError


class Recomputed:
    """``recomputed(sheet, row, col)``: the evaluation's value of a formula cell, else
    the constant's (None for an empty cell); ``clip`` cuts a huge rectangle (``A:A``) to
    the sheet's used range, as the evaluator reads it."""

    def __init__(self, evaluation: Evaluation, constants: Mapping):
        self._evaluation = evaluation
        self._values, self._constants = evaluation.values, constants

    def __call__(self, sheet: str, row: int, col: int):
        key = (sheet, row, col)
        return self._values[key] if key in self._values else self._constants.get(key)

    def clip(self, sheet: str, r1: int, c1: int, r2: int, c2: int
             ) -> tuple[int, int, int, int]:
        return self._evaluation.clip(sheet, r1, c1, r2, c2)


class RecomputedResolver(Resolver):
    """The scalar evaluator's view of the recomputed workbook (for re-evaluating a cell
    with LibreOffice's semantics): its values, its defined names, which cells hold a
    formula (``is_formula(key)``); the Resolver defaults for the rest."""

    def __init__(self, value_of: Recomputed, names: dict[str, str], sheet: str,
                 is_formula: Callable[[tuple[str, int, int]], bool]):
        self.value_of, self.names, self.sheet = value_of, names, sheet
        self.is_formula = is_formula
        self._upper = {k.upper(): v for k, v in names.items()}

    def cell(self, sheet, row, col):
        return self.value_of(sheet or self.sheet, row, col)

    def range(self, sheet, row1, col1, row2, col2):
        # A:A is read up to the used range only
        row1, col1, row2, col2 = self.value_of.clip(sheet or self.sheet, row1, col1, row2, col2)
        return [[self.cell(sheet, r, c) for c in range(col1, col2 + 1)]
                for r in range(row1, row2 + 1)]

    def has_formula(self, sheet, row, col):
        return self.is_formula((sheet or self.sheet, row, col))

    def name(self, name, sheet):
        text = self._upper.get(name.upper())
        if text is None:
            return ExcelError.NAME
        try:
            node = parse_name(text)
        except FormulaSyntaxError:
            return ExcelError.NAME
        return evaluate_scalar(node, self)
