"""Safe access to the parts of an xlsx package: size limits and hostile XML.

Every part is checked against its declared size and compression ratio *before*
it is inflated (zip bombs), the bytes actually inflated are counted against a
budget for the whole workbook, and XML is parsed incrementally by expat.  A
document type declaration is refused outright: spreadsheets never carry one, and
without it there are no entity declarations, so neither entity expansion
("billion laughs") nor external entities (XXE) can occur.  This is the same
policy as ``defusedxml`` with ``forbid_dtd=True``, kept here because
defusedxml's ElementTree parser is the pure-Python one (several times slower).
"""

from __future__ import annotations

import posixpath
import zipfile
import zlib
from collections.abc import Iterator
from pathlib import Path
from xml.etree.ElementTree import Element, ParseError, XMLPullParser

from workbook_gen.errors import WorkbookReadError

MiB = 1 << 20
MAX_UNCOMPRESSED = 1024 * MiB
"""Default budget of inflated bytes for a whole workbook."""
MAX_CELLS = 1_200_000
"""Default ceiling of cells (<c> elements) read from a workbook, where the audit's time and
memory hold on a 2-core machine (CPU time, ``/usr/bin/time``): the sewing machine at
0.05 deg (403k formula cells) 14.8 s and 349 MB; parallel_4dof_balanced at 0.0352 deg
(1.48 M formula cells, 1.50 M cells) 65.6 s and 1.18 GB, i.e. up to ~44 us and ~0.8 KB a
cell: 1.2 M cells stay under ~55 s and ~1 GB. ``generate`` refuses a sweep whose workbook
would exceed it; formulas that each differ cost more and are bounded by the grouping's
cost model (evaluator/grouping.py)."""
MAX_RATIO = 200.0
"""Default ceiling of uncompressed/compressed size for a part larger than RATIO_FLOOR."""
RATIO_FLOOR = 1 * MiB
MAX_PROLOG = 1 * MiB
_CHUNK = 1 << 16
_OLE_MAGIC = b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1"
_ZIP_ERRORS = (zipfile.BadZipFile, zlib.error, EOFError, OSError, NotImplementedError,
               RuntimeError, ValueError)


