"""Blocks of rows written whole, with the bytes XlsxWriter writes cell by cell.

``write_formula`` costs a few microseconds per cell in XlsxWriter (argument
decoding, a regex search for dynamic-array functions, XML escaping of every
formula, a dict per cell) and that was most of the time to write a workbook.
A Table or Checks column is one tree printed once with row slots
(``RowTemplate``), so here a block of rows becomes one row template made once
(XML-escaped once) and one ``str.format`` per row, written to the sheet's row
data in ``constant_memory`` mode.  The XML is exactly what XlsxWriter writes
for the same cells (tests compare the two byte for byte).

Our formulas use only the classic functions of ``expr.tree.FUNCTIONS``, so
XlsxWriter's future-function rewriting has nothing to do; a test checks that
none of them is a future or dynamic-array function.
"""

from __future__ import annotations

import io
import math
from dataclasses import dataclass
from functools import lru_cache
from itertools import repeat
from typing import Callable, Sequence

from ..cellref import column_letters
from ..expr.excel import RowTemplate
from .xlsxwriter_internals import (DYNAMIC_FUNCTION, CellBlankTuple, CellFormulaTuple,
                                   CellNumberTuple, CellStringTuple, WorksheetHooks,
                                   escape_control_characters, preserve_whitespace, xf_index)

ERROR_CODES = frozenset(("#DIV/0!", "#N/A", "#NAME?", "#NULL!", "#NUM!", "#REF!", "#VALUE!"))
_CHUNK = 500  # rows per write (and per progress call)
_PLAIN = (CellStringTuple, CellFormulaTuple, CellNumberTuple, CellBlankTuple)


@dataclass(frozen=True)
class Column:
    """One column of a block: a formula with its cached values, or numbers."""

    col: int                           # 0-based column index
    values: Sequence                   # one per row: the cached values, or the numbers
    formula: RowTemplate | None = None  # None: number cells
    cell_format: object = None         # an XlsxWriter Format, else the column's format


@lru_cache(maxsize=None)
def _column_name(col: int) -> str:
    """The letters of a 0-based column index (XlsxWriter's numbering): 0 -> A."""
    return column_letters(col + 1)


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _brace(text: str) -> str:
    return text.replace("{", "{{").replace("}", "}}")


def cached_xml(value) -> tuple[str, str]:
    """The type attribute and ``<v>`` text XlsxWriter writes for a formula's cached value."""
    if isinstance(value, bool):
        return ' t="b"', "1" if value else "0"
    if isinstance(value, str):
        if value == "":
            return "", ""
        if value in ERROR_CODES:
            return ' t="e"', value
        return ' t="str"', _escape(value)
    return "", f"{value}"


def _number_xml(value) -> str:
    if not math.isfinite(value):
        raise ValueError(f"a number cell cannot hold {value!r}")
    return f"{value:.16G}"


#: A string cell's XML after its reference and style, by its text: XlsxWriter's inline
#: string (control characters escaped, leading/trailing space preserved, XML-escaped).
_STRING_XML: dict[str, str] = {}
_STRING_XML_LIMIT = 4096  # entries; cleared past it (a batch's varied texts never repeat)


def _string_xml(text: str) -> str | None:
    """``' t="inlineStr"><is><t>...</t></is></c>'`` as XlsxWriter writes ``text`` in
    constant_memory mode; None for a rich string (written by XlsxWriter itself)."""
    found = _STRING_XML.get(text)
    if found is None:
        text_x = escape_control_characters(text)
        if text_x.startswith("<r>") and text_x.endswith("</r>"):
            return None
        space = ' xml:space="preserve"' if preserve_whitespace(text_x) else ""
        found = f' t="inlineStr"><is><t{space}>{_escape(text_x)}</t></is></c>'
        if len(_STRING_XML) >= _STRING_XML_LIMIT:
            _STRING_XML.clear()
        _STRING_XML[text] = found
    return found


def _formula_cell_xml(cell) -> str:
    """A formula cell's XML after its reference and style, as ``_write_cell`` writes it."""
    value = cell.value
    kind = ""
    if isinstance(value, bool):
        kind, value = ' t="b"', 1 if value else 0
    elif isinstance(value, str):
        if value in ERROR_CODES:
            kind = ' t="e"'
        elif value != "":
            kind = ' t="str"'
        value = _escape(value)
    return f"{kind}><f>{_escape(cell.formula)}</f><v>{value}</v></c>"


