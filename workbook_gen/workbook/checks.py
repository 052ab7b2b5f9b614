"""The Checks sheet: closure residuals per row, their maxima, PASS/FAIL.

Each residual cell is the template's check tree guarded by the row's status,
``IF(Table!status="ok", residual, "n/a")`` (``tabulate.checks.guarded``), printed as one
tree; the subtrees several residuals share are terms (``tabulate/terms.py``): columns
right of the flags, guarded the same way, that the residuals refer to.  The values the
cells cache are ``result.checks`` (``tabulate/checks.py``).
"""

from __future__ import annotations

from ..cellref import column_letters

from ..expr import Var
from ..tabulate import Evaluated
from ..tabulate.checks import TOLERANCE, cannot_assemble_flag, flagged_flag, guarded
from .conditions import write_conditions
from .layout import (CHECK_FIRST_ROW, CHECKS, LINE_HEIGHT, TableLayout, add_sheet,
                     excel_text, print_columns, wrapped_lines)
from .rows import Column

TOLERANCE_NAME = "check_tol"


FLAG_HEADERS = ("cannot assemble", "flagged")
FLAG_WIDTH = 10
_WIDTH = 14         # a residual's or a term's column, at least
_CHECK_WIDTH = 24   # a residual's column, at most, unless its name is longer
_TERM_WIDTH = 48    # a term's column, at most
_DESCRIPTION_LINES = 4  # a column widens (up to those) until its row-3 text fits these


def spec_header(spec) -> str:
    return f"{spec.name} [{spec.unit}]"


def sheet_widths(checks, term_texts: list[str]) -> list[int]:
    """Column widths (characters) of the residuals, then of the terms: each at least
    _WIDTH and as wide as its name, then widened until the text above it (row 3) takes
    at most _DESCRIPTION_LINES lines, up to _CHECK_WIDTH or _TERM_WIDTH."""
    columns = [(c.description, max(_WIDTH, len(c.name) + 2), _CHECK_WIDTH) for c in checks]
    columns += [(text, _WIDTH, _TERM_WIDTH) for text in term_texts]
    widths = []
    for text, width, most in columns:
        while width < most and wrapped_lines(text, width) > _DESCRIPTION_LINES:
            width += 1
        widths.append(width)
    return widths


NOTE = ("Residuals of the loop-closure equations, each divided by its scale "
        "(dimensionless); rows that are not 'ok' show n/a.")
_NOTE_WIDTH = 60  # characters: the note wraps within about this width


def _write_note(sheet, formats, printed_widths: list[int]) -> None:
    """The note in C1, wrapped in cells merged from C1 rightwards (within the printed
    columns) to about _NOTE_WIDTH characters: unwrapped, it ran past the first page."""
    last, width = 2, printed_widths[2]
    while width < _NOTE_WIDTH and last + 1 < len(printed_widths):
        last += 1
        width += printed_widths[last]
    if last > 2:
        sheet.merge_range(0, 2, 0, last, NOTE, formats["wrap"])
    else:
        sheet.write_string(0, 2, NOTE, formats["wrap"])
    sheet.set_row(0, LINE_HEIGHT * wrapped_lines(NOTE, width))