class Package:
    """An open xlsx zip whose parts are read under size, ratio and XML limits."""

    def __init__(self, path: str | Path, *, max_uncompressed: int = MAX_UNCOMPRESSED,
                 max_ratio: float = MAX_RATIO) -> None:
        self.path = str(path)
        self.max_uncompressed = max_uncompressed
        self.max_ratio = max_ratio
        self.inflated = 0
        try:
            with open(path, "rb") as fh:
                magic = fh.read(8)
            self._zip = zipfile.ZipFile(path)
        except FileNotFoundError:
            raise WorkbookReadError(f"{self.path}: no such file") from None
        except IsADirectoryError:
            raise WorkbookReadError(f"{self.path}: is a directory, not an xlsx file") from None
        except _ZIP_ERRORS as exc:
            hint = (" (an OLE2 file: encrypted workbook or legacy .xls)"
                    if magic == _OLE_MAGIC else "")
            raise WorkbookReadError(f"{self.path}: not a zip / xlsx package{hint}: "
                                    f"{_one_line(exc)}") from None
        self._names = {info.filename: info for info in self._zip.infolist()}
        self._folded = {name.lower(): name for name in self._names}

    def close(self) -> None:
        self._zip.close()

    def __enter__(self) -> "Package":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def find(self, name: str) -> str | None:
        """The member called ``name`` (leading '/' ignored, case-insensitive fallback)."""
        name = posixpath.normpath(name.lstrip("/"))
        if name in self._names:
            return name
        return self._folded.get(name.lower())

    def declared_size(self, part: str) -> int:
        """Uncompressed size of ``part`` as the zip declares it (never more is inflated)."""
        return self._names[part].file_size

    def declared_total(self) -> int:
        return sum(info.file_size for info in self._names.values())

    def error(self, part: str, what: str) -> WorkbookReadError:
        """A one-line error naming the file and the part."""
        return WorkbookReadError(f"{self.path}: {part}: {_one_line(what)}")

    def _check(self, part: str) -> zipfile.ZipInfo:
        info = self._names[part]
        size, packed = info.file_size, info.compress_size
        if size > self.max_uncompressed - self.inflated:
            raise self.error(part, f"declares {size} bytes uncompressed, over the budget of "
                                   f"{self.max_uncompressed} bytes (max_uncompressed)")
        if size > RATIO_FLOOR and (packed <= 0 or size / packed > self.max_ratio):
            ratio = "infinite" if packed <= 0 else f"{size / packed:.0f}"
            raise self.error(part, f"compression ratio {ratio} exceeds {self.max_ratio:g} "
                                   "(zip bomb?)")
        return info

    def _chunks(self, part: str) -> Iterator[bytes]:
        """Inflated bytes of ``part`` in chunks, counted against the budget."""
        info = self._check(part)
        try:
            with self._zip.open(info) as fh:
                while chunk := fh.read(_CHUNK):
                    self.inflated += len(chunk)
                    if self.inflated > self.max_uncompressed:
                        raise self.error(part, "inflates beyond the max_uncompressed budget")
                    yield chunk
        except WorkbookReadError:
            raise
        except _ZIP_ERRORS as exc:
            raise self.error(part, f"corrupt zip member: {exc}") from None

    def read_bytes(self, part: str) -> bytes:
        return b"".join(self._chunks(part))

    def iter_xml(self, part: str) -> Iterator[Element]:
        """Elements of ``part`` as each one ends (document order of end tags).

        The caller should ``clear()`` elements it has consumed to keep memory bounded.
        The last element yielded is the root.
        """
        parser = XMLPullParser(events=("end",))
        head = b""
        checked = False
        try:
            for chunk in self._chunks(part):
                if not checked:
                    head += chunk
                    checked = _prolog_is_safe(head, part, self)
                    if not checked:
                        continue
                    chunk, head = head, b""
                parser.feed(chunk)
                for _event, element in parser.read_events():
                    yield element
            if not checked:
                _prolog_is_safe(head, part, self, final=True)
                parser.feed(head)
            parser.close()
            for _event, element in parser.read_events():
                yield element
        except ParseError as exc:
            raise self.error(part, f"broken XML: {exc}") from None

    def parse(self, part: str) -> Element:
        """The root element of a small part (whole tree kept)."""
        root = None
        for root in self.iter_xml(part):
            pass
        if root is None:
            raise self.error(part, "empty XML document")
        return root


def _prolog_is_safe(head: bytes, part: str, package: Package, final: bool = False) -> bool:
    """True once the root element starts with no DOCTYPE before it; False if undecided.

    Raises on a document type declaration, or on a prolog too long or unreadable.
    """
    if head.startswith((b"\xff\xfe", b"\xfe\xff")):
        text = head.decode("utf-16", errors="ignore")
    elif head[1:2] == b"\0":  # UTF-16 without a byte order mark, as expat detects it
        text = head.decode("utf-16-le", errors="ignore")
    elif head[:1] == b"\0":
        text = head.decode("utf-16-be", errors="ignore")
    else:
        text = head.removeprefix(b"\xef\xbb\xbf").decode("latin-1")  # markup is ASCII
    i = 0
    while (j := text.find("<", i)) >= 0 and j + 4 <= len(text):
        if text.startswith("<?", j):
            end, skip = text.find("?>", j + 2), 2
        elif text.startswith("<!--", j):
            end, skip = text.find("-->", j + 4), 3
        elif text.startswith("<!", j):
            raise package.error(part, "XML with a DOCTYPE/entity declaration is refused "
                                      "(entity expansion or external entity)")
        else:
            return True
        if end < 0:  # the PI or comment is not closed yet
            break
        i = end + skip
    if final or len(head) > MAX_PROLOG:
        raise package.error(part, "no XML root element found in the first "
                                  f"{min(len(head), MAX_PROLOG)} bytes")
    return False


def _one_line(value: object) -> str:
    return " ".join(str(value).split())