@lru_cache(maxsize=4096)
def _formula_xml(formula: RowTemplate, offsets: tuple[int, ...]) -> str:
    """A formula's ``<f>`` text with ``{k}`` slots for its rows (the k-th of ``offsets``),
    XML-escaped and brace-escaped once per process."""
    slot = {o: "{%d}" % i for i, o in enumerate(offsets)}
    parts = formula.parts
    offs = formula.offsets or tuple(repeat(0, len(parts) - 1))
    text = [_brace(_escape(parts[0].removeprefix("=")))]
    for o, part in zip(offs, parts[1:]):
        text += [slot[o], _brace(_escape(part))]
    return "".join(text)


class Sheet(WorksheetHooks):
    """A worksheet that writes our formula text as it is, and blocks of rows whole."""

    def write_held_row(self, current_row_num=0) -> None:
        """XlsxWriter's (constant_memory: the row held back, then the table cleared), the
        XML of plain rows of numbers, texts and formulas written here at once: the same
        bytes as ``_write_row`` and ``_write_cell``, each style index asked in the order
        they ask it (so the xf numbering is unchanged)."""
        row = self.previous_row
        cells = self.table.get(row)
        if (not cells or row in self.comments or self.excel_version != 2007
                or not all(type(c) in _PLAIN for c in cells.values())):
            return super().write_held_row(current_row_num)
        self.previous_row = current_row_num
        info = self.row_info.get(row)
        row_format = None
        out = [f'<row r="{row + 1}"']
        height = self.default_row_height
        if info is not None:
            row_format = info.row_format
            if info.height is not None:
                height = info.height
            if row_format:
                index = xf_index(row_format)
                if index:
                    out.append(f' s="{index}"')
                out.append(' customFormat="1"')
        custom = height != self.original_row_height or height != self.default_row_height
        if custom:
            out.append(f' ht="{height * 0.75:.16g}"')
        if info is not None and info.hidden:
            out.append(' hidden="1"')
        if custom:
            out.append(' customHeight="1"')
        if info is not None and info.level:
            out.append(f' outlineLevel="{info.level}"')
        if info is not None and info.collapsed:
            out.append(' collapsed="1"')
        out.append(">")
        number = str(row + 1)
        col_info = self.col_info
        for col in sorted(cells):
            cell = cells[col]
            fmt = cell.format
            if not fmt:
                fmt = row_format if row_format else None
                if fmt is None and col in col_info:
                    fmt = col_info[col].column_format
            ref = f'<c r="{_column_name(col)}{number}"'
            if fmt is not None:
                ref += f' s="{xf_index(fmt)}"'
            kind = type(cell)
            if kind is CellStringTuple:
                text = _string_xml(cell.string)
                if text is None:   # a rich string: XlsxWriter's own XML
                    fh, self.fh = self.fh, io.StringIO()
                    try:
                        self.write_cell_xml(row, col, cell)
                        out.append(self.fh.getvalue())
                    finally:
                        self.fh = fh
                    continue
                out += (ref, text)
            elif kind is CellFormulaTuple:
                out += (ref, _formula_cell_xml(cell))
            elif kind is CellNumberTuple:
                out.append(f"{ref}><v>{cell.number:.16G}</v></c>")
            else:   # blank
                out.append(ref + "/>")
        out.append("</row>")
        self.fh.write("".join(out))
        self.table.clear()

    # write_string, write_number and write_formula: XlsxWriter's (A1 notation, bounds and
    # dimensions, the row held back in constant_memory mode, the cell stored), without
    # its argument decoding and checks where the cell is a plain one at (row, col) ints,
    # in the sheet, at or below the row held back (else XlsxWriter's own methods).

    def _put(self, row: int, col: int, cell) -> None:
        if self.dim_rowmin is None or row < self.dim_rowmin:
            self.dim_rowmin = row
        if self.dim_rowmax is None or row > self.dim_rowmax:
            self.dim_rowmax = row
        if self.dim_colmin is None or col < self.dim_colmin:
            self.dim_colmin = col
        if self.dim_colmax is None or col > self.dim_colmax:
            self.dim_colmax = col
        if row > self.previous_row:
            self.flush_rows(row)
        self.table[row][col] = cell

    def _plain_cell(self, row, col) -> bool:
        return (row.__class__ is int and col.__class__ is int and self.constant_memory
                and self.previous_row <= row < self.xls_rowmax and 0 <= col < self.xls_colmax)

    def write_string(self, *args, **kwargs):
        if len(args) in (3, 4) and not kwargs and self._plain_cell(args[0], args[1]):
            string = args[2]
            if string.__class__ is str and len(string) <= self.xls_strmax // 2:
                self._put(args[0], args[1], CellStringTuple(string, args[3] if len(args) == 4
                                                            else None))
                return 0
        return WorksheetHooks.write_string(self, *args, **kwargs)

    def write_number(self, *args, **kwargs):
        if len(args) in (3, 4) and not kwargs and self._plain_cell(args[0], args[1]):
            number = args[2]
            if number.__class__ is int or (number.__class__ is float and math.isfinite(number)):
                self._put(args[0], args[1], CellNumberTuple(number, args[3] if len(args) == 4
                                                            else None))
                return 0
        return WorksheetHooks.write_number(self, *args, **kwargs)

    def write_formula(self, *args, **kwargs):
        if 3 <= len(args) <= 5 and not kwargs and self._plain_cell(args[0], args[1]):
            formula = args[2]
            if (formula.__class__ is str and formula and not DYNAMIC_FUNCTION.search(formula)
                    and not (formula.startswith("{") and formula.endswith("}"))):
                self._put(args[0], args[1], CellFormulaTuple(
                    self.prepare_formula(formula), args[3] if len(args) > 3 else None,
                    args[4] if len(args) > 4 else 0))
                return 0
        return WorksheetHooks.write_formula(self, *args, **kwargs)

    def prepare_formula(self, formula, expand_future_functions=False):
        return formula[1:] if formula.startswith("=") else formula

    def _style(self, column: Column) -> str:
        """The ``s`` attribute XlsxWriter gives the cell: its format, else the column's."""
        fmt = column.cell_format
        if fmt is None and column.col in self.col_info:
            fmt = self.col_info[column.col].column_format
        return "" if fmt is None else f' s="{xf_index(fmt)}"'

    def write_rows(self, first_row: int, columns: Sequence[Column],
                   progress: Callable[[int], None] | None = None) -> None:
        """Write ``len(values)`` rows from ``first_row`` (0-based), the cells of
        ``columns`` in each; the rows must lie below every cell written so far."""
        count = len(columns[0].values) if columns else 0
        if count == 0:
            return
        if any(len(c.values) != count for c in columns):
            raise ValueError("write_rows: columns of different lengths")
        last_row = first_row + count - 1
        columns = sorted(columns, key=lambda c: c.col)
        if not self.constant_memory:
            raise ValueError("write_rows needs the constant_memory mode")
        if first_row < self.previous_row or (first_row == self.previous_row
                                             and self.table.get(first_row)):
            raise ValueError(f"write_rows: row {first_row} is above rows already written")
        if (self.excel_version != 2007 or self.default_row_height != self.original_row_height
                or any(first_row <= r <= last_row for r in self.row_info)):
            raise ValueError("write_rows writes plain rows only (no row formats or heights)")
        for row, col in ((first_row, columns[0].col), (last_row, columns[-1].col)):
            if self.check_dimensions(row, col):
                raise ValueError(f"write_rows: cell ({row}, {col}) is outside the sheet")
        if first_row > self.previous_row:  # flush the row XlsxWriter holds back
            self.flush_rows(first_row)

        template, offsets, arguments = self._row_template(columns)
        # 1-based row numbers (ints: str.format prints them as str() would)
        rows = [range(first_row + 1 + o, last_row + 2 + o) for o in offsets]
        lists = rows + arguments
        write = self.fh.write
        fmt = template.format
        for lo in range(0, count, _CHUNK):
            hi = min(lo + _CHUNK, count)
            write("".join([fmt(*cells) for cells in zip(*(a[lo:hi] for a in lists))]))
            if progress is not None:
                progress(hi - lo)
        self.previous_row = last_row + 1
        self.table.clear()

    def _row_template(self, columns: Sequence[Column]) -> tuple[str, list[int], list[list]]:
        """``'<row r="{0}">...</row>'`` with ``{k}`` slots, the row offsets of the first
        slots, and the lists that fill the other slots (one item per row)."""
        offsets = [0]
        for c in columns:
            if c.formula is not None:
                offsets += [o for o in c.formula.offsets if o not in offsets]
        offsets_key = tuple(offsets)
        arguments: list[list] = []

        def add(values: list) -> str:
            arguments.append(values)
            return "{%d}" % (len(offsets) + len(arguments) - 1)

        out = ['<row r="{0}">']
        for c in columns:
            out.append(f'<c r="{_column_name(c.col)}{{0}}"{self._style(c)}')
            if c.formula is None:
                out.append("><v>" + add([_number_xml(v) for v in c.values]) + "</v></c>")
                continue
            if set(map(type, c.values)) == {float}:  # the common case, at C speed
                out.append("")
                texts = c.values   # str.format prints a float as str() does (its repr)
            else:
                pairs = [cached_xml(v) for v in c.values]
                types = {t for t, _ in pairs}
                out.append(_brace(types.pop()) if len(types) == 1
                           else add([t for t, _ in pairs]))
                texts = [v for _, v in pairs]
            out.append("><f>" + _formula_xml(c.formula, offsets_key) + "</f><v>"
                       + add(texts) + "</v></c>")
        out.append("</row>")
        return "".join(out), offsets, arguments
