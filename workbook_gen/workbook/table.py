"""The Table sheet: the input column and one live formula per cell."""

from __future__ import annotations

import numpy as np

from ..compute import Evaluated, headers
from ..expr.excel import row_template
from .. import xlmath as xm
from .layout import FIRST_ROW, TABLE, TableLayout, add_sheet
from ..xlerror import ExcelError


def cached_values(column: xm.XArray) -> list:
    """Cached values for XlsxWriter: numbers, booleans, texts or Excel error texts."""
    values = column.val.tolist()
    if column.boolean:
        values = [bool(v) if v == v else v for v in values]
    if column.err.any():
        for i in np.flatnonzero(column.err):
            values[i] = ExcelError.from_code(int(column.err[i])).value
    return values


def write_table(workbook, formats, result: Evaluated, layout: TableLayout) -> None:
    sheet = add_sheet(workbook, TABLE)
    model = result.model
    aux = {q.name for q in model.columns if not q.output}
    names = model.names
    for col, (name, header) in enumerate(zip(names + ("status",), headers(model))):
        sheet.write_string(0, col, header, formats["aux_header" if name in aux else "header"])
    sheet.set_row(0, 30)
    sheet.freeze_panes(1, 1)
    sheet.set_column(0, 0, 11, formats["input"])
    sheet.set_column(1, len(names) - 1, 13, formats["value"])
    sheet.set_column(len(names), len(names), 15)

    templates = [row_template(q.expr, layout.local) for q in model.columns]
    status = row_template(model.status, layout.local)
    values = [cached_values(result.columns[q.name]) for q in model.columns]
    inputs = result.inputs.tolist()
    texts = result.status.tolist()
    write_formula, write_number = sheet.write_formula, sheet.write_number
    status_col = len(names)
    for i in range(result.rows):
        row = FIRST_ROW + i
        r0 = row - 1
        write_number(r0, 0, inputs[i])
        for c, (template, column) in enumerate(zip(templates, values), start=1):
            write_formula(r0, c, template.render(row), None, column[i])
        write_formula(r0, status_col, status.render(row), None, texts[i])
