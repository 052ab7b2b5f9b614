"""batching/sheetzip.py: a member deflated as it arrives (inflated back by zlib, its
CRC-32 by zlib.crc32) spliced into a zip XlsxWriter wrote: zipfile reads every member
back and checks their CRCs, the other members keep their bytes, openpyxl reads the new
sheet; in ZIP64 form (thresholds lowered) the local header is the one of the ZIP spec
(APPNOTE 4.3.7/4.3.9: version 45, bit 3, a data descriptor with 8-byte sizes), which
zipfile reads, and the central directory's ZIP64 extra field (APPNOTE 4.5.3) holds the
size."""

from __future__ import annotations

import io
import struct
import zipfile
import zlib

import openpyxl
import pytest
import xlsxwriter

from workbook_gen.batching import sheetzip
from workbook_gen.batching.sheetzip import DeflatedMember, member_data, needs_zip64, splice

SHEET = "xl/worksheets/sheet1.xml"


def _book() -> bytes:
    stream = io.BytesIO()
    book = xlsxwriter.Workbook(stream, {"in_memory": True})
    sheet = book.add_worksheet("Variants")
    sheet.write_string(0, 0, "stand-in")
    book.add_worksheet("About").write_string(0, 0, "about")
    book.close()
    return stream.getvalue()


def _member(data: bytes, pieces: int = 7) -> DeflatedMember:
    member = DeflatedMember()
    step = max(1, len(data) // pieces)
    for i in range(0, len(data), step):
        member.write(data[i:i + step])
    member.close()
    return member


def _sheet_xml(rows: int) -> bytes:
    """The stand-in sheet's XML with ``rows`` rows of numbers in column A."""
    xml = member_data(_book(), SHEET).decode()
    cells = "".join(f'<row r="{r}"><c r="A{r}"><v>{r * 0.5}</v></c></row>'
                    for r in range(1, rows + 1))
    head, rest = xml.split("<sheetData>")
    _, tail = rest.split("</sheetData>")
    return f"{head}<sheetData>{cells}</sheetData>{tail}".encode()


def test_deflated_member_inflates_to_its_data():
    data = _sheet_xml(300)
    member = _member(data)
    out = io.BytesIO()
    member.copy_to(out)
    assert zlib.decompressobj(-15).decompress(out.getvalue()) == data
    assert member.crc == zlib.crc32(data) and member.size == len(data)
    assert member.compressed_size == len(out.getvalue()) < len(data)
    member.restart()
    member.write(b"abc")
    member.close()
    out = io.BytesIO()
    member.copy_to(out)
    assert zlib.decompressobj(-15).decompress(out.getvalue()) == b"abc"
    assert member.crc == zlib.crc32(b"abc")
    member.discard()


def test_splice_replaces_one_member():
    book, data = _book(), _sheet_xml(50)
    target = io.BytesIO()
    splice(book, SHEET, _member(data), target)
    spliced = target.getvalue()
    with zipfile.ZipFile(io.BytesIO(spliced)) as z, zipfile.ZipFile(io.BytesIO(book)) as old:
        assert z.testzip() is None                                # every CRC
        assert z.namelist() == old.namelist()
        for name in old.namelist():
            assert z.read(name) == (data if name == SHEET else old.read(name)), name
            assert z.getinfo(name).date_time == old.getinfo(name).date_time
    ws = openpyxl.load_workbook(io.BytesIO(spliced))["Variants"]
    assert ws.max_row == 50 and ws["A50"].value == 25.0
    assert not needs_zip64(_member(data))


@pytest.mark.parametrize("extra", [False, True])
def test_zip64_form(monkeypatch, extra):
    data = _sheet_xml(40)
    monkeypatch.setattr(sheetzip, "ZIP64_THRESHOLD", 1000)
    if extra:
        monkeypatch.setattr(sheetzip, "ZIP64_EXTRA_THRESHOLD", 1000)
    member = _member(data)
    assert needs_zip64(member)
    target = io.BytesIO()
    splice(_book(), SHEET, member, target)
    spliced = target.getvalue()
    with zipfile.ZipFile(io.BytesIO(spliced)) as z:
        assert z.testzip() is None and z.read(SHEET) == data
        info = z.getinfo(SHEET)
        assert info.file_size == len(data)
        local = spliced[info.header_offset:info.header_offset + 30]
        sig, version, flags, method, _, _, crc, csize, usize = struct.unpack(
            "<4sHHHHHIII", local[:26])
        assert (sig, version, flags & 8, method) == (b"PK\x03\x04", 45, 8, 8)
        assert (crc, csize, usize) == (0, 0, 0)
        names = struct.unpack("<H", local[26:28])[0]
        start = info.header_offset + 30 + names
        descriptor = spliced[start + info.compress_size:start + info.compress_size + 24]
        assert descriptor == struct.pack("<4sIQQ", b"PK\x07\x08", zlib.crc32(data),
                                         info.compress_size, len(data))
        # the central directory entry: the size itself, or 0xFFFFFFFF and the extra field
        if extra:
            assert info.extra == struct.pack("<HHQ", 1, 8, len(data))
        else:
            assert info.extra == b""
    assert openpyxl.load_workbook(io.BytesIO(spliced))["Variants"]["A40"].value == 20.0
