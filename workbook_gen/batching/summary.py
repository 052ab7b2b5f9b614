"""summary.csv, summary.parquet and summary.xlsx of a batch (written last, atomically,
same bytes for the same command).

summary.xlsx: a Variants sheet (headers with units, frozen, autofilter, the file
column a HYPERLINK to each workbook (a formula: no limit of 65,530 links per sheet),
rows not ``ok`` marked by conditional formats), for a random study a Statistics sheet
(``statistics.py``), a Charts sheet (``charts.py``) and an About sheet.
"""

from __future__ import annotations

import csv
import datetime as dt
import io
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

from ..cellref import column_letters
from ..files import Place, write_atomically
from ..version import VERSION
from ..workbook.xlsxwriter_internals import ZippedWorkbook, discard_row_data, reserve_rows
from .blocktext import block_texts
from .columnar import ParquetSink
from .sheetzip import DeflatedMember, member_data, splice
from .charts import charts_sheet
from .statistics import write_statistics
from .table import Table
from .variants import MAX_CELL_TEXT

DOCUMENT_DATE = dt.datetime(2024, 1, 1)
_ROWS_PER_WRITE = 2000
VARIANTS = "xl/worksheets/sheet1.xml"   # the Variants sheet in the zip
_ROWS = "<!--workbook-gen: the data rows-->"


class _SummaryBook(ZippedWorkbook):
    """XlsxWriter zips at zlib's default level 6 and has no option for it; a summary of
    100,000 variants is ~70 MB of XML, which level 1 packs a third faster (the file is
    somewhat larger).  Only this workbook: every other keeps its level."""

    compresslevel = 1


@dataclass(frozen=True)
class BlockText:
    """A block of rows formatted where it was evaluated (``blocktext.block_texts``),
    with the kinds it assumed for the figure columns and which of them it fills."""

    csv: str
    xml: bytes
    kinds: tuple[tuple[str, str], ...]
    filled: frozenset[str]

    def fits(self, table: Table) -> bool:
        """Whether the block's text is what the whole table's column kinds give: a
        kind differs only in how a filled cell is written, and a text is written
        alike in a ``text`` and a ``mixed`` column."""
        for name, kind in self.kinds:
            whole = table.kind(name)
            if name in self.filled and kind != whole and (kind, whole) != ("text", "mixed"):
                return False
        return True


