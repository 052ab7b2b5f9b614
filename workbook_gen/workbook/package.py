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
import zlib
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
    from the import of this module on (unchanged behaviour for every other file).

    ``writestr`` of a part to a ``Stream`` (the in-memory path: a ZipInfo, deflated, a
    seekable file) writes the entry itself: what zipfile writes (the local header with
    the final CRC and sizes, which zipfile writes first with zeros and then again over
    them, then the deflated bytes), without its write handle, and the deflated bytes of
    a small part kept per process (``_deflated``).  The central directory is zipfile's
    (``close``)."""

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
_DEFLATED: dict[tuple, tuple[bytes, bytes]] = {}
_DEFLATED_LIMIT = 512
_KEPT_SIZE = 1 << 16   # larger parts (the Table, the Checks) differ between variants


def _deflated(data: bytes, level: int) -> tuple[bytes, bytes]:
    """zipfile's deflate of a part (raw deflate at ``level``, one ``compress`` of the
    whole part, then ``flush``): the two outputs, kept for small parts."""
    key = (level, data) if len(data) <= _KEPT_SIZE else None
    found = None if key is None else _DEFLATED.get(key)
    if found is None:
        packer = zlib.compressobj(level, zlib.DEFLATED, -15)
        found = packer.compress(data), packer.flush()
        if key is not None:
            if len(_DEFLATED) >= _DEFLATED_LIMIT:
                _DEFLATED.clear()
            _DEFLATED[key] = found
    return found


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


_PLAIN_TYPES = frozenset((type(None), bool, int, float, str))


def _plain(value) -> bool:
    kind = type(value)
    if kind in _PLAIN_TYPES:
        return True
    if isinstance(value, (list, tuple)):
        return all(type(v) in _PLAIN_TYPES or _plain(v) for v in value)
    return isinstance(value, (bool, int, float, str, Enum))


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
