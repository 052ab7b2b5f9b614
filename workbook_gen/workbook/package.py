"""How the xlsx is packaged: in memory for ordinary workbooks, through temporary
files for very large ones.

XlsxWriter in ``constant_memory`` mode streams each sheet's rows to a temporary
file and writes every part of the package (sheets, styles, charts ...) to one
more before zipping them: about 30 files made and removed per workbook, which
cost more than writing a 10-degree workbook's cells on a slow file system.
A ``Book`` of up to ``IN_MEMORY_CELLS`` Table and Checks cells keeps the row data
and the parts in memory instead (``MemorySheet``); a larger one (a 0.01-degree
sweep, hundreds of megabytes of XML) keeps XlsxWriter's temporary files so that
memory stays bounded.  Both give the same cells; the choice depends on the
scene alone, so the same scene still gives the same bytes.
"""

from __future__ import annotations

import io
import zipfile
from enum import Enum
from functools import partial

import xlsxwriter
import xlsxwriter.workbook

from .rows import Sheet

#: zlib level of the package.  XlsxWriter leaves zlib's default (6); level 3 takes a
#: third of the time (0.7 s less for the 26 MB of XML of a 0.1-degree workbook) for a
#: file about 15 % larger.  Deterministic like any level: same scene, same bytes.
COMPRESSLEVEL = 3

#: Table + Checks cells up to which a workbook is packaged in memory (a 0.1-degree
#: sewing-machine workbook has about 200,000, some 25 MB of XML).
IN_MEMORY_CELLS = 600_000


class Stream(io.BytesIO):
    """The bytes of a Book's package, and the zlib level to write them with."""

    compresslevel = COMPRESSLEVEL


class _ZipFile(zipfile.ZipFile):
    """XlsxWriter's ZipFile, at the level of the file object it writes to when that
    names one (a ``Stream``); exactly zipfile.ZipFile otherwise.

    XlsxWriter offers no compression option: it makes the archive in
    ``Workbook._store_workbook`` with the module name ``ZipFile``, which is this class
    from the import of this module on (unchanged behaviour for every other file)."""

    def __init__(self, file, *args, **kwargs):
        self._level = getattr(file, "compresslevel", None)
        if self._level is not None:
            kwargs["compresslevel"] = self._level  # used by write(): the temp-file path
        super().__init__(file, *args, **kwargs)

    def writestr(self, zinfo_or_arcname, data, compress_type=None, compresslevel=None):
        if compresslevel is None:
            compresslevel = self._level  # the in-memory path passes ZipInfo objects
        if isinstance(data, str):
            data = data.encode("utf-8")   # as zipfile does
        self._part = data if self._level is not None and len(data) <= _KEPT_SIZE else None
        try:
            return super().writestr(zinfo_or_arcname, data, compress_type, compresslevel)
        finally:
            self._part = None

    def _open_to_write(self, zinfo, force_zip64=False):
        dest = super()._open_to_write(zinfo, force_zip64)
        part = getattr(self, "_part", None)
        if part is not None and dest._compressor is not None:
            dest._compressor = _Kept(dest._compressor,
                                     (zinfo.compress_type, zinfo._compresslevel, part))
        return dest


#: Deflated parts kept per process by (method, level, bytes): most parts of a workbook
#: (styles, theme, charts, drawings, rels, content types) are the same for every design
#: variant of a scene, and deflate gives the same bytes for the same input.
_DEFLATED: dict[tuple, tuple[bytes, bytes]] = {}
_DEFLATED_LIMIT = 512
_KEPT_SIZE = 1 << 16   # larger parts (the Table, the Checks) differ between variants


class _Kept:
    """The compressor of one ``writestr`` (one ``compress`` of the whole part, then
    ``flush``): the bytes kept for ``key``, else the real compressor's, then kept."""

    def __init__(self, real, key: tuple):
        self.real, self.key, self.kept, self.calls = real, key, _DEFLATED.get(key), 0
        self.out = b""

    def compress(self, data) -> bytes:
        self.calls += 1
        if self.calls > 1 or bytes(data) != self.key[2]:
            raise RuntimeError("a kept part must be compressed in one call")
        if self.kept is not None:
            return self.kept[0]
        self.out = self.real.compress(data)
        return self.out

    def flush(self) -> bytes:
        if self.kept is not None:
            return self.kept[1]
        tail = self.real.flush()
        if len(_DEFLATED) >= _DEFLATED_LIMIT:
            _DEFLATED.clear()
        _DEFLATED[self.key] = (self.out, tail)
        return tail


if xlsxwriter.workbook.ZipFile is zipfile.ZipFile:
    xlsxwriter.workbook.ZipFile = _ZipFile


class Book(xlsxwriter.Workbook):
    """A constant-memory workbook, its package built in memory when ``in_memory``."""

    def __init__(self, stream: Stream, in_memory: bool):
        super().__init__(stream, {"constant_memory": True})
        # Set after __init__, which would turn constant_memory off: the sheets still
        # write their rows as they go (MemorySheet keeps them in memory).
        self.in_memory = in_memory

    def sheet(self, name: str) -> Sheet:
        return self.add_worksheet(name, worksheet_class=MemorySheet if self.in_memory
                                  else Sheet)

    def _prepare_drawings(self) -> None:
        super()._prepare_drawings()
        for drawing in self.drawings:
            key = _drawing_key(drawing)
            if key is not None:
                drawing._assemble_xml_file = partial(_assemble_kept, drawing, key)


# A drawing part (where the charts sit) is a function of its anchors, sizes, names and
# kinds, all plain values: the same for every variant of a scene.  Its XML is kept per
# process by their text, as the charts' (charts.py).
_DRAWING_XML: dict[str, str] = {}
_DRAWING_XML_LIMIT = 256


def _plain(value) -> bool:
    if isinstance(value, (list, tuple)):
        return all(_plain(v) for v in value)
    return value is None or isinstance(value, (bool, int, float, str, Enum))


def _drawing_key(drawing) -> str | None:
    """Everything the drawing's XML is made of, as text; None if any is not plain."""
    items = []
    for info in drawing.drawings:
        try:
            fields = tuple(sorted(vars(info).items()))
        except TypeError:
            return None
        if not all(_plain(v) for _, v in fields):
            return None
        items.append(fields)
    return repr((type(drawing).__name__, drawing.embedded, drawing.orientation, items))


def _assemble_kept(drawing, key: str) -> None:
    """``drawing._assemble_xml_file()``, from the XML kept for ``key``."""
    found = _DRAWING_XML.get(key)
    if found is None:
        fh, internal = drawing.fh, drawing.internal_fh
        drawing.fh, drawing.internal_fh = io.StringIO(), False
        try:
            type(drawing)._assemble_xml_file(drawing)
            found = drawing.fh.getvalue()
        finally:
            drawing.fh, drawing.internal_fh = fh, internal
        if len(_DRAWING_XML) >= _DRAWING_XML_LIMIT:
            _DRAWING_XML.clear()
        _DRAWING_XML[key] = found
    drawing.fh.write(found)
    drawing._xml_close()


class MemorySheet(Sheet):
    """A Sheet whose constant_memory row data is a string buffer, not a temporary file."""

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