class SummaryWriter:
    """summary.csv, summary.parquet and summary.xlsx of a batch (each written
    atomically, same bytes for the same command).  Blocks of rows formatted
    elsewhere may be added as they arrive, in any order: each is written (its sheet
    XML deflated, its values appended to the Parquet file) when the rows before it
    are; at ``finish`` the rest (all of them for a file batch) are formatted here from
    the table, and all of them if a block was formatted with a kind the whole table
    does not have (read back from the Parquet file when the table keeps no rows)."""

    def __init__(self, table: Table, csv_path: Path, xlsx_path: Path):
        self.table, self.csv_path, self.xlsx_path = table, csv_path, xlsx_path
        fd, temp = tempfile.mkstemp(prefix=f".{csv_path.stem}.", suffix=".csv.tmp",
                                    dir=csv_path.parent)
        self._csv_temp = Path(temp)
        self._csv = os.fdopen(fd, "w", encoding="utf-8", newline="")
        self._book = self._sheet = self._rows = self._sink = None
        self._sunk = 1                      # the next variant index to append to Parquet
        try:
            self._sink = ParquetSink(
                csv_path.with_suffix(".parquet"), table.columns, table.headers,
                table.figures, table.design.kind != "design" or all(
                    v.label == str(v.index) for v in table.design.variants),
                texts_always=table.text_options,
                integers=set(table.design.options) - table.text_options)
            csv.writer(self._csv, lineterminator="\n").writerow(table.headers)
            self._csv_mark = self._csv.tell()
            self._book, self._sheet = _book(table)
            if len(table.design):  # else XlsxWriter writes the sheet (a header row)
                self._rows = DeflatedMember()
                self._prefix = _variants_xml(table)[0]
                self._rows.write(self._prefix)
        except BaseException:
            self.abort()
            raise
        self._next = 1                      # the next variant index to write
        self._waiting: dict[int, tuple[int, BlockText]] = {}
        self._written: list[BlockText] = []

    def add(self, first: int, count: int, text: BlockText, variants=None, block=None
            ) -> None:
        """Rows ``first .. first + count - 1`` (variant indices), formatted, and their
        every column (``block``, as ``summary_rows`` gives them) for the Parquet file."""
        self._waiting[first] = (count, text, variants, block)
        while self._next in self._waiting:
            count, text, variants, block = self._waiting.pop(self._next)
            self._csv.write(text.csv)
            self._rows.write(text.xml)
            self._written.append(BlockText("", b"", text.kinds, text.filled))  # not the text
            if block is not None:
                self._sink.write(block, count)
                self._sunk += count
            self._next += count

    def _stored(self, names=None):
        """The rows from ``self._next`` on, ``ROWS_PER_WRITE`` or so at a time, from the
        table or (a table that keeps none) the Parquet file."""
        table = self.table
        names = list(names or table.columns)
        if table.keep:
            for lo in range(self._next - 1, len(table.design), _ROWS_PER_WRITE):
                hi = min(len(table.design), lo + _ROWS_PER_WRITE)
                yield lo, {name: table.data[name][lo:hi] for name in names}
            return
        self._sink.close()
        yield from self._sink.batches(names, self._next - 1)

    def _format(self, csv_too: bool = True) -> None:
        """The rows from ``self._next`` on, formatted here from the table."""
        table = self.table
        size = len(table.design)
        if not size:
            return
        columns, kinds = table.columns, {name: table.kind(name) for name in table.columns}
        for lo, data in self._stored():
            count = len(data["variant"])
            csv_text, xml_text = block_texts(columns, kinds, data, lo + 2, count)
            if csv_too:
                self._csv.write(csv_text)
            self._rows.write(xml_text.encode())
            if lo + 1 >= self._sunk:  # not yet in the Parquet file
                self._sink.write(data, count)
                self._sunk = lo + 1 + count
        self._next = size + 1

    def finish(self, about: Sequence[tuple[str, str]], place: Place = os.replace) -> None:
        """Write the rest and put both files in place: ``place(temporary, target)``
        (a rename by default; the batch folder's keeps a summary edited since)."""
        table = self.table
        try:
            if not all(text.fits(table) for text in self._written):
                self._csv.seek(self._csv_mark)
                self._csv.truncate()
                self._rows.restart()
                self._rows.write(self._prefix)
                self._next = 1
            self._written, self._waiting = [], {}
            self._format()
            self._csv.close()
            os.chmod(self._csv_temp, 0o644)
            if not table.keep:  # the columns they read, back from the Parquet file
                table.data = _Stored(self._sink)
            write_statistics(self._book, table)
            charts = self._book.add_worksheet("Charts")
            _about_sheet(self._book, about)
            charts_sheet(self._book, charts, table)  # after About: its data sheet comes last
            stream = self._book.filename
            self._book.close()
            self._book = None
            book = stream.getvalue()
            place(self._csv_temp, self.csv_path)
            if self._rows is None:
                self._sink.finish({name: table.kind(name) for name in table.columns})
                write_atomically(self.xlsx_path, lambda temp: temp.write_bytes(book), force=True,
                                 place=place)
                return
            prefix, suffix = member_data(book, VARIANTS).split(_ROWS.encode())
            if prefix != self._prefix:  # the sheet starts otherwise: its rows again after it
                self._rows.restart()
                self._rows.write(prefix)
                self._next = 1
                self._format(csv_too=False)
            self._rows.write(suffix)
            self._rows.close()
            self._sink.finish({name: table.kind(name) for name in table.columns})

            def build(temp: Path) -> None:
                with temp.open("wb") as handle:
                    splice(book, VARIANTS, self._rows, handle)
            write_atomically(self.xlsx_path, build, force=True, place=place)
            self._rows.discard()
        except BaseException:
            self.abort()
            raise

    def abort(self) -> None:
        """Remove the temporary files (nothing is written to the summaries' paths)."""
        if not self._csv.closed:
            self._csv.close()
        self._csv_temp.unlink(missing_ok=True)
        if self._sink is not None:
            self._sink.abort()
        if self._rows is not None:
            self._rows.discard()
        sheet = self._sheet
        if self._book is not None and sheet is not None:
            discard_row_data(sheet)
        self._book = None


