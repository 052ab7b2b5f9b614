"""The <row> elements of a worksheet part, in order, for :func:`sheetdata.read_sheet`.

The part's bytes are cut into batches of whole rows (about a megabyte each); a batch in
the plain form spreadsheet programs write is read by the regular-expression scanner of
:mod:`scan`: whole (``PlainRows``) when all its cells are plain, else as rows
``(attributes, cells, xml, plain, context)``; any other by ElementTree (rows as
elements), which words every error; a part this cutting cannot handle is read
element by element.
"""

from __future__ import annotations

import re
from typing import NamedTuple
from xml.etree.ElementTree import Element, ParseError, fromstring

from workbook_gen.xlsx import scan
from workbook_gen.xlsx.limits import Package
from workbook_gen.xlsx.model import Sheet
from workbook_gen.xlsx.scan import Unrecognised

_MAIN_NS = ("http://schemas.openxmlformats.org/spreadsheetml/2006/main",
            "http://purl.oclc.org/ooxml/spreadsheetml/main")  # transitional, strict
_LOCAL = {f"{{{ns}}}{name}": name for ns in _MAIN_NS
          for name in ("row", "c", "v", "f", "is", "t", "r", "si", "dimension")}

_SHEET_DATA = re.compile(rb"<(?:([A-Za-z_][\w.-]*):)?sheetData\b[^>]*?(/?)>")
_DIMENSION = re.compile(rb"<(?:[A-Za-z_][\w.-]*:)?dimension\b[^>]*?\bref=\"([^\"]*)\"")
_ROOT_TAG = re.compile(rb"<(?!\?|!)((?:[A-Za-z_][\w.-]*:)?[A-Za-z_][\w.-]*)\b[^>]*>")
_BATCH = 1 << 20


def _rows(pkg: Package, part: str, sheet: Sheet):
    """The <row> elements of a worksheet part, in order.

    Fast path: the part's bytes are cut after a ``</row>`` about every megabyte and each
    batch of rows is parsed whole (in C) inside a copy of the root's start tag, so that
    no Python code runs per XML element. The prolog is checked first (no DOCTYPE); a part
    that is not plain UTF-8 or that this cutting cannot handle is read element by element.
    """
    chunks = pkg._chunks(part)
    head = b""
    for chunk in chunks:
        head += chunk
        if _SHEET_DATA.search(head) or len(head) > 4 * _BATCH:
            break
    ok = not head.startswith((b"\xff\xfe", b"\xfe\xff")) and head[:2].find(b"\0") < 0
    m = _SHEET_DATA.search(head) if ok else None
    root = _ROOT_TAG.search(head) if m else None
    if m is None or root is None or b"<![CDATA[" in head or not _safe(pkg, part, head):
        yield from _slow_rows(pkg, part, sheet)
        return
    dim = _DIMENSION.search(head, 0, m.start())
    if dim is not None:
        sheet.dimension = dim.group(1).decode("utf-8", "replace")
    if m.group(2):  # <sheetData/>
        return
    prefix = m.group(1) + b":" if m.group(1) else b""
    start_tag = head[root.start():root.end()]
    if start_tag.endswith(b"/>"):
        yield from _slow_rows(pkg, part, sheet)
        return
    close_root = b"</" + root.group(1) + b">"
    context = start_tag, close_root
    end_data = b"</" + prefix + b"sheetData>"
    row_end = b"</" + prefix + b"row>"
    buf = head[m.end():]
    done = False
    clean = 0  # the bytes of buf already searched for end_data (without finding it)
    while True:
        stop = buf.find(end_data, max(0, clean - len(end_data) + 1))
        if stop >= 0:
            batch, buf, done = buf[:stop], b"", True
        else:
            clean = len(buf)
            cut = buf.rfind(row_end) if len(buf) >= _BATCH else -1
            if cut < 0:
                chunk = next(chunks, None)
                if chunk is None:
                    raise pkg.error(part, "broken XML: the sheet data does not end")
                if b"<![CDATA[" in chunk:
                    raise pkg.error(part, "CDATA in sheet data is not read")
                buf += chunk
                continue
            cut += len(row_end)
            batch, buf = buf[:cut], buf[cut:]
            clean -= cut
        scanned = text = None
        if not prefix:
            try:
                text = scan.decoded(batch)
                plain = scan.plain_rows(text)
                scanned = [PlainRows(*plain, text, context)] if plain else scan.rows(text)
            except Unrecognised:
                pass  # ElementTree reads the batch, and words what is wrong
        if scanned is not None:
            yield from (row if type(row) is PlainRows else _scanned(pkg, part, context, row)
                        for row in scanned)
        else:
            try:
                wrapper = fromstring(start_tag + batch + close_root)
            except ParseError as exc:
                raise pkg.error(part, f"broken XML: {exc}") from None
            yield from wrapper
        if done:
            for _ in chunks:  # the rest of the part still counts against the budget
                pass
            return


class PlainRows(NamedTuple):
    """A batch of rows whose cells are all plain (scan.plain_rows), to be taken whole."""

    attributes: list[str]  # each row's
    cells: list[tuple]     # every cell's scan.PLAIN groups
    text: str
    context: tuple[bytes, bytes]


def apart(pkg: Package, part: str, batch: PlainRows) -> list:
    """The rows of a PlainRows batch one by one, as ``_rows`` gives other batches' rows."""
    return [_scanned(pkg, part, batch.context, row) for row in scan.rows(batch.text)]


def _scanned(pkg: Package, part: str, context: tuple[bytes, bytes], row: tuple):
    return _parse_row(pkg, part, context, row[2]) if row[0] is None else (*row, context)


def _safe(pkg: Package, part: str, head: bytes) -> bool:
    from workbook_gen.xlsx.limits import _prolog_is_safe
    return _prolog_is_safe(head, part, pkg, final=True)


def _slow_rows(pkg: Package, part: str, sheet: Sheet):
    for el in pkg.iter_xml(part):
        tag = _LOCAL.get(el.tag)
        if tag == "row":
            yield el
        elif tag == "dimension":
            sheet.dimension = el.get("ref")


def _parse_row(pkg: Package, part: str, context: tuple[bytes, bytes], xml: str) -> Element:
    """One row's XML, parsed by ElementTree inside the part's root start tag."""
    head, close = context
    try:
        return fromstring(head + xml.encode("utf-8") + b"</row>" + close)[0]
    except ParseError as exc:
        raise pkg.error(part, f"broken XML: {exc}") from None
