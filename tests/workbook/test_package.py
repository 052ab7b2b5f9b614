"""workbook/package.py: a Book's package, in memory or through XlsxWriter's temporary
files, holds part for part the XML that plain XlsxWriter (constant_memory) writes for
the same content; each part is deflated at COMPRESSLEVEL (zlib at that level over the
part's XML gives exactly the stored bytes); openpyxl reads the cells back; the drawing
part kept per process is the one XlsxWriter assembles."""

from __future__ import annotations

import datetime
import io
import zipfile
import zlib

import openpyxl
import pytest
import xlsxwriter

from workbook_gen.workbook import package
from workbook_gen.workbook.package import (COMPRESSLEVEL, Book, MemorySheet, Stream,
                                           _drawing_key, _plain)

CREATED = datetime.datetime(2024, 1, 1)


def _fill(book, sheet) -> None:
    """Numbers, texts, formulas and a chart on two sheets, rows top to bottom."""
    book.set_properties({"title": "package test", "created": CREATED})
    sheet.write_string(0, 0, "x")
    sheet.write_string(0, 1, "x squared")
    for r in range(1, 40):
        sheet.write_number(r, 0, r * 0.25)
        sheet.write_formula(r, 1, f"=A{r + 1}^2", None, (r * 0.25) ** 2)
    chart = book.add_chart({"type": "scatter", "subtype": "straight"})
    chart.add_series({"categories": "=Data!$A$2:$A$40", "values": "=Data!$B$2:$B$40",
                      "name": "x^2"})
    return chart


def _ours(in_memory: bool, anchor: str = "B2") -> bytes:
    stream = Stream()
    book = Book(stream, in_memory=in_memory)
    sheet = book.sheet("Data")
    chart = _fill(book, sheet)
    book.sheet("Plot").insert_chart(anchor, chart)
    book.close()
    return stream.getvalue()


def _xlsxwriter(anchor: str = "B2") -> bytes:
    stream = io.BytesIO()
    book = xlsxwriter.Workbook(stream, {"constant_memory": True, "in_memory": False})
    sheet = book.add_worksheet("Data")
    chart = _fill(book, sheet)
    book.add_worksheet("Plot").insert_chart(anchor, chart)
    book.close()
    return stream.getvalue()


def _parts(data: bytes) -> dict[str, bytes]:
    with zipfile.ZipFile(io.BytesIO(data)) as z:
        return {name: z.read(name) for name in z.namelist()}


@pytest.fixture(scope="module")
def packages():
    return {"memory": _ours(True), "files": _ours(False), "xlsxwriter": _xlsxwriter()}


def test_every_part_is_xlsxwriters(packages):
    reference = _parts(packages["xlsxwriter"])
    assert "xl/drawings/drawing1.xml" in reference and "xl/charts/chart1.xml" in reference
    for kind in ("memory", "files"):
        assert _parts(packages[kind]) == reference, kind


def test_each_way_is_deterministic_with_xlsxwriters_timestamps(packages):
    """XlsxWriter (workbook.py, _store_workbook) dates in-memory parts 1/1/1980 and
    temporary files 31/1/1980; otherwise the ways are the same."""
    assert _ours(True) == packages["memory"]   # the drawing now kept: the same bytes
    assert _ours(False) == packages["files"]
    for kind, day in (("memory", 1), ("files", 31)):
        with zipfile.ZipFile(io.BytesIO(packages[kind])) as z:
            assert {i.date_time for i in z.infolist()} == {(1980, 1, day, 0, 0, 0)}


def test_parts_are_deflated_at_compresslevel(packages):
    assert COMPRESSLEVEL == 3
    data = packages["memory"]
    with zipfile.ZipFile(io.BytesIO(data)) as z:
        infos = z.infolist()
        for info in infos:
            assert info.compress_type == zipfile.ZIP_DEFLATED
            raw = z.read(info.filename)
            # the stored bytes: after the local header (30 bytes + name + extra)
            start = info.header_offset
            name_len = int.from_bytes(data[start + 26:start + 28], "little")
            extra_len = int.from_bytes(data[start + 28:start + 30], "little")
            body = data[start + 30 + name_len + extra_len:][:info.compress_size]
            packer = zlib.compressobj(COMPRESSLEVEL, zlib.DEFLATED, -15)
            assert body == packer.compress(raw) + packer.flush(), info.filename


def test_openpyxl_reads_the_cells_back(packages):
    for kind in ("memory", "files"):
        wb = openpyxl.load_workbook(io.BytesIO(packages[kind]))
        ws = wb["Data"]
        assert ws["A1"].value == "x" and ws["A11"].value == 2.5
        assert ws["B11"].value == "=A11^2"
        cached = openpyxl.load_workbook(io.BytesIO(packages[kind]), data_only=True)["Data"]
        assert cached["B11"].value == 6.25
        assert wb.properties.title == "package test"


def test_memory_sheets_only_in_memory():
    book = Book(Stream(), in_memory=True)
    assert isinstance(book.sheet("A"), MemorySheet)
    other = Book(Stream(), in_memory=False)
    assert not isinstance(other.sheet("A"), MemorySheet)
    book.close()
    other.close()


def test_plain_values_and_the_drawing_key():
    assert _plain(None) and _plain(3) and _plain("a") and _plain([1, (2.0, "x")])
    assert not _plain(object()) and not _plain([1, object()])

    class Drawing:   # a drawing part holding one anchor that is not plain
        embedded, orientation = 1, 0
        drawings = [type("Info", (), {})()]
    Drawing.drawings[0].anchor = object()
    assert _drawing_key(Drawing()) is None
    Drawing.drawings[0].anchor = [1, 2, 3, 4]
    assert "[1, 2, 3, 4]" in _drawing_key(Drawing())


def test_the_drawing_cache_is_bounded(monkeypatch):
    monkeypatch.setattr(package, "_DRAWING_XML", {str(i): "" for i in range(256)})
    first = _ours(True)
    assert len(package._DRAWING_XML) == 1          # cleared, then this drawing kept
    assert _parts(first) == _parts(_xlsxwriter())


def test_a_kept_drawing_is_not_reused_for_another_anchor(packages):
    _ours(True)                                   # B2's drawing kept
    moved = _parts(_ours(True, "F12"))
    assert moved == _parts(_xlsxwriter("F12"))
    assert moved["xl/drawings/drawing1.xml"] != _parts(packages["memory"])[
        "xl/drawings/drawing1.xml"]
