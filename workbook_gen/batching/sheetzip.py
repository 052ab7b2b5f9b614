"""A zip member deflated as its data arrives, then put into the zip XlsxWriter wrote.

summary.xlsx's Variants sheet is ~2.5 KB of XML per variant: deflating it after the
last variant (as XlsxWriter does when the workbook closes) put seconds of zlib after
the batch.  Here the sheet's XML is deflated as its rows are written (while the
workers evaluate the next blocks) by ISA-L's deflate at level 1 (``isal``: one raw
deflate stream, whose output does not depend on how the input is cut; three times
zlib's level-1 speed and a tenth smaller on this XML, for 100,000 variants ~1.4 s of
CPU instead of ~4.4 s), and ``splice`` writes the zip XlsxWriter made (with a one-line
stand-in for the rows) with that member's data, size and CRC in place of the stand-in.

A Variants sheet of more than 2 GiB of XML (about 800,000 variants of the sewing
machine) needs ZIP64, which XlsxWriter does not write.  That member is then written in
the form Excel reads without asking to repair the file (found by Apache POI's bug 57342
and rzymek/opczip: Excel looks at the *local* header): version needed 4.5, flag bit 3
(a data descriptor follows the data, holding the CRC and 8-byte sizes), no sizes in
the local header; in the central directory, version 4.5 and the uncompressed size as
0xFFFFFFFF with a ZIP64 extra field holding it (when 32 bits cannot).  Every other member is copied as it
is, so a smaller summary keeps its bytes.
"""

from __future__ import annotations

import io
import shutil
import struct
import tempfile
import zipfile
from typing import BinaryIO

from isal import isal_zlib

from ..workbook.xlsxwriter_internals import (encoded_filename, mark_modified, stringCentralDir,
                                            stringEndArchive, structCentralDir,
                                            structEndArchive)

_LOCAL_HEADER = 30  # bytes of a local file header before its name and extra field
# A member at least this large (uncompressed) is written in ZIP64 form: zipfile's own
# limit (2 GiB - 1, which readers that take sizes as signed 32-bit numbers also read).
ZIP64_THRESHOLD = zipfile.ZIP64_LIMIT
# ... and its central directory entry holds its size in a ZIP64 extra field from this
# size on, where 32 bits cannot hold it (LibreOffice 7.4 opens no file with such a
# field; the local form alone it opens).
ZIP64_EXTRA_THRESHOLD = 0xFFFFFFFF
_ZIP64_VERSION = 45
_DATA_DESCRIPTOR = 0x08
_LIMIT32 = 0xFFFFFFFF


class DeflatedMember:
    """One member's data, deflated (ISA-L level ``level``, raw) to a temporary file as
    it is written, with its CRC-32 and size."""

    def __init__(self, level: int = 1):
        self.level = level
        self._out = tempfile.TemporaryFile()
        self.restart()

    def restart(self) -> None:
        """Forget what was written."""
        self._out.seek(0)
        self._out.truncate()
        self._zlib = isal_zlib.compressobj(self.level, isal_zlib.DEFLATED, -15)
        self.crc = self.size = self.compressed_size = 0

    def write(self, data: bytes) -> None:
        self.crc = isal_zlib.crc32(data, self.crc)
        self.size += len(data)
        self._out.write(self._zlib.compress(data))

    def close(self) -> None:
        self._out.write(self._zlib.flush())
        self.compressed_size = self._out.tell()

    def copy_to(self, target: BinaryIO) -> None:
        self._out.seek(0)
        shutil.copyfileobj(self._out, target, 1 << 20)

    def discard(self) -> None:
        self._out.close()


def member_data(book: bytes, name: str) -> bytes:
    with zipfile.ZipFile(io.BytesIO(book)) as archive:
        return archive.read(name)


def needs_zip64(member: DeflatedMember) -> bool:
    return member.size >= ZIP64_THRESHOLD


