"""Filters of a worksheet: which hidden rows a filter hid (not a hand).

The file marks a row hidden by a filter exactly as one hidden by hand (``<row
hidden="1">``). What tells them apart is the filter: a sheet's ``<autoFilter>`` (after
its ``<sheetData>``) or a table's, with at least one ``<filterColumn>`` holding a
criterion. The hidden rows below the header of such a filter's range are the rows the
filter left out: SUBTOTAL 1-11 leaves them out too (Microsoft's SUBTOTAL page: "ignores
any rows that are not included in the result of a filter, no matter which function_num
value you use"), while only 101-111 leave out the rows hidden by hand.
"""

from __future__ import annotations

import re
from xml.etree.ElementTree import Element

from workbook_gen.xlsx.limits import Package

_P = rb"(?:[A-Za-z_][\w.-]*:)?"
_END_DATA = re.compile(rb"</" + _P + rb"sheetData\s*>|<" + _P + rb"sheetData\b[^>]*/>")
_FILTER = re.compile(rb"<(" + _P + rb")autoFilter\b([^>]*?)(/?)>")
_VIEWS = re.compile(rb"<" + _P + rb"customSheetViews\b")  # their views' autoFilters follow
_REF = re.compile(rb"""\sref\s*=\s*["']([^"']*)["']""")
CRITERIA = ("filters", "customFilters", "top10", "dynamicFilter", "colorFilter", "iconFilter")
_CRITERION = re.compile(rb"<" + _P + rb"(?:" + b"|".join(c.encode() for c in CRITERIA)
                        + rb")\b")


def sheet_filter(pkg: Package, part: str) -> str | None:
    """The range of the worksheet's own autoFilter if it filters (a criterion in one of
    its columns), else None. Reads the part again (its bytes not counted twice)."""
    inflated = pkg.inflated
    buf, tail = b"", None
    try:
        for chunk in pkg._chunks(part):
            if tail is None:
                buf = buf[-256:] + chunk
                m = _END_DATA.search(buf)
                if m is not None:
                    tail = buf[m.end():]
            else:
                tail += chunk
    finally:
        pkg.inflated = inflated
    return _active(tail) if tail else None


def _active(tail: bytes) -> str | None:
    """The filtering range of the sheet's own autoFilter in the part's bytes after its
    sheet data (an autoFilter of a custom view, inside <customSheetViews>, is not it)."""
    m = _FILTER.search(tail)
    views = _VIEWS.search(tail)
    if m is None or m.group(3) or (views is not None and views.start() < m.start()):
        return None
    end = tail.find(b"</" + m.group(1) + b"autoFilter", m.end())
    body = tail[m.end():end if end >= 0 else len(tail)]
    ref = _REF.search(m.group(2))
    if ref is None or _CRITERION.search(body) is None:
        return None
    return ref.group(1).decode("utf-8", "replace")


def table_filter(table: Element) -> str | None:
    """The range of a table part's autoFilter if it filters, else None."""
    for el in table:
        if el.tag.rpartition("}")[2] != "autoFilter":
            continue
        for column in el:
            if column.tag.rpartition("}")[2] == "filterColumn" and any(
                    c.tag.rpartition("}")[2] in CRITERIA for c in column):
                return el.get("ref")
    return None
