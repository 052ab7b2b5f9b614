"""The design conditions (a template's balancing conditions) on the Checks sheet.

They follow the per-row residuals, below the last row (the sheet is written top to
bottom): name, residual, unit, scale (the sum of its terms' magnitudes), PASS/FAIL
against ``check_tol`` times the scale, and what it says.  They judge the design, not
the workbook: the auditor's closure residuals are the per-row columns above.
"""

from __future__ import annotations

from ..tabulate import Evaluated
from ..expr.numeric import compile_numpy
from .layout import excel_text
from .table import cached_values

SKIP = 2  # blank rows between the per-row residuals and the conditions


def _value(tree, params):
    return cached_values(compile_numpy(tree)({}, params, 1))[0]


def write_conditions(sheet, formats, result: Evaluated, after: int, tolerance: float) -> None:
    """Write the conditions from 0-based row ``after`` + SKIP on (``after``: the last row
    written so far)."""
    items = result.model.conditions
    if not items:
        return
    row = after + SKIP
    sheet.write_string(row, 0, "design conditions", formats["label"])
    sheet.write_string(row, 2, "Balancing conditions of the design (a residual, 0 when it "
                               "holds): FAIL means the mechanism is not balanced, not that "
                               "the workbook is wrong.")
    first = row + 3                       # 0-based row of the first condition
    last = first + len(items)             # 1-based row of the last
    values = [_value(item.expr, result.params) for item in items]
    scales = [_value(item.scale, result.params) for item in items]
    relative = [(0.0 if s == 0 else abs(v) / s)
                if isinstance(v, float) and isinstance(s, float) else v
                for v, s in zip(values, scales)]
    ok = [isinstance(r, float) and r <= tolerance for r in relative]
    sheet.write_string(row + 1, 0, "all conditions", formats["label"])
    sheet.write_formula(row + 1, 1, f'=IF(MAX(E{first + 1}:E{last})<=check_tol,"PASS","FAIL")',
                        formats["label"], "PASS" if all(ok) else "FAIL")
    for c, text in enumerate(("condition", "residual", "unit", "scale", "|residual|/scale",
                              "result", "description")):
        sheet.write_string(row + 2, c, text, formats["header"])
    for r, item, value, scale, rel, good in zip(range(first, last), items, values, scales,
                                                relative, ok):
        sheet.write_string(r, 0, item.name)
        sheet.write_formula(r, 1, excel_text(item.expr), formats["residual"], value)
        sheet.write_string(r, 2, item.unit)
        sheet.write_formula(r, 3, excel_text(item.scale), formats["residual"], scale)
        sheet.write_formula(r, 4, f"=IF(D{r + 1}=0,0,ABS(B{r + 1})/D{r + 1})",
                            formats["residual"], rel)
        sheet.write_formula(r, 5, f'=IF(E{r + 1}<=check_tol,"PASS","FAIL")', None,
                            "PASS" if good else "FAIL")
        sheet.write_string(r, 6, item.description)
