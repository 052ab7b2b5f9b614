"""The Checks sheet: closure residuals per row, their maxima, PASS/FAIL.

Each residual cell is the template's check tree guarded by the row's status,
``IF(Table!status="ok", residual, "")``, built and printed as one tree.
"""

from __future__ import annotations

import numpy as np
from xlsxwriter.utility import xl_col_to_name

from .. import xlmath as xm
from ..compute import Evaluated
from ..expr import Node, Var, eq, if_
from ..expr.numeric import compile_numpy
from .conditions import write_conditions
from ..xlerror import ExcelError
from .layout import CHECK_FIRST_ROW, CHECKS, STATUS, TableLayout, add_sheet
from .rows import Column
from .table import cached_values

TOLERANCE = 1e-9
TOLERANCE_NAME = "check_tol"


SKIPPED = "n/a"


def guarded(check: Node) -> Node:
    """The residual where the row is 'ok', else a text that MAX and MIN skip.

    Not "": XlsxWriter cannot mark an empty cached string as text, and readers
    then see an empty number where LibreOffice and Excel hold a string."""
    return if_(eq(Var(STATUS), "ok"), check, SKIPPED)


def cannot_assemble_flag() -> Node:
    return if_(eq(Var(STATUS), "cannot assemble"), 1, 0)


def flagged_flag() -> Node:
    """1 where the row assembles but is flagged (toggle, dead centre, not converged ...)."""
    return if_(eq(Var(STATUS), "ok"), 0, if_(eq(Var(STATUS), "cannot assemble"), 0, 1))


def is_flagged(status: str) -> bool:
    return status not in ("ok", "cannot assemble")


def residuals(result: Evaluated) -> dict[str, xm.XArray]:
    """Each check's guarded residual per row, as the cells hold it."""
    columns = dict(result.columns)
    columns[STATUS] = xm.XArray(result.status, np.zeros(result.rows, np.uint8))
    return {c.name: compile_numpy(guarded(c.expr))(columns, result.params,
                                                   result.rows)
            for c in result.model.checks}


def _max_abs(column: xm.XArray) -> float | str:
    """What MAX(MAX(r),-MIN(r)) gives: the first error of the range if any (Excel's
    MAX propagates it), else the largest magnitude; texts are skipped, none left is 0."""
    if column.err.any():
        return ExcelError.from_code(int(column.err[np.flatnonzero(column.err)[0]])).value
    numbers = [abs(v) for v in column.val if not isinstance(v, str)]
    return max(numbers, default=0.0)


def _verdict(maximum: float | str) -> str:
    """What IF(max<=check_tol,"PASS","FAIL") gives (an error passes through)."""
    if isinstance(maximum, str):
        return maximum
    return "PASS" if maximum <= TOLERANCE else "FAIL"


def write_checks(workbook, formats, result: Evaluated, layout: TableLayout,
                 progress=None) -> None:
    sheet = add_sheet(workbook, CHECKS)
    checks = result.model.checks
    values = residuals(result)
    flag_col = len(checks) + 1
    maxima = {name: _max_abs(column) for name, column in values.items()}
    spec = result.scene.template.input

    sheet.write_string(0, 0, "tolerance", formats["label"])
    sheet.write_number(0, 1, TOLERANCE, formats["residual"])
    workbook.define_name(TOLERANCE_NAME, f"={CHECKS}!$B$1")
    sheet.write_string(0, 2, "Residuals of the loop-closure equations, each divided by its "
                             "scale (dimensionless); rows that are not 'ok' show n/a.")
    sheet.write_string(1, 0, "all checks", formats["label"])
    if checks:
        errors = [m for m in maxima.values() if isinstance(m, str)]
        verdict = errors[0] if errors else _verdict(max(maxima.values()))
        sheet.write_formula(1, 1, f'=IF(MAX(B4:{xl_col_to_name(len(checks))}4)<=check_tol,'
                                  '"PASS","FAIL")', formats["label"], verdict)
    sheet.freeze_panes(CHECK_FIRST_ROW - 1, 1)
    sheet.set_column(0, 0, 11, formats["input"])
    sheet.set_column(1, len(checks), 14, formats["residual"])
    sheet.set_row(2, 45)
    # constant_memory: each row is written whole, top to bottom
    first, last = CHECK_FIRST_ROW, CHECK_FIRST_ROW + result.rows - 1
    named = [(c, xl_col_to_name(c), check) for c, check in enumerate(checks, start=1)]
    for c, col, check in named:
        sheet.write_string(2, c, check.description, formats["wrap"])
    sheet.write_string(3, 0, "max |r|", formats["label"])
    for c, col, check in named:
        sheet.write_formula(3, c, f"=MAX(MAX({col}{first}:{col}{last}),-MIN({col}{first}:{col}{last}))",
                            formats["residual"], maxima[check.name])
    sheet.write_string(4, 0, "result", formats["label"])
    for c, col, check in named:
        sheet.write_formula(4, c, f'=IF({col}4<=check_tol,"PASS","FAIL")', None,
                            _verdict(maxima[check.name]))
    sheet.write_string(5, 0, "level", formats["label"])
    for c, col, check in named:
        sheet.write_string(5, c, check.level)
    sheet.write_string(6, 0, f"{spec.name} [{spec.unit}]", formats["header"])
    for c, col, check in named:
        sheet.write_string(6, c, check.name, formats["header"])
    sheet.write_string(6, flag_col, "cannot assemble", formats["header"])
    sheet.write_string(6, flag_col + 1, "flagged", formats["header"])

    texts = result.status.tolist()
    columns = [Column(0, result.inputs.tolist(), layout.formula(Var(spec.name), True))]
    columns += [Column(c, cached_values(values[check.name]), layout.formula(guarded(check.expr),
                                                                             True))
                for c, col, check in named]
    columns.append(Column(flag_col, [1 if t == "cannot assemble" else 0 for t in texts],
                          layout.formula(cannot_assemble_flag(), True)))
    columns.append(Column(flag_col + 1, [1 if is_flagged(t) else 0 for t in texts],
                          layout.formula(flagged_flag(), True)))
    sheet.write_rows(CHECK_FIRST_ROW - 1, columns, progress)
    write_conditions(sheet, formats, result, last - 1, TOLERANCE)
