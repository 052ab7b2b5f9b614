"""When a workbook was last saved: ``dcterms:modified`` of its core properties
(docProps/core.xml), the bound of what TODAY() and NOW() can have cached."""

from __future__ import annotations

import datetime as dt
import posixpath
import re
import zipfile
from pathlib import Path
from xml.etree import ElementTree

MAX_PART = 1 << 20  # a property part is a few hundred bytes; a larger one is not read
_CORE = "http://schemas.openxmlformats.org/package/2006/relationships/metadata/core-properties"
_MODIFIED = "{http://purl.org/dc/terms/}modified"
_W3CDTF = re.compile(r"(\d{4})-(\d\d)-(\d\d)(?:T(\d\d):(\d\d)(?::(\d\d)(?:\.\d+)?)?"
                     r"(Z|[+-]\d\d:\d\d)?)?$")


def _read(z: zipfile.ZipFile, name: str) -> bytes | None:
    try:
        info = z.getinfo(name)
    except KeyError:
        return None
    return None if info.file_size > MAX_PART else z.read(info)


def _core_part(z: zipfile.ZipFile) -> str:
    rels = _read(z, "_rels/.rels")
    if rels:
        try:
            for rel in ElementTree.fromstring(rels):
                if rel.get("Type") == _CORE and rel.get("TargetMode") != "External":
                    return posixpath.normpath(rel.get("Target", "").lstrip("/"))
        except ElementTree.ParseError:
            pass
    return "docProps/core.xml"


def parse_w3cdtf(text: str) -> dt.datetime | None:
    """A W3C date-time (``2022-01-19T18:06:06Z``) as a naive UTC datetime, or None."""
    m = _W3CDTF.match(text.strip())
    if not m:
        return None
    y, mo, d, h, mi, s, zone = m.groups()
    try:
        when = dt.datetime(int(y), int(mo), int(d), int(h or 0), int(mi or 0), int(s or 0))
    except ValueError:
        return None
    if zone and zone != "Z":
        sign = 1 if zone[0] == "+" else -1
        when -= sign * dt.timedelta(hours=int(zone[1:3]), minutes=int(zone[4:6]))
    return when


def last_saved(path: str | Path) -> dt.datetime | None:
    """``dcterms:modified`` in UTC, or None when the file does not say (or says it badly)."""
    try:
        with zipfile.ZipFile(path) as z:
            data = _read(z, _core_part(z))
    except (OSError, zipfile.BadZipFile):
        return None
    if not data or b"<!DOCTYPE" in data or b"<!ENTITY" in data:
        return None
    try:
        el = ElementTree.fromstring(data).find(_MODIFIED)
    except ElementTree.ParseError:
        return None
    return parse_w3cdtf(el.text or "") if el is not None else None
