"""The Checks sheet: closure residuals per row, their maxima, PASS/FAIL.

Each residual cell is the template's check tree guarded by the row's status,
``IF(Table!status="ok", residual, "n/a")``, built and printed as one tree.  The
subtrees several residuals share are terms (``terms.py``): columns right of the
flags, guarded the same way, that the residuals refer to.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..cellref import column_letters
from .. import xlmath as xm
from ..tabulate import Evaluated
from ..expr import Node, Var, eq, if_
from ..expr.numeric import compiled_set
from .conditions import write_conditions
from ..xlerror import ExcelError
from .layout import (CHECK_FIRST_ROW, CHECKS, LINE_HEIGHT, STATUS, TableLayout, add_sheet,
                     excel_text, print_columns, wrapped_lines)
from .rows import Column
from .table import cached_values
from .terms import Term, common_terms


TOLERANCE = 1e-9
TOLERANCE_NAME = "check_tol"


SKIPPED = "n/a"


@lru_cache(maxsize=4096)   # trees are immutable: the same guarded tree for every variant
def guarded(check: Node) -> Node:
    """The residual where the row is 'ok', else a text that MAX and MIN skip.

    Not "": XlsxWriter cannot mark an empty cached string as text, and readers
    then see an empty number where LibreOffice and Excel hold a string."""
    return if_(eq(Var(STATUS), "ok"), check, SKIPPED)


@lru_cache(maxsize=1)
def cannot_assemble_flag() -> Node:
    return if_(eq(Var(STATUS), "cannot assemble"), 1, 0)


@lru_cache(maxsize=1)
def flagged_flag() -> Node:
    """1 where the row assembles but is flagged (toggle, dead centre, not converged ...)."""
    return if_(eq(Var(STATUS), "ok"), 0, if_(eq(Var(STATUS), "cannot assemble"), 0, 1))


def is_flagged(status: str) -> bool:
    return status not in ("ok", "cannot assemble")


def plan(model) -> tuple[tuple[Term, ...], tuple[Node, ...]]:
    """The terms and each check's tree over Table columns and terms."""
    return common_terms(tuple(c.expr for c in model.checks))


def _unguarded(result: Evaluated):
    """Each term's and check's value where the row is "ok" (the cells' "ok" branch), and
    the "ok" condition; each check under "\x00check i"."""
    terms, trees = plan(result.model)
    columns = dict(result.columns)
    status = xm.XArray(result.status, np.zeros(result.rows, np.uint8))
    columns[STATUS] = status
    ok = xm.compare("=", status, xm.const("ok", result.rows))
    # The residuals read a term in their "ok" branch only, where the cell holds the
    # unguarded value: evaluate them over that (terms first, each seeing those before).
    named = tuple((t.name, t.expr) for t in terms) + tuple(
        (f"\x00check {i}", tree) for i, tree in enumerate(trees))
    return compiled_set(named)(columns, result.params, result.rows), ok


def residuals(result: Evaluated) -> tuple[dict[str, xm.XArray], dict[str, xm.XArray]]:
    """Each check's guarded residual per row, and each term's, as the cells hold them."""
    out, ok = _unguarded(result)
    skipped = xm.const(SKIPPED, result.rows)
    terms, _ = plan(result.model)
    held = {t.name: xm.where(ok, out[t.name], skipped) for t in terms}
    values = {c.name: xm.where(ok, out[f"\x00check {i}"], skipped)
              for i, c in enumerate(result.model.checks)}
    return values, held


def _cells(column: xm.XArray, ok: xm.XArray) -> tuple[list, np.ndarray]:
    """``cached_values(xm.where(ok, column, "n/a"))`` and that column's error codes,
    without the object arrays for a plain numeric column."""
    if column.is_text or column.boolean or np.count_nonzero(ok.err):
        guarded_column = xm.where(ok, column, xm.const(SKIPPED, len(column.val)))
        return cached_values(guarded_column), guarded_column.err
    picks = ok.val != 0
    cells = [v if p else SKIPPED for v, p in zip(column.val.tolist(), picks.tolist())]
    err = np.where(picks, column.err, 0).astype(np.uint8)
    if np.count_nonzero(err):
        for i in np.flatnonzero(err):
            cells[i] = ExcelError.from_code(int(err[i])).value
    return cells, err


def _max_abs(cells: list, err: np.ndarray) -> float | str:
    """What MAX(MAX(r),-MIN(r)) gives: the first error of the range if any (Excel's
    MAX propagates it), else the largest magnitude; texts are skipped, none left is 0."""
    if np.count_nonzero(err):
        return ExcelError.from_code(int(err[np.flatnonzero(err)[0]])).value
    numbers = [abs(v) for v in cells if not isinstance(v, str)]
    return max(numbers, default=0.0)


def _verdict(maximum: float | str) -> str:
    """What IF(max<=check_tol,"PASS","FAIL") gives (an error passes through)."""
    if isinstance(maximum, str):
        return maximum
    return "PASS" if maximum <= TOLERANCE else "FAIL"


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
    out, ok = _unguarded(result)
    terms, trees = plan(result.model)
    cells = {c.name: _cells(out[f"\x00check {i}"], ok) for i, c in enumerate(checks)}
    flag_col = len(checks) + 1
    local = tuple((t.name, column_letters(flag_col + 3 + i)) for i, t in enumerate(terms))
    maxima = {name: _max_abs(*found) for name, found in cells.items()}
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
        errors = [m for m in maxima.values() if isinstance(m, str)]
        verdict = errors[0] if errors else _verdict(max(maxima.values()))
        sheet.write_formula(1, 1, f'=IF(MAX(B4:{column_letters(len(checks) + 1)}4)<=check_tol,'
                                  '"PASS","FAIL")', formats["label"], verdict)
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
                            formats["residual"], maxima[check.name])
    sheet.write_string(4, 0, "result", formats["label"])
    for c, col, check in named:
        sheet.write_formula(4, c, f'=IF({col}4<=check_tol,"PASS","FAIL")', None,
                            _verdict(maxima[check.name]))
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

    texts = result.status.tolist()
    columns = [Column(0, result.inputs.tolist(), layout.formula(Var(spec.name), True))]
    columns += [Column(c, cells[check.name][0],
                       layout.formula(guarded(tree), True, local))
                for (c, col, check), tree in zip(named, trees)]
    columns.append(Column(flag_col, [1 if t == "cannot assemble" else 0 for t in texts],
                          layout.formula(cannot_assemble_flag(), True)))
    columns.append(Column(flag_col + 1, [1 if is_flagged(t) else 0 for t in texts],
                          layout.formula(flagged_flag(), True)))
    columns += [Column(i, _cells(out[term.name], ok)[0],
                       layout.formula(guarded(term.expr), True, local))
                for i, term in enumerate(terms, start=flag_col + 2)]
    sheet.write_rows(CHECK_FIRST_ROW - 1, columns, progress)
    write_conditions(sheet, formats, result, last - 1, TOLERANCE)