def write_checks(workbook, formats, result: Evaluated, layout: TableLayout,
                 progress=None) -> None:
    sheet = add_sheet(workbook, CHECKS)
    checks = result.model.checks
    values = result.checks
    terms, trees = values.terms, values.trees
    flag_col = len(checks) + 1
    local = tuple((t.name, column_letters(flag_col + 3 + i)) for i, t in enumerate(terms))
    spec = result.scene.template.input

    sheet.write_string(0, 0, "tolerance", formats["label"])
    sheet.write_number(0, 1, TOLERANCE, formats["residual"])
    workbook.define_name(TOLERANCE_NAME, f"={CHECKS}!$B$1")
    term_texts = ["shared by the residuals: " + excel_text(t.expr, str)[1:] for t in terms]
    widths = sheet_widths(checks, term_texts)
    printed_widths = [11] + widths[:len(checks)] + [FLAG_WIDTH] * 2
    _write_note(sheet, formats, printed_widths)
    sheet.write_string(1, 0, "all checks", formats["label"])
    if checks:
        sheet.write_formula(1, 1, f'=IF(MAX(B4:{column_letters(len(checks) + 1)}4)<=check_tol,'
                                  '"PASS","FAIL")', formats["label"], values.overall)
    sheet.freeze_panes(CHECK_FIRST_ROW - 1, 1)
    # printed: the input, the residuals and the two flags; not the terms
    print_columns(workbook, sheet, [True] * (flag_col + 2) + [False] * len(terms),
                  CHECK_FIRST_ROW - 2, CHECK_FIRST_ROW + result.rows - 2)
    sheet.set_column(0, 0, 11, formats["input"])
    for c, width in enumerate(widths[:len(checks)], start=1):
        sheet.set_column(c, c, width, formats["residual"])
    sheet.set_column(flag_col, flag_col + 1, FLAG_WIDTH)
    for i, width in enumerate(widths[len(checks):], start=flag_col + 2):
        sheet.set_column(i, i, width, formats["value"])
    texts = [c.description for c in checks] + term_texts
    sheet.set_row(2, LINE_HEIGHT * max((wrapped_lines(t, w) for t, w in zip(texts, widths)),
                                       default=1))
    heads = [spec_header(spec)] + [c.name for c in checks] + list(FLAG_HEADERS)
    sheet.set_row(CHECK_FIRST_ROW - 2, LINE_HEIGHT * max(
        wrapped_lines(h, w) for h, w in zip(heads, printed_widths)))
    # constant_memory: each row is written whole, top to bottom
    first, last = CHECK_FIRST_ROW, CHECK_FIRST_ROW + result.rows - 1
    named = [(c, column_letters(c + 1), check) for c, check in enumerate(checks, start=1)]
    for c, col, check in named:
        sheet.write_string(2, c, check.description, formats["wrap"])
    for i, text in enumerate(term_texts, start=flag_col + 2):
        sheet.write_string(2, i, text, formats["wrap"])
    sheet.write_string(3, 0, "max |r|", formats["label"])
    for c, col, check in named:
        sheet.write_formula(3, c, f"=MAX(MAX({col}{first}:{col}{last}),-MIN({col}{first}:{col}{last}))",
                            formats["residual"], values.maxima[check.name])
    sheet.write_string(4, 0, "result", formats["label"])
    for c, col, check in named:
        sheet.write_formula(4, c, f'=IF({col}4<=check_tol,"PASS","FAIL")', None,
                            values.verdicts[check.name])
    sheet.write_string(5, 0, "level", formats["label"])
    for c, col, check in named:
        sheet.write_string(5, c, check.level)
    for i, term in enumerate(terms, start=flag_col + 2):
        sheet.write_string(5, i, "term")
    sheet.write_string(6, 0, spec_header(spec), formats["header"])
    for c, col, check in named:
        sheet.write_string(6, c, check.name, formats["header"])
    for c, text in enumerate(FLAG_HEADERS, start=flag_col):
        sheet.write_string(6, c, text, formats["header"])
    for i, term in enumerate(terms, start=flag_col + 2):
        sheet.write_string(6, i, term.name, formats["aux_header"])

    columns = [Column(0, result.inputs.tolist(), layout.formula(Var(spec.name), True))]
    columns += [Column(c, values.cells[check.name],
                       layout.formula(guarded(tree), True, local))
                for (c, col, check), tree in zip(named, trees)]
    columns.append(Column(flag_col, values.cannot_assemble,
                          layout.formula(cannot_assemble_flag(), True)))
    columns.append(Column(flag_col + 1, values.flagged, layout.formula(flagged_flag(), True)))
    columns += [Column(i, values.term_cells[term.name],
                       layout.formula(guarded(term.expr), True, local))
                for i, term in enumerate(terms, start=flag_col + 2)]
    sheet.write_rows(CHECK_FIRST_ROW - 1, columns, progress)
    write_conditions(sheet, formats, result, last - 1)
