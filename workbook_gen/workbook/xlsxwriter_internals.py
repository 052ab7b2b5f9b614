"""The private and undocumented parts of XlsxWriter and zipfile that the writer relies on.

This is the one module of workbook_gen that imports a non-public name of either library,
calls or overrides one of their underscore methods, or sets an underscore attribute; every
other module uses the public names below (``FastZipFile``, ``ZippedWorkbook``,
``WorksheetHooks``, ``RowsInMemory``, ``xf_index``, ``assemble_xml`` ...).  Each is a
speed-up: XlsxWriter has no API for it.  ``PRIVATE`` lists every name relied on, with its
parameters where it is called or overridden; tests/workbook/test_xlsxwriter_internals.py
checks each against the installed libraries and fails naming the one that went or changed,
and checks that no other module uses an underscore name of either library.  XlsxWriter is
pinned to the tested range in pyproject.toml.

Undocumented attributes without an underscore are listed (and tested) here too, but are
still read where they are used: the worksheet state in workbook/rows.py's ``Sheet`` (a
subclass reading its own state), the drawing fields in workbook/package.py, Chart ``id``
in workbook/charts.py, ZipFile ``fp``, ``filelist``, ``NameToInfo``, ``start_dir`` and
ZipInfo ``FileHeader`` in batching/sheetzip.py, Workbook ``filename`` in
batching/summary.py, the series-cache options in batching/charts.py and
batching/statistics.py.

The names, and why:

- Packaging: XlsxWriter zips at zlib's default level with no option.  ``ZippedWorkbook``
  runs ``Workbook._store_workbook``'s own code with its global ``ZipFile`` bound to
  ``FastZipFile`` at the workbook's ``compresslevel`` (no assignment into xlsxwriter's
  module: every other workbook of the process keeps zipfile.ZipFile).
  ``FastZipFile.writestr`` writes an in-memory part itself (zipfile's local header and
  deflate, the deflated bytes of small parts kept per process), with ZipFile's
  ``_writecheck``, ``_lock``, ``_seekable``, ``_writing``, ``_didModify``, ``fp``,
  ``mode``, ``start_dir``, ``filelist``, ``NameToInfo`` and ZipInfo's ``_compresslevel``,
  ``FileHeader``.  batching/sheetzip.py splices a deflated sheet into a written zip with
  ZipInfo's ``_encodeFilenameFlags`` (``encoded_filename``), ``_didModify``
  (``mark_modified``) and zipfile's ``structCentralDir``, ``stringCentralDir``,
  ``structEndArchive``, ``stringEndArchive`` (the record layouts, re-exported here).
- Kept part XML (workbook/package.py drawings, workbook/charts.py charts): a part's
  ``_assemble_xml_file`` replaced per object (``replace_assembly``, ``assembly``), the
  class's run into a string (``assemble_xml``: the part's ``fh``, ``internal_fh``) and the
  kept text written with ``_xml_close`` (``write_xml``); ``Workbook._prepare_drawings``
  (the hook ``drawings_prepared``), Workbook ``drawings``, Drawing ``drawings``,
  ``embedded``, ``orientation`` (what a drawing's XML is made of), Chart ``id``; a chart
  object re-used by the next workbook (``reuse_chart``): Workbook ``charts``,
  ``date_1904``, ``remove_timezone``, Chart ``formula_data``, ``already_inserted``,
  ``date_1904``, ``remove_timezone``, and what its XML's assembly counts up: ``series_index``,
  ``axis_ids``, ``axis2_ids``.
- Rows written whole (workbook/rows.py): ``CellStringTuple``, ``CellFormulaTuple``,
  ``CellNumberTuple``, ``CellBlankTuple`` (the cells of the held row), ``_preserve_whitespace``
  and XMLwriter's ``_escape_control_characters`` (a string cell's XML), ``re_dynamic_function``
  (which formulas XlsxWriter rewrites), Format's ``_get_xf_index`` (``xf_index``), Worksheet's
  ``_write_single_row`` and ``_prepare_formula`` (overridden through ``WorksheetHooks``),
  ``_check_dimensions``, ``_write_cell``, and the constant_memory state the row writer reads:
  ``table``, ``previous_row``, ``row_info``, ``col_info``, ``comments``, ``excel_version``,
  ``default_row_height``, ``original_row_height``, ``dim_rowmin``, ``dim_rowmax``,
  ``dim_colmin``, ``dim_colmax``, ``constant_memory``, ``xls_rowmax``, ``xls_colmax``,
  ``xls_strmax``, ``fh``.
- Row data in memory (``RowsInMemory``, workbook/package.py): Worksheet's ``_initialize``,
  ``_opt_close``, ``_opt_reopen``, ``_write_optimized_sheet_data``, ``row_data_fh``,
  ``row_data_filename``, ``row_data_fh_closed`` and XMLwriter's ``_xml_start_tag``,
  ``_xml_end_tag``, ``_xml_empty_tag``.
- The summary's Variants rows (batching/summary.py): ``reserve_rows`` and
  ``discard_row_data`` over the state above; Workbook ``filename`` (its stream).
- Workbook ``in_memory``, set by workbook/package.py's Book after ``__init__`` (which
  turns constant_memory off with it): parts packaged in memory, rows written as they go.
- Series caches (batching/charts.py, statistics.py): add_series' undocumented options
  ``values_data``, ``categories_data``, ``name_data``.
"""

