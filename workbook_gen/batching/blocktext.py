"""The summary's rows as text, a block of rows at a time: the lines of summary.csv and
the row XML of summary.xlsx's Variants sheet.

One code path for both places that format them: the ``--summary-only`` workers (each
formats the block it evaluated, in parallel) and the command (the file batch's
summary, and any block a worker formatted with a column kind the whole table does
not have).  The bytes are those the cell-by-cell writers gave:

- a number as Python's shortest round-trip text (``repr``), nothing for NaN or None,
  in both files (``<c r="F2"><v>-125.0</v></c>``); a float in a ``mixed`` column (a
  figure that is a number for some variants and a text for others) as ``%.16G`` in
  the sheet;
- a text as itself in the CSV (quoted as ``csv.writer`` quotes) and as an inline
  string in the sheet (``xml:space="preserve"`` when it has outer spaces; control
  characters escaped as ECMA-376's ``ST_Xstring`` says: ``xstring``); the file
  column a ``HYPERLINK`` formula with the name as cached text; the ``variant`` column a
  number in the sheet where the label is a variant number (not a design's name).

Columns are formatted whole, not cell by cell: a column's distinct numbers are
formatted once (``repr`` of a list, in C) and spread by numpy, and a block's rows are
assembled by interleaving whole columns into one list and joining it once.
"""

from __future__ import annotations

import csv
import io
import math
import re
from typing import Mapping, Sequence

import numpy as np
import orjson

from ..cellref import column_letters

TEXT_COLUMNS = ("variant", "file", "status", "audit")
_CSV_SPECIAL = re.compile(r'[,"\r\n]')
_EXACT_FLOATS = {float, type(None)}
_PROBE = 64   # rows that tell a column of few distinct numbers from one of many
_VARIANT_NUMBER = re.compile("[1-9][0-9]{0,14}")  # exactly a double, no leading zero
# ST_Xstring (ECMA-376 Part 1, 22.9.2.19): what ``xstring`` escapes
_ESCAPE_LIKE = re.compile("(_x[0-9a-fA-F]{4}_)")
_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\ufffe\uffff]")
_XSTRING_SPECIAL = re.compile("_x[0-9a-fA-F]{4}_|[\x00-\x08\x0b-\x1f\ufffe\uffff]")


def value_kind(values: Sequence[object]) -> str:
    """A figure column's kind from its values: ``number`` (floats, ints, None),
    ``text`` (texts, None) or ``mixed``."""
    types = set(map(type, values))
    types.discard(type(None))
    if all(issubclass(t, (int, float)) for t in types):
        return "number"
    return "text" if types <= {str} else "mixed"


def has_value(values: Sequence[object]) -> bool:
    """Whether any cell of the column shows something (not None, NaN or empty text)."""
    return any(not (v is None or v == "" or (isinstance(v, float) and v != v))
               for v in values)


def number_texts(values: Sequence[object]) -> list[str]:
    """``repr`` of each number ('' for None and NaN), formatted in C: ``repr`` of a list
    formats its floats as ``repr`` of each does."""
    if not len(values):
        return []
    if isinstance(values, np.ndarray) or set(map(type, values)) <= _EXACT_FLOATS:
        return _float_texts(np.asarray(values, dtype=np.float64))
    text = repr(list(values))[1:-1]
    texts = text.split(", ")
    if "nan" not in text and "None" not in text:  # every row a number: nothing to blank
        return texts
    return ["" if t in ("nan", "None") else t for t in texts]


def _float_texts(values: np.ndarray) -> list[str]:
    """``repr`` of each float ('' for NaN).  A column with few distinct values (``_at``
    columns hold a few sweep inputs, the varied parameters a few levels) has each
    distinct value (bit for bit: -0.0 is not 0.0) formatted once, then spread; any
    other is formatted whole (finding its distinct values would cost half as much
    as formatting them)."""
    bits = np.ascontiguousarray(values).view(np.int64)
    if len(bits) > _PROBE and len(np.unique(bits[:_PROBE])) > _PROBE // 2:
        return _repr_texts(values.tolist())
    bits, where = np.unique(bits, return_inverse=True)
    texts = _repr_texts(bits.view(np.float64).tolist())
    return np.array(texts, dtype=object)[where.reshape(-1)].tolist()


def _repr_texts(floats: list[float]) -> list[str]:
    """``repr`` of each float ('' for NaN).  orjson writes a float's shortest round-trip
    digits (Ryu) about eight times faster than ``repr``, and as ``repr`` spells them
    where ``repr`` writes no exponent (1e-4 <= |x| < 1e16); outside a narrower band
    (1e-3 <= |x| < 1e15, and zero), and for NaN and the infinities, ``repr`` itself
    (tests/batching/test_blocktext.py compares the two on millions of floats)."""
    if not floats:
        return []
    texts = orjson.dumps(floats).decode()[1:-1].split(",")
    size = np.abs(np.array(floats))
    for i in np.flatnonzero(~(((size >= 1e-3) & (size < 1e15)) | (size == 0.0))).tolist():
        x = floats[i]
        texts[i] = "" if x != x else repr(x)
    return texts


