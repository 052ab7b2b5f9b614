"""The regular-expression scanner of <sheetData> rows in the plain form programs write.

``plain_rows(text)`` takes a batch of whole ``<row>`` elements (decoded, without a
namespace prefix) made only of plain cells as a whole: the rows' attributes and every
cell's groups, each a C loop over the batch. ``rows(text)`` cuts any other batch into
``(row attributes, cells)``, each cell the groups of ``CELL``: no Python code runs per XML
element, and no element object is made. Whatever it does not
recognise to the last character (other elements, a prefix, unusual spellings, entities it
does not know) it hands back as the row's XML text, for ElementTree to parse: the scanner
only ever takes the common path, never guesses.

Text is returned as XML defines it: line ends normalised to ``\\n`` and the five named
and the numeric character references replaced (``xml_text``).
"""

from __future__ import annotations

import re

import numpy as np

_ATTRS = r'((?: [A-Za-z_:][\w:.-]*="[^"<&\t\n\r]*")*)'
# one <c>: whole, column letters, row digits, attributes after r, plain <f> text,
# <f> attributes, their <f> text, <v> text, inline string <is><t> text
CELL = re.compile(
    r'(<c r="([A-Z]{1,3})([1-9][0-9]{0,6})"' + _ATTRS + r'(?:/>|>'
    r'(?:<f>([^<]*)</f>|<f' + _ATTRS + r'(?:/>|>([^<]*)</f>))?'
    r'(?:<v>([^<]*)</v>|<is><t(?: xml:space="preserve")?>([^<]*)</t></is>)?'
    r'</c>))')
# the plain cell most programs write most of the time: a style, a common type, a formula
# with its text (LibreOffice's aca="false" is the default), a non-empty value; groups:
# column letters, row digits, type, <f> text, <v> text
_PLAIN = (r'<c r="([A-Z]{1,3})([1-9][0-9]{0,6})"(?: s="[0-9]{1,9}")?(?: t="(n|s|str|b|e)")?'
          r'(?:/>|>(?:<f(?: aca="false")?>([^<]+)</f>)?(?:<v>([^<]+)</v>)?</c>)')
PLAIN = re.compile(_PLAIN)
_PLAIN_ROW = re.compile("(?:" + re.sub(r"\((?!\?)", "(?:", _PLAIN) + ")*")
_S = r"[ \t\r\n]*"  # XML's white space
ROW_TAG = re.compile(r'<row' + _ATTRS + _S + '>')
_ROW_START = re.compile(_S + ROW_TAG.pattern)
# a batch of rows whose cells are all plain (the rows' attributes hold no "<")
_PLAIN_ROWS = re.compile(f"(?:{_S}<row{re.sub(r'[(](?![?])', '(?:', _ATTRS)}{_S}>"
                         f"{_PLAIN_ROW.pattern}</row>)*{_S}")
ATTR = re.compile(r' ([A-Za-z_:][\w:.-]*)="([^"]*)"')
_ENTITY = re.compile(r"&(#[0-9]+|#x[0-9A-Fa-f]+|[A-Za-z]+);")
_CONTROL = bytes(c for c in range(32) if c not in (9, 10, 13))  # not XML characters
_NAMED = {"amp": "&", "lt": "<", "gt": ">", "quot": '"', "apos": "'"}


class Unrecognised(Exception):
    """Text the scanner does not take: the caller parses it with ElementTree."""


def decoded(data: bytes) -> str:
    """A batch of rows (UTF-8) as text; Unrecognised if it holds characters XML forbids
    (the parser's error to word)."""
    octets = np.frombuffer(data, np.uint8)  # (the usual batch has none of the bytes
    if ((octets < 32) | (octets == 0x5D) | (octets == 0xEF)).any() and (  # searched: numpy)
            len(data.translate(None, _CONTROL)) != len(data) or b"]]>" in data
            or b"\xef\xbf\xbe" in data or b"\xef\xbf\xbf" in data):
        raise Unrecognised
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        raise Unrecognised from None


def plain_rows(text: str) -> tuple[list[str], list[tuple]] | None:
    """``(each row's attributes, every cell's PLAIN groups)`` of a batch of rows that are
    all plain, else None."""
    if _PLAIN_ROWS.fullmatch(text) is None:
        return None
    return ROW_TAG.findall(text), PLAIN.findall(text)


def rows(text: str) -> list[tuple[str | None, list | tuple, str, bool]]:
    """``(attributes, cells, xml without </row>, plain)`` for each row of ``text`` (whole
    rows and nothing else, ``decoded``); ``attributes`` is None for a row the scanner does
    not recognise to the last character. A plain row's cells are all of the ``PLAIN`` kind,
    as its groups; another row's cells are the groups of ``CELL``. Raises Unrecognised if
    ``text`` holds anything else."""
    pieces = text.split("</row>")
    if pieces[-1].strip():
        raise Unrecognised
    out = []
    match, cells_of = _ROW_START.match, CELL.findall
    plain, plain_cells = _PLAIN_ROW.fullmatch, PLAIN.findall
    for piece in pieces[:-1]:
        m = match(piece)
        if m is None:
            raise Unrecognised  # not a <row ...> start tag: a self-closed row, a prefix
        content = piece[m.end():]
        if plain(content):
            out.append((m.group(1), plain_cells(content), piece, True))
            continue
        cells = cells_of(content)
        if "<row" in content or sum(map(len, [c[0] for c in cells])) != len(content):
            out.append((None, (), piece, False))
        else:
            out.append((m.group(1), cells, piece, False))
    return out


def xml_text(s: str) -> str:
    """Character data as an XML parser returns it: line ends as ``\\n``, references
    replaced. Raises Unrecognised for an entity XML does not predefine."""
    if "\r" in s:
        s = s.replace("\r\n", "\n").replace("\r", "\n")
    if "&" in s:
        s = _ENTITY.sub(_reference, s)
    return s


def _reference(m: re.Match) -> str:
    name = m.group(1)
    if name[0] != "#":
        if name not in _NAMED:
            raise Unrecognised
        return _NAMED[name]
    code = int(name[2:], 16) if name[1] == "x" else int(name[1:])
    if not (code in (0x9, 0xA, 0xD) or 0x20 <= code <= 0xD7FF or 0xE000 <= code <= 0xFFFD
            or 0x10000 <= code <= 0x10FFFF):
        raise Unrecognised  # not an XML character: the parser's error, not ours
    return chr(code)


def attributes(attrs: str) -> dict[str, str]:
    """The attributes matched by ``_ATTRS`` as a dict (values hold no ``&`` or ``<``)."""
    return dict(ATTR.findall(attrs))