def splice(book: bytes, name: str, member: DeflatedMember, target: BinaryIO) -> None:
    """Write ``book`` (a zip) to ``target`` with member ``name``'s data replaced by
    ``member``'s (closed): every other member copied as it is, ``name``'s local
    header and central directory entry made by ``zipfile`` from its own ``ZipInfo``
    (name, date, attributes) with the new CRC and sizes, or in ZIP64 form
    (``needs_zip64``)."""
    zip64 = needs_zip64(member)
    source = zipfile.ZipFile(io.BytesIO(book))
    out = zipfile.ZipFile(target, "w", compression=zipfile.ZIP_DEFLATED)
    try:
        for info in source.infolist():
            offset = info.header_offset
            start = out.fp.tell()
            if info.filename == name:
                info.CRC, info.file_size = member.crc, member.size
                info.compress_size = member.compressed_size
                if zip64:
                    _zip64_member(out.fp, info, member)
                else:
                    out.fp.write(info.FileHeader(False))
                    member.copy_to(out.fp)
            else:
                names, extra = struct.unpack("<HH", book[offset + 26:offset + 30])
                end = offset + _LOCAL_HEADER + names + extra + info.compress_size
                out.fp.write(book[offset:end])
            info.header_offset = start
            out.filelist.append(info)
            out.NameToInfo[info.filename] = info
        out.start_dir = out.fp.tell()
        if zip64:
            _central_directory(out.fp, out.filelist, name)
            out.fp = None  # written: nothing left for zipfile to write
        else:
            mark_modified(out)
    finally:
        out.close()  # the central directory, from those ZipInfo
        source.close()


def _dos_time(info: zipfile.ZipInfo) -> tuple[int, int]:
    y, mo, d, h, mi, s = info.date_time
    return h << 11 | mi << 5 | s // 2, (y - 1980) << 9 | mo << 5 | d


def _zip64_member(fp: BinaryIO, info: zipfile.ZipInfo, member: DeflatedMember) -> None:
    """The local header (no CRC, no sizes), the data, the ZIP64 data descriptor."""
    if member.compressed_size >= _LIMIT32 or fp.tell() >= _LIMIT32:
        raise zipfile.LargeZipFile("summary.xlsx: the Variants sheet deflates to more "
                                   "than 4 GiB")
    filename, flags = encoded_filename(info)
    info.flag_bits = flags | _DATA_DESCRIPTOR
    info.extract_version = info.create_version = _ZIP64_VERSION
    time, date = _dos_time(info)
    fp.write(struct.pack("<4sHHHHHIIIHH", b"PK\x03\x04", _ZIP64_VERSION, info.flag_bits,
                         zipfile.ZIP_DEFLATED, time, date, 0, 0, 0, len(filename), 0))
    fp.write(filename)
    member.copy_to(fp)
    fp.write(struct.pack("<4sIQQ", b"PK\x07\x08", member.crc, member.compressed_size,
                         member.size))


def _central_directory(fp: BinaryIO, infos: list[zipfile.ZipInfo], name: str) -> None:
    """The central directory and its end record, ``name``'s entry in ZIP64 form (its
    uncompressed size in a ZIP64 extra field where it needs one), the others as
    ``zipfile`` writes them."""
    start = fp.tell()
    if start >= _LIMIT32 or len(infos) >= 0xFFFF:
        raise zipfile.LargeZipFile("summary.xlsx: the zip would need a ZIP64 end record")
    for info in infos:
        filename, flags = encoded_filename(info)
        time, date = _dos_time(info)
        size, extra, version = info.file_size, info.extra, info.extract_version
        if info.filename == name and info.file_size >= ZIP64_EXTRA_THRESHOLD:
            size, extra = _LIMIT32, struct.pack("<HHQ", 1, 8, info.file_size)
        fp.write(struct.pack(structCentralDir, stringCentralDir,
                             max(version, info.create_version), info.create_system, version,
                             info.reserved, flags, info.compress_type, time, date, info.CRC,
                             info.compress_size, size, len(filename), len(extra),
                             len(info.comment), 0, info.internal_attr, info.external_attr,
                             info.header_offset))
        fp.write(filename + extra + info.comment)
    end = fp.tell()
    fp.write(struct.pack(structEndArchive, stringEndArchive, 0, 0,
                         len(infos), len(infos), end - start, start, 0))
