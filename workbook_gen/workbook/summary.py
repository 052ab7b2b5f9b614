"""The Summary sheet: extremes of each output and where they occur, spans
(stroke, swing), figures from the parameters, and the count of rows that
cannot be assembled.  The values its formulas cache are ``result.summary``
(``tabulate/summary.py``)."""

from __future__ import annotations

from ..cellref import column_letters

from ..tabulate import STATUS_OK as OK
from ..tabulate import Evaluated
from ..tabulate.summary import TIE
from .layout import (CHECK_FIRST_ROW, CHECKS, FIRST_ROW, LINE_HEIGHT, STATUS, SUMMARY,
                     TableLayout, add_sheet, excel_text, print_wide, wrapped_lines)


def _where(row: int, value_col: str, inputs_abs: str, rng: str, ok: str, first: int,
           tie: float) -> str:
    """The input of the first ok row holding the extreme in ``value_col`` (the smallest
    row number among them, by AGGREGATE), or "tie" when the column is constant to
    rounding (max - min within ``tie``)."""
    r = row + 1
    return (f'=IF(C{r}-E{r}<={tie!r},"{TIE}",INDEX({inputs_abs},'
            f"_xlfn.AGGREGATE(15,6,(ROW({rng})-{first - 1})/(({rng}={value_col}{r})*{ok}),1)))")


def _aggregate(function: int, rng: str, ok: str, counted: str) -> str:
    """LARGE (14) or SMALL (15) of the column's ok rows, errors left out (AGGREGATE's
    option 6; its array form takes the array expression without array entry): Excel
    2010+ and LibreOffice; #N/A in both where no row is ok (``counted``: the cell that
    counts them)."""
    return f"=IF({counted},_xlfn.AGGREGATE({function},6,{rng}/{ok},1),NA())"


_DESCRIPTION_WIDTH = 42  # characters: columns D to F, where a description wraps


def _describe(sheet, formats, row: int, text: str) -> None:
    """A figure's description in D, wrapped in D:F merged (E and F are empty in the
    figures' rows): unwrapped, the longest ran far to the right and the Summary, fitted to
    the page width, printed at 6 pt."""
    sheet.merge_range(row, 3, row, 5, text, formats["note"])
    lines = wrapped_lines(text, _DESCRIPTION_WIDTH)
    if lines > 1:
        sheet.set_row(row, LINE_HEIGHT * lines)


def write_summary(workbook, formats, result: Evaluated, layout: TableLayout) -> None:
    sheet = add_sheet(workbook, SUMMARY)
    spec = result.scene.template.input
    heads = ["quantity", "unit", "max", f"at {spec.name} [{spec.unit}]", "min",
             f"at {spec.name} [{spec.unit}]"]
    for c, text in enumerate(heads):
        sheet.write_string(0, c, text, formats["header"])
    sheet.set_column(0, 0, 30)
    print_wide(sheet, 0)
    sheet.set_column(1, 1, 9)
    sheet.set_column(2, 5, 14, formats["value"])
    inputs_abs = layout.column(spec.name, absolute=True)
    status = layout.column(STATUS, absolute=True)
    ok = f'({status}="{OK}")'
    # the Summary's "rows in the extremes" cell, below the outputs, spans and figures
    model = result.model
    count_cell = "$C$" + str(len(model.outputs()) + len(model.spans) + len(model.figures) + 5)
    values = result.summary
    lines: dict[str, int] = {}  # each output's row on the sheet (1-based)
    row = 1
    for q in result.model.outputs():
        found = values.outputs[q.name]
        rng = layout.column(q.name)
        tie = found.tie
        sheet.write_string(row, 0, q.name)
        sheet.write_string(row, 1, q.unit)
        for col, text, value in (
                (2, _aggregate(14, rng, ok, count_cell), found.hi),
                (3, _where(row, "C", inputs_abs, rng, ok, FIRST_ROW, tie), found.at_hi),
                (4, _aggregate(15, rng, ok, count_cell), found.lo),
                (5, _where(row, "E", inputs_abs, rng, ok, FIRST_ROW, tie), found.at_lo)):
            sheet.write_formula(row, col, text, None, value)
        lines[q.name] = row + 1
        row += 1

    row += 1
    for c, text in enumerate(("figure", "unit", "value", "description")):
        sheet.write_string(row, c, text, formats["header"])
    row += 1
    for span, value in zip(result.model.spans, values.spans):
        line, tie = lines[span.quantity], values.outputs[span.quantity].tie
        sheet.write_string(row, 0, f"{span.label} (from the table)")
        sheet.write_string(row, 1, result.model.template.quantity(span.quantity).unit)
        sheet.write_formula(row, 2, f"=IF(C{line}-E{line}<={tie!r},0,C{line}-E{line})", None,
                            value)
        _describe(sheet, formats, row, f"max - min of {span.quantity} over the sweep")
        row += 1
    for figure, cached in zip(result.model.figures, values.figures):
        sheet.write_string(row, 0, figure.label)
        sheet.write_string(row, 1, figure.unit)
        sheet.write_formula(row, 2, excel_text(figure.expr), None, cached)
        _describe(sheet, formats, row, figure.description)
        row += 1
    flags = column_letters(len(result.model.checks) + 2)
    last = CHECK_FIRST_ROW + result.rows - 1
    sheet.write_string(row, 0, "rows")
    sheet.write_number(row, 2, values.rows)
    row += 1
    assert f"$C${row + 1}" == count_cell  # (the extremes' formulas refer to this cell)
    sheet.write_string(row, 0, "rows in the extremes")
    sheet.write_formula(row, 2, f'=COUNTIF({layout.column(STATUS, absolute=True)},"{OK}")',
                        None, values.rows_ok)
    _describe(sheet, formats, row, "the max and min above are taken over the ok rows only; "
                                   "the rows counted below are left out")
    row += 1
    sheet.write_string(row, 0, "rows that cannot be assembled")
    sheet.write_formula(row, 2, f"=SUM({CHECKS}!{flags}{CHECK_FIRST_ROW}:{flags}{last})", None,
                        values.rows_not_assembled)
    _describe(sheet, formats, row, "these rows hold #NUM! in the Table")
    row += 1
    flagged = column_letters(len(result.model.checks) + 3)
    counts = ", ".join(f"{t}: {n}" for t, n in values.flagged.items())
    sheet.write_string(row, 0, "rows flagged singular or not converged")
    sheet.write_formula(row, 2, f"=SUM({CHECKS}!{flagged}{CHECK_FIRST_ROW}:{flagged}{last})",
                        None, values.rows_flagged)
    _describe(sheet, formats, row, "status other than ok (toggle, dead centre, not converged, "
                                   "...): rates there are singular or not to be trusted"
                                   + (f"; {counts}" if counts else ""))
