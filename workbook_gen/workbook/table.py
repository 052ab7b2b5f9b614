"""The Table sheet: the input column and one live formula per cell."""

from __future__ import annotations

from ..tabulate import Evaluated, headers
from ..tabulate.table import STATUS, cached_values
from .layout import FIRST_ROW, TABLE, TableLayout, add_sheet, print_columns
from .rows import Column


def write_table(workbook, formats, result: Evaluated, layout: TableLayout,
                progress=None) -> None:
    sheet = add_sheet(workbook, TABLE)
    model = result.model
    aux = {q.name for q in model.columns if not q.output}
    names = model.names
    for col, (name, header) in enumerate(zip(names + (STATUS,), headers(model))):
        sheet.write_string(0, col, header, formats["aux_header" if name in aux else "header"])
    sheet.set_row(0, 30)
    sheet.freeze_panes(1, 1)
    # printed: the input, the outputs and the status; not the intermediate columns
    print_columns(workbook, sheet, [True] + [q.output for q in model.columns] + [True], 0,
                  layout.last_row - 1)
    sheet.set_column(0, 0, 11, formats["input"])
    sheet.set_column(1, len(names) - 1, 13, formats["value"])
    sheet.set_column(len(names), len(names), 15)

    status_col = len(names)
    columns = [Column(0, result.inputs.tolist())]
    columns += [Column(c, cached_values(result.columns[q.name]), layout.formula(q.expr))
                for c, q in enumerate(model.columns, start=1)]
    columns.append(Column(status_col, result.status.tolist(),
                          layout.formula(model.status)))
    sheet.write_rows(FIRST_ROW - 1, columns, progress)