class _Stored(dict):
    """A table's columns read back from the Parquet file when first asked (the
    Statistics and Charts sheets of a table that keeps no rows): numbers as float64
    arrays."""

    def __init__(self, sink: ParquetSink):
        super().__init__()
        self._sink = sink

    def __missing__(self, name: str):
        self._sink.close()
        column = self[name] = self._sink.column(name)
        return column


def write_summaries(table: Table, csv_path: Path, xlsx_path: Path,
                    about: Sequence[tuple[str, str]]) -> None:
    """summary.csv and summary.xlsx of a complete table, formatted here."""
    SummaryWriter(table, csv_path, xlsx_path).finish(about)


def _variants_head(book, table: Table):
    """The Variants sheet up to its data rows (written whole by ``block_texts``, the
    XML XlsxWriter writes for the same cells in constant_memory mode: XlsxWriter takes
    microseconds per cell, and a summary may have 100,000 rows x 70 columns)."""
    sheet = book.add_worksheet("Variants")
    header = book.add_format({"bold": True, "bottom": 1, "text_wrap": True, "valign": "top"})
    sheet.freeze_panes(1, 0)
    sheet.set_row(0, 30, header)
    sheet.set_column(0, 0, 9)
    sheet.set_column(1, 1, 24)
    sheet.set_column(2, 2, 14)
    sheet.set_column(3, len(table.columns) - 1, 13)
    size = len(table.design)
    last_col = len(table.columns) - 1
    status = column_letters(3)
    audit = column_letters(last_col + 1)
    for rule, colour in ((f'=LEFT(${status}2,7)="refused"', "#F4B6B6"),
                         (f'=${status}2="partial"', "#FCE4B6"),
                         (f'=${audit}2="fail"', "#F4B6B6")):
        sheet.conditional_format(1, 0, max(1, size), last_col, {
            "type": "formula", "criteria": rule,
            "format": book.add_format({"bg_color": colour})})
    sheet.autofilter(0, 0, max(1, size), last_col)
    sheet.write_row(0, 0, table.headers, header)
    if size:  # the header row now, then the data rows' place
        reserve_rows(sheet, size, last_col, _ROWS)
    return sheet


def _book(table: Table):
    """summary.xlsx without its Charts and About sheets, the Variants sheet's data rows
    a stand-in (``_ROWS``)."""
    book = _SummaryBook(io.BytesIO(), {"constant_memory": True, "nan_inf_to_errors": False})
    book.set_properties({"title": "workbook-gen batch summary", "author": "workbook-gen",
                         "comments": f"Generated by workbook-gen {VERSION}",
                         "created": DOCUMENT_DATE})
    return book, _variants_head(book, table)


def _variants_xml(table: Table) -> tuple[bytes, bytes]:
    """The Variants sheet's XML before and after its data rows, as XlsxWriter writes
    them (the sheet of a workbook closed as soon as it is made; ``finish`` checks the
    real one)."""
    book, _ = _book(table)
    book.close()
    before, after = member_data(book.filename.getvalue(), VARIANTS).split(_ROWS.encode())
    return before, after




def _about_sheet(book, about: Sequence[tuple[str, str]]) -> None:
    sheet = book.add_worksheet("About")
    label = book.add_format({"bold": True, "valign": "top"})
    sheet.set_column(0, 0, 20)
    sheet.set_column(1, 1, 110)
    row = 0
    for key, value in about:
        sheet.write_string(row, 0, key, label)
        for line in value.splitlines() or [""]:
            for piece in cell_pieces(line):
                sheet.write_string(row, 1, piece)
                row += 1


def cell_pieces(text: str, limit: int = MAX_CELL_TEXT) -> list[str]:
    """``text`` cut into pieces of at most ``limit`` UTF-16 code units (what an Excel
    cell holds), to go in consecutive cells: a command line of thousands of
    ``--vary`` values is kept whole on the About sheet, over several rows."""
    pieces = []
    while True:
        n = limit
        while len(text[:n].encode("utf-16-le")) // 2 > limit:  # characters beyond the BMP
            n -= len(text[:n].encode("utf-16-le")) // 2 - limit
        pieces.append(text[:n])
        text = text[n:]
        if not text:
            return pieces