def cell_text(value: object) -> str:
    """A CSV cell: floats as Python's shortest round-trip text, no number as empty."""
    if value is None:
        return ""
    if isinstance(value, float):
        return "" if math.isnan(value) else repr(value)
    return str(value)


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def xstring(text: str) -> str:
    """A cell's text as ECMA-376 ``ST_Xstring`` holds it (Part 1, 22.9.2.19), as
    XlsxWriter escapes it: a control character XML 1.0 forbids (and carriage return,
    which XML readers turn into a line feed) as ``_xHHHH_``, a literal ``_xHHHH_``
    with its underscore escaped (``_x005F_xHHHH_``), U+FFFE and U+FFFF as
    ``_xFFFE_``/``_xFFFF_``.  Any other text is returned as it is."""
    if not _XSTRING_SPECIAL.search(text):
        return text
    text = _ESCAPE_LIKE.sub(r"_x005F\1", text)
    return _CONTROL.sub(lambda m: f"_x{ord(m.group(0)):04X}_", text)


def text_cell(ref: str, text: str) -> str:
    text = xstring(text)
    space = ' xml:space="preserve"' if text != text.strip() else ""
    return f'<c r="{ref}" t="inlineStr"><is><t{space}>{_escape(text)}</t></is></c>'


def _cell(name: str, ref: str, value: object) -> str:
    """One cell of a ``file`` or ``mixed`` column, as XlsxWriter writes it."""
    if value is None or value == "" or (isinstance(value, float) and value != value):
        return ""
    if name == "file":
        target = _escape(str(value).replace('"', '""'))
        return (f'<c r="{ref}" t="str"><f>HYPERLINK("{target}","{target}")</f>'
                f"<v>{_escape(xstring(str(value)))}</v></c>")
    if isinstance(value, str):
        return text_cell(ref, value)
    if isinstance(value, bool) or not math.isfinite(value):
        return text_cell(ref, str(value))
    return f'<c r="{ref}"><v>{value:.16G}</v></c>'


def _xml_items(name: str, col: int, kind: str, values: Sequence[object],
               texts: list[str] | None, rows: list[str]) -> list:
    """A column's share of each row's XML: constants (str) and per-row lists."""
    letter = column_letters(col + 1)
    if name == "variant":
        return _variant_items(letter, values, rows)
    if kind == "number":
        if all(texts):
            return [f'<c r="{letter}', rows, '"><v>', texts, "</v></c>"]
        if not any(texts):
            return []
        return [[f'<c r="{letter}{r}"><v>{t}</v></c>' if t else ""
                 for r, t in zip(rows, texts)]]
    if kind == "text" and name != "file":  # each distinct text's XML made once
        bodies: dict[str, str] = {}
        for value in set(values):
            if value:
                bodies[value] = text_cell("", value)[len('<c r="'):]
        if all(values):
            return [f'<c r="{letter}', rows, [bodies[v] for v in values]]
        if not bodies:
            return []
        return [[f'<c r="{letter}{r}{bodies[v]}' if v else "" for r, v in zip(rows, values)]]
    cells = [_cell(name, f"{letter}{r}", v) for r, v in zip(rows, values)]
    return [cells] if any(cells) else []


def _variant_items(letter: str, labels: Sequence[str], rows: list[str]) -> list:
    """The ``variant`` column: a number where the label is one (the variants' numbers
    of a grid, random samples or an unnamed design row: the autofilter then sorts 1, 2,
    ..., 10), a text where the design names the row (``007`` stays a text)."""
    numeric = [bool(_VARIANT_NUMBER.fullmatch(v)) for v in labels]
    if all(numeric):
        return [f'<c r="{letter}', rows, '"><v>', list(labels), "</v></c>"]
    return [[f'<c r="{letter}{r}"><v>{v}</v></c>' if n else text_cell(f"{letter}{r}", v)
             if v else "" for r, v, n in zip(rows, labels, numeric)]]


def _join(items: list, count: int) -> str:
    """``count`` rows whose pieces are ``items`` (a constant, or one text per row)."""
    merged: list = []
    for item in items:
        if isinstance(item, str) and merged and isinstance(merged[-1], str):
            merged[-1] += item
        else:
            merged.append(item)
    width = len(merged)
    flat: list = [None] * (width * count)
    for k, item in enumerate(merged):
        flat[k::width] = [item] * count if isinstance(item, str) else item
    return "".join(flat)


def block_texts(columns: Sequence[str], kinds: Mapping[str, str],
                data: Mapping[str, Sequence[object]], first_row: int, count: int
                ) -> tuple[str, str]:
    """(summary.csv lines, Variants sheet row XML) of ``count`` rows, the first on
    sheet row ``first_row`` (1-based; the header is row 1); ``data``: each column's
    values for those rows, ``kinds`` each column's kind in the whole table."""
    if not count:
        return "", ""
    rows = list(map(str, range(first_row, first_row + count)))
    csv_cols: list[list[str]] = []
    special = False
    xml: list = ['<row r="', rows, '">']
    for col, name in enumerate(columns):
        values, kind = data[name], kinds[name]
        if kind == "number":
            texts = number_texts(values)
        else:
            texts = [cell_text(v) for v in values]
            special = special or bool(_CSV_SPECIAL.search("\x00".join(texts)))
        csv_cols.append(texts)
        xml += _xml_items(name, col, kind, values, texts if kind == "number" else None, rows)
    xml.append("</row>")
    if special:  # a text with a comma, quote or line break: csv.writer quotes it
        out = io.StringIO()
        csv.writer(out, lineterminator="\n").writerows(zip(*csv_cols))
        csv_text = out.getvalue()
    else:  # csv.writer (QUOTE_MINIMAL) writes such fields as they are
        items: list = []
        for texts in csv_cols:
            items += [texts[0] if texts.count(texts[0]) == count else texts, ","]
        items[-1] = "\n"
        csv_text = _join(items, count)
    return csv_text, _join(xml, count)
