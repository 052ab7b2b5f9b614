"""Where everything sits in the workbook: sheet names, columns, ranges, formats."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache

from ..cellref import column_letters, quoted_sheet
from ..tabulate import Evaluated
from ..tabulate.table import STATUS
from ..expr import Node
from ..expr.excel import ROW, Piece, Row, RowTemplate, row_template, to_excel
from .rows import Sheet

TABLE, PARAMETERS, CHECKS, SUMMARY, CHARTS, ABOUT = (
    "Table", "Parameters", "Checks", "Summary", "Charts", "About")
FIRST_ROW = 2  # first data row of the Table (1-based); row 1 holds the headers
CHECK_FIRST_ROW = 8  # first data row of the Checks sheet
# A Checks row refers to the Table row this many rows up.
_TABLE_ROW_FROM_CHECKS = Row(FIRST_ROW - CHECK_FIRST_ROW)


@dataclass(frozen=True)
class TableLayout:
    """Column letters of the Table, by quantity name; the status comes last."""

    letters: dict[str, str]
    status: str
    rows: int

    @classmethod
    def of(cls, result: Evaluated) -> "TableLayout":
        names = result.model.names
        letters = {name: column_letters(i + 1) for i, name in enumerate(names + (STATUS,))}
        return cls(letters, letters[STATUS], result.rows)

    @property
    def last_row(self) -> int:
        return FIRST_ROW + self.rows - 1

    def local(self, name: str) -> tuple[Piece, ...]:
        """A same-row reference from within the Table: ``C`` + row."""
        return (self.letters[name], ROW)

    def remote(self, name: str) -> tuple[Piece, ...]:
        """From a Checks row, the reference to the Table row of the same step: ``Table!C`` +
        row - 6."""
        return (f"{TABLE}!{self.letters[name]}", _TABLE_ROW_FROM_CHECKS)

    def formula(self, node: Node, on_checks: bool = False,
                local: tuple[tuple[str, str], ...] = ()) -> RowTemplate:
        """``node`` printed for a Table row, or for a Checks row (``on_checks``) where the
        names in ``local`` are columns of the Checks sheet; printed once per tree and
        layout in a process (a batch prints each template's trees once)."""
        return _printed(node, self._letter_items, on_checks, local)

    @cached_property
    def _letter_items(self) -> tuple[tuple[str, str], ...]:
        return tuple(self.letters.items())

    def column(self, name: str, absolute: bool = False) -> str:
        """The whole data range of a column, e.g. ``Table!C$2:C$38``."""
        col = self.letters[name]
        d = "$" if absolute else ""
        return f"{TABLE}!{d}{col}${FIRST_ROW}:{d}{col}${self.last_row}"


FORMATS = {
    "header": {"bold": True, "bottom": 1, "text_wrap": True, "valign": "top"},
    "aux_header": {"bold": True, "italic": True, "font_color": "#595959", "bottom": 1,
                   "text_wrap": True, "valign": "top"},
    "input": {"num_format": "0.0##", "bg_color": "#F2F2F2"},
    "value": {"num_format": "0.000000"},
    "residual": {"num_format": "0.00E+00"},
    "param": {"num_format": "General", "bg_color": "#FFF2CC"},
    "title": {"bold": True, "font_size": 13},
    "label": {"bold": True},
    "wrap": {"text_wrap": True, "valign": "top"},
    "note": {"text_wrap": True},  # wrapped, at the bottom like the row's other cells
}


@lru_cache(maxsize=4096)
def _printed(node: Node, letters: tuple[tuple[str, str], ...], on_checks: bool,
             local: tuple[tuple[str, str], ...]) -> RowTemplate:
    table, own = dict(letters), dict(local)

    def resolve(name: str) -> tuple[Piece, ...]:
        if name in own:
            return (own[name], ROW)
        if on_checks:
            return (f"{TABLE}!{table[name]}", _TABLE_ROW_FROM_CHECKS)
        return (table[name], ROW)
    return row_template(node, resolve)


A4 = 9  # XlsxWriter's paper index


#: ``to_excel`` of a tree (resolve None or ``str``) once per process: the Checks' term
#: descriptions, the derived values and figures are printed for every variant.
excel_text = lru_cache(maxsize=4096)(to_excel)


#: Every printed page's footer: the sheet's name left, the page number right.
FOOTER = "&L&A&Rpage &P"


def print_wide(sheet, header_row: int | None = None) -> None:
    """Print a narrow sheet (Parameters, Summary, About) landscape on A4, fitted to the
    page width (as many pages down as it takes), with its header row, if any, repeated
    on every page."""
    sheet.set_landscape()
    sheet.set_paper(A4)
    sheet.fit_to_pages(1, 0)
    sheet.set_footer(FOOTER)
    if header_row is not None:
        sheet.repeat_rows(header_row)


#: Print scale of the Table and the Checks, in percent: their 11 pt text prints at
#: 8.8 pt.  Fitted to one page width, the five-bar's 95 columns printed at 0.7 pt.  A
#: fixed scale rather than "fit to N pages wide": it holds for a print area of several
#: ranges (each starts its own pages, in Excel and LibreOffice alike), and the text is
#: the same size in every workbook.
PRINT_SCALE = 80


def printed_runs(printed: list[bool]) -> list[tuple[int, int]]:
    """The first and last column of each run of printed columns.  Column 0, the input,
    is printed on every page as a title column: a run of it alone is left out."""
    runs: list[tuple[int, int]] = []
    for col, shown in enumerate(printed):
        if not shown:
            continue
        if runs and runs[-1][1] == col - 1:
            runs[-1] = (runs[-1][0], col)
        else:
            runs.append((col, col))
    if len(runs) > 1 and runs[0] == (0, 0):
        runs.pop(0)
    return runs


def print_columns(workbook, sheet, printed: list[bool], header_row: int,
                  last_row: int) -> None:
    """Print the columns marked in ``printed`` (rows 0 to ``last_row``, 0-based) at
    PRINT_SCALE, landscape on A4, across as many pages as they take, with the header row
    and the input column (A) repeated on every page.  Helper columns (intermediate
    quantities, the Checks' terms) stay where they are and are left out of the print
    area, which is then a list of ranges, one per run of printed columns.

    Page order: down, then over (the default): a column is one quantity over the sweep,
    so each quantity's whole cycle prints on consecutive pages, every page labelled by
    the repeated input column and header row."""
    sheet.set_landscape()
    sheet.set_paper(A4)
    sheet.set_print_scale(PRINT_SCALE)
    sheet.set_margins(left=0.5, right=0.5, top=0.6, bottom=0.6)
    sheet.set_footer(FOOTER)
    sheet.repeat_rows(header_row)
    sheet.repeat_columns(0)
    runs = printed_runs(printed)
    if len(runs) == 1:
        sheet.print_area(0, runs[0][0], last_row, runs[0][1])
        return
    areas = ",".join(f"{quoted_sheet(sheet.name)}!${column_letters(first + 1)}$1:"
                     f"${column_letters(last + 1)}${last_row + 1}" for first, last in runs)
    workbook.define_name(f"{sheet.name}!_xlnm.Print_Area", areas)


LINE_HEIGHT = 15  # points: a line of 11 pt text, as a row height


def wrapped_lines(text: str, width: float) -> int:
    """Lines ``text`` takes wrapped at spaces in a column ``width`` characters wide (a
    character of the width is a digit's; most letters are narrower, so this errs
    towards a line too many rather than too few)."""
    room = max(1, int(width))
    lines, used = 0, room  # as if after a full line
    for word in text.split():
        if used + 1 + len(word) <= room:
            used += 1 + len(word)
            continue
        starts = -(-len(word) // room)  # a word wider than the column breaks anywhere
        lines += starts
        used = len(word) - (starts - 1) * room
    return max(lines, 1)


def add_sheet(workbook, name: str) -> Sheet:
    """A sheet of ``workbook``: a package.Book makes it (in memory or not), else a Sheet."""
    make = getattr(workbook, "sheet", None)
    return make(name) if make else workbook.add_worksheet(name, worksheet_class=Sheet)