from __future__ import annotations

import io
import types
import zipfile
import zlib
from dataclasses import dataclass
from functools import partial
from pathlib import Path

import xlsxwriter
from xlsxwriter.worksheet import (CellBlankTuple, CellFormulaTuple, CellNumberTuple,
                                  CellStringTuple, Worksheet)
from xlsxwriter.worksheet import _preserve_whitespace as preserve_whitespace
from xlsxwriter.worksheet import re_dynamic_function as DYNAMIC_FUNCTION
from xlsxwriter.xmlwriter import XMLwriter
from zipfile import stringCentralDir, stringEndArchive, structCentralDir, structEndArchive

# XlsxWriter's and zipfile's own objects, imported here for the other modules (the rest
# of this module's public names are its own)
REEXPORTED = ("CellBlankTuple", "CellFormulaTuple", "CellNumberTuple", "CellStringTuple",
              "DYNAMIC_FUNCTION", "preserve_whitespace", "escape_control_characters",
              "stringCentralDir", "stringEndArchive", "structCentralDir", "structEndArchive")


@dataclass(frozen=True)
class Private:
    """A name relied on: ``module:Owner.name`` (``Owner().name``: an instance's attribute,
    ``module:name``: the module's), with a callable's parameters as its signature names
    them (None: not called, or any)."""

    path: str
    params: tuple[str, ...] | None = None


