"""Where everything sits in the workbook: sheet names, columns, ranges, formats."""

from __future__ import annotations

from dataclasses import dataclass

from xlsxwriter.utility import xl_col_to_name
from xlsxwriter.worksheet import Worksheet

from ..compute import Evaluated
from ..expr.excel import ROW, Piece

TABLE, PARAMETERS, CHECKS, SUMMARY, CHARTS, ABOUT = (
    "Table", "Parameters", "Checks", "Summary", "Charts", "About")
STATUS = "status"  # the Table's last column
FIRST_ROW = 2  # first data row of the Table (1-based); row 1 holds the headers
CHECK_FIRST_ROW = 8  # first data row of the Checks sheet


@dataclass(frozen=True)
class TableLayout:
    """Column letters of the Table, by quantity name; the status comes last."""

    letters: dict[str, str]
    status: str
    rows: int

    @classmethod
    def of(cls, result: Evaluated) -> "TableLayout":
        names = result.model.names
        letters = {name: xl_col_to_name(i) for i, name in enumerate(names + (STATUS,))}
        return cls(letters, letters[STATUS], result.rows)

    @property
    def last_row(self) -> int:
        return FIRST_ROW + self.rows - 1

    def local(self, name: str) -> tuple[Piece, ...]:
        """A same-row reference from within the Table: ``C`` + row."""
        return (self.letters[name], ROW)

    def remote(self, name: str) -> tuple[Piece, ...]:
        """A same-row reference from another sheet: ``Table!C`` + row."""
        return (f"{TABLE}!{self.letters[name]}", ROW)

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
}


class Sheet(Worksheet):
    """A worksheet that writes our formula text as it is.

    Every formula we write is printed from a tree whose functions are Excel's
    classic ones (``expr.tree.FUNCTIONS``), so XlsxWriter's hundred-odd regex
    substitutions for 'future functions' have nothing to do; they were 80% of
    the time to write a 3,600-row workbook.
    """

    def _prepare_formula(self, formula, expand_future_functions=False):
        return formula[1:] if formula.startswith("=") else formula


def add_sheet(workbook, name: str) -> Sheet:
    return workbook.add_worksheet(name, worksheet_class=Sheet)
