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
from enum import Enum
from functools import partial

from .rows import Sheet
from .xlsxwriter_internals import (RowsInMemory, ZippedWorkbook, assemble_xml,
                                   replace_assembly, write_xml)

#: zlib level of the package.  XlsxWriter leaves zlib's default (6); level 3 takes a
#: third of the time (0.7 s less for the 26 MB of XML of a 0.1-degree workbook) for a
#: file about 15 % larger.  Deterministic like any level: same scene, same bytes.
COMPRESSLEVEL = 3

#: Table + Checks cells up to which a workbook is packaged in memory (a 0.1-degree
#: sewing-machine workbook has about 200,000, some 25 MB of XML).
IN_MEMORY_CELLS = 600_000


class Stream(io.BytesIO):
    """The bytes of a Book's package."""


class Book(ZippedWorkbook):
    """A constant-memory workbook, its package built in memory when ``in_memory``, zipped
    at ``COMPRESSLEVEL`` (``FastZipFile``: only our workbooks, not XlsxWriter's others)."""

    compresslevel = COMPRESSLEVEL

    def __init__(self, stream: Stream, in_memory: bool):
        super().__init__(stream, {"constant_memory": True})
        # Set after __init__, which would turn constant_memory off: the sheets still
        # write their rows as they go (MemorySheet keeps them in memory).
        self.in_memory = in_memory

    def sheet(self, name: str) -> Sheet:
        return self.add_worksheet(name, worksheet_class=MemorySheet if self.in_memory
                                  else Sheet)

    def drawings_prepared(self) -> None:
        for drawing in self.drawings:
            key = _drawing_key(drawing)
            if key is not None:
                replace_assembly(drawing, partial(_assemble_kept, drawing, key))


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
    """The drawing's XML, from the XML kept for ``key``."""
    found = _DRAWING_XML.get(key)
    if found is None:
        found = assemble_xml(drawing)
        if len(_DRAWING_XML) >= _DRAWING_XML_LIMIT:
            _DRAWING_XML.clear()
        _DRAWING_XML[key] = found
    write_xml(drawing, found)


class MemorySheet(RowsInMemory, Sheet):
    """A Sheet whose constant_memory row data is a string buffer, not a temporary file."""