_S = ("self",)
PRIVATE: tuple[Private, ...] = (
    Private("xlsxwriter.workbook:ZipFile"),
    Private("xlsxwriter.workbook:Workbook._store_workbook", _S),
    Private("xlsxwriter.workbook:Workbook._prepare_drawings", _S),
    *(Private(f"xlsxwriter.workbook:Workbook().{n}") for n in (
        "filename", "in_memory", "drawings", "charts", "date_1904", "remove_timezone")),
    Private("xlsxwriter.worksheet:CellStringTuple"),
    Private("xlsxwriter.worksheet:CellFormulaTuple"),
    Private("xlsxwriter.worksheet:CellNumberTuple"),
    Private("xlsxwriter.worksheet:CellBlankTuple"),
    Private("xlsxwriter.worksheet:_preserve_whitespace", ("string",)),
    Private("xlsxwriter.worksheet:re_dynamic_function"),
    Private("xlsxwriter.worksheet:Worksheet._initialize", _S + ("init_data",)),
    Private("xlsxwriter.worksheet:Worksheet._write_single_row", _S + ("current_row_num",)),
    Private("xlsxwriter.worksheet:Worksheet._prepare_formula",
            _S + ("formula", "expand_future_functions")),
    Private("xlsxwriter.worksheet:Worksheet._check_dimensions",
            _S + ("row", "col", "ignore_row", "ignore_col")),
    Private("xlsxwriter.worksheet:Worksheet._write_cell", _S + ("row", "col", "cell")),
    Private("xlsxwriter.worksheet:Worksheet._opt_close", _S),
    Private("xlsxwriter.worksheet:Worksheet._opt_reopen", _S),
    Private("xlsxwriter.worksheet:Worksheet._write_optimized_sheet_data", _S),
    *(Private(f"xlsxwriter.worksheet:Worksheet().{n}") for n in (
        "table", "previous_row", "row_info", "col_info", "comments", "excel_version",
        "default_row_height", "original_row_height", "dim_rowmin", "dim_rowmax",
        "dim_colmin", "dim_colmax", "constant_memory", "xls_rowmax", "xls_colmax",
        "xls_strmax", "fh", "row_data_fh", "row_data_filename", "row_data_fh_closed")),
    Private("xlsxwriter.format:Format._get_xf_index", _S),
    Private("xlsxwriter.xmlwriter:XMLwriter._escape_control_characters", ("data",)),
    Private("xlsxwriter.xmlwriter:XMLwriter._xml_close", _S),
    Private("xlsxwriter.xmlwriter:XMLwriter._xml_start_tag", _S + ("tag", "attributes")),
    Private("xlsxwriter.xmlwriter:XMLwriter._xml_end_tag", _S + ("tag",)),
    Private("xlsxwriter.xmlwriter:XMLwriter._xml_empty_tag", _S + ("tag", "attributes")),
    Private("xlsxwriter.chart:Chart._assemble_xml_file", _S),
    *(Private(f"xlsxwriter.chart:Chart().{n}") for n in (
        "fh", "internal_fh", "id", "formula_data", "already_inserted", "date_1904",
        "remove_timezone", "series_index", "axis_ids", "axis2_ids")),
    Private("xlsxwriter.drawing:Drawing._assemble_xml_file", _S),
    *(Private(f"xlsxwriter.drawing:Drawing().{n}") for n in (
        "fh", "internal_fh", "drawings", "embedded", "orientation")),
    Private("zipfile:ZipFile._writecheck", _S + ("zinfo",)),
    *(Private(f"zipfile:ZipFile().{n}") for n in (
        "_lock", "_seekable", "_writing", "_didModify", "fp", "mode", "start_dir",
        "filelist", "NameToInfo")),
    Private("zipfile:ZipInfo.FileHeader", _S + ("zip64",)),
    Private("zipfile:ZipInfo._encodeFilenameFlags", _S),
    Private("zipfile:ZipInfo()._compresslevel"),
    *(Private(f"zipfile:{n}") for n in (
        "structCentralDir", "stringCentralDir", "structEndArchive", "stringEndArchive")),
)

#: add_series options XlsxWriter reads but does not document: a series' cached points.
SERIES_CACHE_OPTIONS = ("values_data", "categories_data", "name_data")


# -- cells and their XML ------------------------------------------------------------

escape_control_characters = XMLwriter._escape_control_characters


def xf_index(cell_format) -> int:
    """The ``s`` attribute XlsxWriter writes for a cell of ``cell_format``."""
    return cell_format._get_xf_index()


class WorksheetHooks(Worksheet):
    """XlsxWriter's Worksheet, the private methods a subclass overrides or calls under
    public names: ``write_held_row`` (``_write_single_row``: the row held back in
    constant_memory mode written, ``next_row`` becoming the held one) and
    ``prepare_formula`` (``_prepare_formula``), XlsxWriter's unless overridden."""

    def _write_single_row(self, current_row_num=0) -> None:
        self.write_held_row(current_row_num)

    def _prepare_formula(self, formula, expand_future_functions=False):
        return self.prepare_formula(formula, expand_future_functions)

    def write_held_row(self, next_row: int = 0) -> None:
        Worksheet._write_single_row(self, next_row)

    def prepare_formula(self, formula, expand_future_functions=False):
        return Worksheet._prepare_formula(self, formula, expand_future_functions)

    def flush_rows(self, next_row: int) -> None:
        """The held row written (by whichever ``_write_single_row`` the class has)."""
        self._write_single_row(next_row)

    def check_dimensions(self, row: int, col: int) -> bool:
        """True if (row, col) is outside the sheet; else the sheet's extent grows to it."""
        return bool(self._check_dimensions(row, col))

    def write_cell_xml(self, row: int, col: int, cell) -> None:
        """XlsxWriter's XML of one stored cell, written to ``self.fh``."""
        self._write_cell(row, col, cell)


