"""Recompute every formula cell of any workbook from its text, fast.

    result = evaluate_cells(formulas, constants, names)   # {(sheet, row, col): text}
    result.values[("Table", 2, 3)], result.cycles, result.unsupported, result.groups

Columns of formulas equal in R1C1 form are compiled once to numpy functions; the
rest goes cell by cell through the scalar reference evaluator (``formula.scalar``),
whose semantics the vector path reproduces exactly.
"""

from workbook_gen.evaluator.engine import CYCLE_VALUE, VOLATILE, evaluate_cells
from workbook_gen.evaluator.evaluation import CellMap, Evaluation, GroupStats
from workbook_gen.evaluator.tasks import cell_scale
from workbook_gen.evaluator.grouping import expand_shared

__all__ = ["CYCLE_VALUE", "VOLATILE", "CellMap", "Evaluation", "GroupStats", "cell_scale",
           "evaluate_cells", "expand_shared"]
