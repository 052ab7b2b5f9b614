"""The design conditions (a template's balancing conditions) on the Checks sheet.

They follow the per-row residuals, below the last row (the sheet is written top to
bottom): name, residual, unit, scale (the sum of its terms' magnitudes), PASS/FAIL
against ``check_tol`` times the scale, and what it says.  They judge the design, not
the workbook: the auditor's closure residuals are the per-row columns above.  Their
values are ``result.conditions`` (``tabulate/checks.py``).
"""

from __future__ import annotations

from ..tabulate import Evaluated
from .layout import excel_text

SKIP = 2  # blank rows between the per-row residuals and the conditions


def write_conditions(sheet, formats, result: Evaluated, after: int) -> None:
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
    found = result.conditions
    sheet.write_string(row + 1, 0, "all conditions", formats["label"])
    sheet.write_formula(row + 1, 1, f'=IF(MAX(E{first + 1}:E{last})<=check_tol,"PASS","FAIL")',
                        formats["label"], found.overall)
    for c, text in enumerate(("condition", "residual", "unit", "scale", "|residual|/scale",
                              "result", "description")):
        sheet.write_string(row + 2, c, text, formats["header"])
    for r, item, value in zip(range(first, last), items, found.items):
        sheet.write_string(r, 0, item.name)
        sheet.write_formula(r, 1, excel_text(item.expr), formats["residual"], value.value)
        sheet.write_string(r, 2, item.unit)
        sheet.write_formula(r, 3, excel_text(item.scale), formats["residual"], value.scale)
        sheet.write_formula(r, 4, f"=IF(D{r + 1}=0,0,ABS(B{r + 1})/D{r + 1})",
                            formats["residual"], value.relative)
        sheet.write_formula(r, 5, f'=IF(E{r + 1}<=check_tol,"PASS","FAIL")', None,
                            value.verdict)
        sheet.write_string(r, 6, item.description)