class RowsInMemory(Worksheet):
    """A constant_memory sheet whose row data is a string buffer, not a temporary file
    (mixed in before a Worksheet subclass)."""

    def _initialize(self, init_data) -> None:
        super()._initialize({**init_data, "constant_memory": False})
        self.constant_memory = init_data["constant_memory"]
        if self.constant_memory:
            self.row_data_fh = io.StringIO()
            self.row_data_filename = None
            self.row_data_fh_closed = False
            self.fh = self.row_data_fh

    def _opt_close(self) -> None:
        pass  # nothing to close: the rows stay in the buffer until the sheet is packaged

    def _opt_reopen(self) -> None:
        self.fh = self.row_data_fh

    def _write_optimized_sheet_data(self) -> None:
        data, self.row_data_fh = self.row_data_fh.getvalue(), io.StringIO()
        if self.dim_rowmin is None:
            self._xml_empty_tag("sheetData")
            return
        self._xml_start_tag("sheetData")
        self.fh.write(data)
        self._xml_end_tag("sheetData")


def reserve_rows(sheet: Worksheet, last_row: int, last_col: int, stand_in: str) -> None:
    """A constant_memory sheet's rows 1 .. ``last_row`` left to be written into its XML
    later: the held (header) row written, the extent grown to (last_row, last_col), and
    ``stand_in`` where the rows go; cells written afterwards go below ``last_row``."""
    sheet._check_dimensions(last_row, last_col)
    sheet._write_single_row(1)
    sheet.previous_row = last_row + 1
    sheet.fh.write(stand_in)


def discard_row_data(sheet: Worksheet) -> None:
    """Remove a constant_memory sheet's temporary row file (a workbook never closed)."""
    if sheet.row_data_filename:
        if not sheet.row_data_fh.closed:
            sheet.row_data_fh.close()
        Path(sheet.row_data_filename).unlink(missing_ok=True)


# -- parts assembled once, their XML kept ---------------------------------------------

def assemble_xml(part) -> str:
    """The XML the part's class assembles (a chart, a drawing), as text: the part's own
    file handle untouched."""
    fh, internal = part.fh, part.internal_fh
    part.fh, part.internal_fh = io.StringIO(), False
    try:
        type(part)._assemble_xml_file(part)
        return part.fh.getvalue()
    finally:
        part.fh, part.internal_fh = fh, internal


def write_xml(part, xml: str) -> None:
    """Write ``xml`` as the part's assembled XML (what ``_assemble_xml_file`` writes)."""
    part.fh.write(xml)
    part._xml_close()


def replace_assembly(part, assemble) -> None:
    """The part assembles its XML with ``assemble()`` (no arguments) when packaged."""
    part._assemble_xml_file = assemble


def assembly(part):
    """What the part assembles its XML with (a ``replace_assembly`` partial)."""
    return part._assemble_xml_file


def reuse_chart(workbook, chart) -> bool:
    """Add a chart made for an earlier workbook (of the same date system) to ``workbook``
    as ``add_chart`` adds one: not inserted yet, its ranges' data not gathered (its id is
    set when packaged).  False, and nothing done, if the date systems differ."""
    if (chart.date_1904 != workbook.date_1904
            or chart.remove_timezone != workbook.remove_timezone):
        return False
    chart.already_inserted = False
    chart.formula_data = [None] * len(chart.formula_data)
    # what assembling its XML counts up (series idx/order, axis ids): from the start again,
    # else a chart assembled a second time numbers its series from 1 and adds axes
    chart.series_index = 0
    chart.axis_ids, chart.axis2_ids = [], []
    workbook.charts.append(chart)
    return True


# -- the package --------------------------------------------------------------------

class FastZipFile(zipfile.ZipFile):
    """zipfile.ZipFile at zlib level ``level`` (None: zipfile's default, and exactly
    zipfile.ZipFile).  ``writestr`` of a part to a seekable file (a ZipInfo, deflated:
    XlsxWriter's in-memory path) writes the entry itself: what zipfile writes (the local
    header with the final CRC and sizes, which zipfile writes first with zeros and then
    again over them, then the deflated bytes), without its write handle, and the deflated
    bytes of a small part kept per process (``_deflated``).  The central directory is
    zipfile's (``close``)."""

    def __init__(self, file, *args, level: int | None = None, **kwargs):
        self._level = level
        if level is not None:
            kwargs["compresslevel"] = level  # used by write(): the temp-file path
        super().__init__(file, *args, **kwargs)

    def writestr(self, zinfo_or_arcname, data, compress_type=None, compresslevel=None):
        if compresslevel is None:
            compresslevel = self._level  # the in-memory path passes ZipInfo objects
        if isinstance(data, str):
            data = data.encode("utf-8")   # as zipfile does
        zinfo = zinfo_or_arcname
        if (self._level is None or compress_type is not None or type(zinfo) is not zipfile.ZipInfo
                or zinfo.compress_type != zipfile.ZIP_DEFLATED or not self._seekable
                or not self.fp or self._writing or self.mode != "w"
                or len(data) * 1.05 > zipfile.ZIP64_LIMIT):
            return super().writestr(zinfo_or_arcname, data, compress_type, compresslevel)
        # zipfile's writestr, _open_to_write and _ZipWriteFile.write/close, in one
        zinfo._compresslevel = compresslevel
        zinfo.file_size = len(data)
        zinfo.flag_bits = 0x00
        if not zinfo.external_attr:
            zinfo.external_attr = 0o600 << 16
        with self._lock:
            self.fp.seek(self.start_dir)
            zinfo.header_offset = self.fp.tell()
            zinfo.compress_size = zinfo.CRC = 0
            self._writecheck(zinfo)
            self._didModify = True
            head, tail = _deflated(data, compresslevel)
            zinfo.compress_size = len(head) + len(tail)
            zinfo.CRC = zlib.crc32(data)
            self.fp.write(zinfo.FileHeader(False))
            self.fp.write(head)
            self.fp.write(tail)
            self.start_dir = self.fp.tell()
            self.filelist.append(zinfo)
            self.NameToInfo[zinfo.filename] = zinfo


#: Deflated parts kept per process by (level, bytes): most parts of a workbook (styles,
#: theme, charts, drawings, rels, content types) are the same for every design variant
#: of a scene, and deflate gives the same bytes for the same input.
DEFLATED: dict[tuple, tuple[bytes, bytes]] = {}
_DEFLATED_LIMIT = 512
_KEPT_SIZE = 1 << 16   # larger parts (the Table, the Checks) differ between variants


def _deflated(data: bytes, level: int) -> tuple[bytes, bytes]:
    """zipfile's deflate of a part (raw deflate at ``level``, one ``compress`` of the
    whole part, then ``flush``): the two outputs, kept for small parts."""
    key = (level, data) if len(data) <= _KEPT_SIZE else None
    found = None if key is None else DEFLATED.get(key)
    if found is None:
        packer = zlib.compressobj(level, zlib.DEFLATED, -15)
        found = packer.compress(data), packer.flush()
        if key is not None:
            if len(DEFLATED) >= _DEFLATED_LIMIT:
                DEFLATED.clear()
            DEFLATED[key] = found
    return found


def _store_workbook_with(zip_class):
    """``Workbook._store_workbook``'s own code, its global ``ZipFile`` ``zip_class``: a
    function of its own, over a copy of xlsxwriter.workbook's globals (the module is
    left as it is)."""
    store = xlsxwriter.Workbook._store_workbook
    scope = dict(store.__globals__, ZipFile=zip_class)
    return types.FunctionType(store.__code__, scope, store.__name__, store.__defaults__,
                              store.__closure__)


class ZippedWorkbook(xlsxwriter.Workbook):
    """An XlsxWriter Workbook zipped by ``FastZipFile`` at zlib level ``compresslevel``
    (None: zlib's default, as XlsxWriter), with a hook ``drawings_prepared`` run once its
    drawing parts exist (before they are assembled)."""

    compresslevel: int | None = None

    def _store_workbook(self) -> None:
        _store_workbook_with(partial(FastZipFile, level=self.compresslevel))(self)

    def _prepare_drawings(self) -> None:
        super()._prepare_drawings()
        self.drawings_prepared()

    def drawings_prepared(self) -> None:
        """Called when ``self.drawings`` holds the workbook's drawing parts."""


def encoded_filename(info: zipfile.ZipInfo) -> tuple[bytes, int]:
    """The member's name as the zip stores it, and the flag bits that encoding sets."""
    return info._encodeFilenameFlags()


def mark_modified(archive: zipfile.ZipFile) -> None:
    """``close`` writes the central directory of entries added to ``filelist`` by hand."""
    archive._didModify = True
