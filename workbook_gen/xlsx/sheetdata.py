"""The <sheetData> of a worksheet part: its rows and cells, cached values and formula text.

``read_sheet`` fills a Sheet from its part's rows (:mod:`sheetrows`): a row the
regular-expression scanner of :mod:`scan` read (``_scanned_row``), else an ElementTree
element; the cell limit, Excel's row and column bounds and the shared and array formula
bookkeeping are the same either way.
"""

from __future__ import annotations

import logging
import re
from operator import itemgetter
from xml.etree.ElementTree import Element

from workbook_gen.xlerror import ExcelError
from workbook_gen.xlsx.limits import Package
from workbook_gen.xlsx.model import (MAX_COL, Cell, SharedFormula, Sheet, Value,
                                     column_letters)
from workbook_gen.xlsx.scan import Unrecognised, attributes, xml_text
from workbook_gen.xlsx.sheetrows import _LOCAL, PlainRows, _parse_row, _rows, apart

log = logging.getLogger(__name__)

MAX_ROW = 1_048_576
_REF = re.compile(r"([A-Za-z]{1,3})([0-9]{1,7})")
_ESCAPE = re.compile(r"_x([0-9A-Fa-f]{4})_")
_UPPER = "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
_COLS: dict[str, int] = {}

def _text_of(el: Element) -> str:
    """Text of an <si> or <is>: its <t>, or its rich-text runs' <t>; phonetic runs skipped."""
    parts = []
    for child in el:
        tag = _LOCAL.get(child.tag)
        if tag == "t":
            parts.append(child.text or "")
        elif tag == "r":
            parts.extend(t.text or "" for t in child if _LOCAL.get(t.tag) == "t")
    return unescape("".join(parts))


def unescape(text: str | None) -> str | None:
    """ECMA-376 ST_Xstring: ``_xHHHH_`` is the character U+HHHH (a control character such
    as CHAR(7) is stored as ``_x0007_``)."""
    if text is None or "_x" not in text:
        return text
    return _ESCAPE.sub(lambda m: chr(int(m.group(1), 16)), text)



def read_sheet(pkg: Package, part: str, sheet: Sheet, strings: list[str], budget: int,
                max_cells: int) -> int:
    """Fill ``sheet.cells`` from ``part``; returns the number of <c> elements read."""
    local, shared, cols = _LOCAL, sheet.shared_formulas, _COLS
    where = f"{part} ({sheet.name})"
    count = row_no = n_rows = 0
    pending: list[Cell] = []
    arrays: list[Cell] = []
    rows, again = _rows(pkg, part, sheet), []
    while (row := again.pop() if again else next(rows, None)) is not None:
        if type(row) is PlainRows:  # a batch of plain rows, taken whole
            try:
                row_no, count, n_rows = _plain_rows(row, row_no, count, n_rows, budget, sheet,
                                                    strings)
            except Unrecognised:  # something in it to word, or unusual: row by row
                again = apart(pkg, part, row)[::-1]
            continue
        if type(row) is tuple:  # scanned: (attributes, cells, the row's XML)
            marks = len(pending), len(arrays), set(shared)
            try:
                row_no, count = _scanned_row(row, row_no, count, budget, sheet, strings,
                                             pending, arrays)
                n_rows += 1
                if n_rows > MAX_ROW:
                    raise pkg.error(where, f"row {row_no} beyond Excel's {MAX_ROW} rows")
                continue
            except Unrecognised:  # ElementTree reads it, and says what is wrong
                del pending[marks[0]:], arrays[marks[1]:]
                for index in set(shared) - marks[2]:
                    del shared[index]
                row = _parse_row(pkg, part, row[4], row[2])
        n_rows += 1
        cells = sheet.cells  # (the plain cells before this row become Cell objects first)
        r = row.get("r")
        row_no = int(r) if r and r.isdigit() else row_no + 1
        if row_no > MAX_ROW or n_rows > MAX_ROW:
            raise pkg.error(where, f"row {row_no} beyond Excel's {MAX_ROW} rows")
        if _hidden(row):  # hidden by hand or by a filter
            sheet.hidden_rows.add(row_no)
        col, row_digits = 0, str(row_no)
        for c in row:
            if local.get(c.tag) != "c":
                continue
            count += 1
            if count > budget:
                raise pkg.error(where, f"more than {max_cells} cells: read it with "
                                       "--max-cells N (audit(path, max_cells=N)), at "
                                       "about 1 KB of memory a cell")
            ref = c.get("r")
            if ref is not None and ref.endswith(row_digits) and (
                    col := cols.get(ref[:-len(row_digits)], 0)):
                r_ = row_no  # the usual spelling, in this row: what the branches below find
            elif ref is None:
                col, r_ = col + 1, row_no
                ref = f"{column_letters(col)}{r_}"
            else:
                digits = ref.lstrip(_UPPER)
                col = cols.get(ref[:len(ref) - len(digits)], 0)
                if col and digits.isdigit() and digits[0] != "0":
                    r_ = int(digits)
                else:  # unusual spelling: lower case, $, leading zeros, or a new column
                    r_, col = _split_ref(ref, pkg, where)
                    ref = f"{column_letters(col)}{r_}"
            if col > MAX_COL or not 0 < r_ <= MAX_ROW:
                raise pkg.error(where, f"cell {ref} outside Excel's {MAX_ROW} rows x "
                                       f"{MAX_COL} columns")
            v = f = inline = None
            for child in c:
                t = local.get(child.tag)
                if t == "v":
                    v = child.text or ""
                elif t == "f":
                    f = child
                elif t == "is":
                    inline = child
            kind = c.get("t", "n")
            try:
                if kind == "n":
                    value = float(v) if v else None
                else:
                    value = _value(kind, v, inline, strings)
            except (ValueError, IndexError):
                raise pkg.error(where, f"cell {ref}: bad cached value {v!r} "
                                       f"of type {kind!r}") from None
            if value is None and f is None:
                continue
            cell = Cell(ref, r_, col, value)
            if f is not None:
                if f.attrib:
                    _formula(cell, f, shared, pending, arrays)
                else:  # a plain <f>: what _formula records for it
                    text = f.text or None
                    if text is not None and text.startswith("="):
                        text = text[1:]
                    cell.formula, cell.formula_type = text, "normal"
            cells[ref] = cell
        row.clear()
    for cell in pending:
        if cell.shared_index not in shared:
            raise pkg.error(where, f"cell {cell.ref}: shared formula si={cell.shared_index} "
                                   "has no master")
        cell.shared_master = shared[cell.shared_index].master
    if arrays:
        _mark_arrays(sheet, arrays)
    return count


def _scanned_row(row: tuple, row_no: int, count: int, budget: int, sheet: Sheet,
                 strings: list[str], pending: list[Cell], arrays: list[Cell]) -> tuple[int, int]:
    """Add the cells of one row the scanner recognised; ``(row number, cells read)``.
    Anything unusual (an error the ElementTree path words, an entity) raises Unrecognised
    before the row's cells are added, so that the row is read again by that path."""
    if row[3]:
        return _plain_row(row, row_no, count, budget, sheet, strings)
    found = row[1]
    a, _, row_no = _row_start(row, row_no, count, budget)
    count += len(found)
    cols, shared, out = _COLS, sheet.shared_formulas, []
    try:
        for whole, letters, digits, cattrs, fplain, fattrs, ftext, v, istr in found:
            col = cols.get(letters) or _column(letters)
            if (r_ := int(digits)) > MAX_ROW:
                raise Unrecognised
            if not cattrs or (i := cattrs.find(' t="')) < 0:
                value = float(v) if v else None
            else:
                kind = cattrs[i + 4:cattrs.index('"', i + 4)]
                if kind == "n":
                    value = float(v) if v else None
                elif kind == "s":
                    value = strings[int(v)] if v else None
                    if v and int(v) < 0:
                        raise Unrecognised
                elif kind == "inlineStr" and "<is>" in whole:
                    value = unescape(xml_text(istr))
                else:
                    if not v and "<v>" not in whole:
                        v = None
                    value = _value(kind, xml_text(v) if v else v, None, strings)
            if fplain:
                if "&" in fplain or "\r" in fplain:
                    fplain = xml_text(fplain)
                cell = Cell(letters + digits, r_, col, value,
                            fplain[1:] if fplain[0] == "=" else fplain, "normal")
            elif fattrs:
                cell = Cell(letters + digits, r_, col, value)
                _formula_of(cell, attributes(fattrs), xml_text(ftext) or None, shared,
                            pending, arrays)
            elif "<f" in whole:  # <f></f> or <f/>: a formula cell without text
                cell = Cell(letters + digits, r_, col, value, None, "normal")
            elif value is None:
                continue
            else:
                cell = Cell(letters + digits, r_, col, value)
            out.append(cell)
    except (ValueError, IndexError):
        raise Unrecognised from None
    if _hidden(a):
        sheet.hidden_rows.add(row_no)
    cells = sheet.cells
    for cell in out:
        cells[cell.ref] = cell
    return row_no, count


def _row_start(row: tuple, row_no: int, count: int, budget: int) -> tuple[dict, str, int]:
    """(attributes, its r, row number) of a scanned row; Unrecognised beyond Excel's rows or
    the cell budget (the ElementTree path words those errors)."""
    if count + len(row[1]) > budget:
        raise Unrecognised
    return _row_number(row[0], row_no)


def _row_number(attrs: str, row_no: int) -> tuple[dict, str, int]:
    """(attributes, its r, row number) of a row's start tag after row ``row_no``;
    Unrecognised beyond Excel's rows."""
    a = attributes(attrs) if attrs else {}
    r = a.get("r")
    row_no = int(r) if r and r.isdigit() else row_no + 1
    if row_no > MAX_ROW:
        raise Unrecognised
    return a, r, row_no


def _hidden(row) -> bool:
    """Is a row hidden (its element, or its attributes as a dict)?"""
    return row.get("hidden") in ("1", "true")


def _cell_rows(digits) -> list[int]:
    """The rows of scanned cells' refs; Unrecognised beyond Excel's rows."""
    rows = list(map(int, digits))
    if max(rows) > MAX_ROW:
        raise Unrecognised
    return rows


def _plain_rows(batch: PlainRows, row_no: int, count: int, n_rows: int, budget: int,
                sheet: Sheet, strings: list[str]) -> tuple[int, int, int]:
    """Add a batch of plain rows (scan.plain_rows) as columns, a few list operations per
    batch; ``(row number, cells read, rows read)``. Unrecognised (before anything is added)
    for what the row-by-row path words or reads otherwise: the cell budget, Excel's rows."""
    found = batch.cells
    if count + len(found) > budget or n_rows + len(batch.attributes) > MAX_ROW:
        raise Unrecognised
    hidden = []
    for attrs in batch.attributes:
        a, _, row_no = _row_number(attrs, row_no)
        if _hidden(a):
            hidden.append(row_no)
    if found:  # (zip(*found) takes twice as long on a batch's tens of thousands of cells)
        letters, digits, kinds, texts, vs = (list(map(g, found)) for g in _GROUPS)
        _plain_cells(sheet, strings, letters, _cell_rows(digits), kinds, texts, vs)
    sheet.hidden_rows.update(hidden)
    return row_no, count + len(found), n_rows + len(batch.attributes)


_GROUPS = [itemgetter(k) for k in range(5)]  # of a scan.PLAIN match


def _plain_row(row: tuple, row_no: int, count: int, budget: int, sheet: Sheet,
               strings: list[str]) -> tuple[int, int]:
    """_scanned_row for a row of plain cells (scan.PLAIN): appended to the sheet's open
    chunk as columns, a few list operations per row rather than Python code per cell."""
    found = row[1]
    a, r, row_no = _row_start(row, row_no, count, budget)
    if found:
        letters, digits, kinds, texts, vs = zip(*found)
        if r and digits.count(r) == len(digits):  # every cell in the row's own row
            rows = [row_no] * len(digits)
        else:
            rows = _cell_rows(digits)
        _plain_cells(sheet, strings, letters, rows, kinds, texts, vs)
    if _hidden(a):
        sheet.hidden_rows.add(row_no)
    return row_no, count + len(found)


def _plain_cells(sheet: Sheet, strings: list[str], letters, rows: list[int], kinds, texts,
                 vs) -> None:
    """Append plain cells (the columns of their scan.PLAIN groups, their rows) to the
    sheet's open chunk; Unrecognised, before anything is added, for a value to word."""
    cols = list(map(_COLS.get, letters))
    if None in cols:
        cols = [c or _column(x) for c, x in zip(cols, letters)]
    try:
        typed = [i for i, k in enumerate(kinds) if k and k != "n"] if any(kinds) else ()
        typed_vs: list[str] = []
        if typed:  # numbers at C speed, then the few typed cells one by one
            vs, typed_vs = list(vs), [vs[i] for i in typed]
            for i in typed:
                vs[i] = "0"
        values = [float(v) if v else None for v in vs] if "" in vs else list(map(float, vs))
        for i, v in zip(typed, typed_vs):
            values[i] = _value(kinds[i], xml_text(v) if v else None, None, strings)
    except (ValueError, IndexError):
        raise Unrecognised from None
    joined = "\0".join(texts)  # (XML text never holds a NUL)
    if "&" in joined or "\r" in joined:
        joined = xml_text(joined)
        texts = joined.split("\0")
    if joined[:1] == "=" or "\0=" in joined:
        texts = [f[1:] if f[:1] == "=" else f for f in texts]
    formulas = [f or None for f in texts] if "" in texts else list(texts)
    if None in values:  # a cell with neither a value nor a formula is not kept
        keep = [v is not None or f is not None for v, f in zip(values, formulas)]
        if not all(keep):
            rows, cols, values, formulas = ([x for x, k in zip(column, keep) if k]
                                            for column in (rows, cols, values, formulas))
    chunk = sheet.chunk()
    for column, new in zip(chunk, (rows, cols, values, formulas)):
        column.extend(new)


def _column(letters: str) -> int:
    col = 0
    for ch in letters:
        col = col * 26 + ord(ch) - 64
    if col > MAX_COL:
        raise Unrecognised
    _COLS[letters] = col
    return col


def _value(kind: str, v: str | None, inline: Element | None, strings: list[str]) -> Value:
    if kind == "n":
        return float(v) if v else None
    if kind == "s":
        if not v:
            return None
        if (index := int(v)) < 0:
            raise IndexError(index)
        return strings[index]
    if kind == "str":  # a formula's cached text, escaped as shared strings are
        return unescape(v)
    if kind == "inlineStr":
        return _text_of(inline) if inline is not None else v
    if kind == "b":
        if not v:
            return None
        if v in ("1", "true", "0", "false"):
            return v in ("1", "true")
        raise ValueError(v)
    if kind == "e":
        if not v:
            return None
        error = ExcelError.from_text(v)
        if error is None:
            log.warning("unknown Excel error %r kept as text", v)
        return error if error is not None else v
    return v  # "d" (ISO 8601 date) and unknown types: the text as stored


def _formula(cell: Cell, f: Element, shared: dict[int, SharedFormula], pending: list[Cell],
             arrays: list[Cell]) -> None:
    _formula_of(cell, f.attrib, f.text or None, shared, pending, arrays)


def _formula_of(cell: Cell, f: dict[str, str], text: str | None,
                shared: dict[int, SharedFormula], pending: list[Cell],
                arrays: list[Cell]) -> None:
    """Record the formula of ``cell`` from its <f>'s attributes and text."""
    kind = f.get("t", "normal")
    if text is not None and text.startswith("="):
        text = text[1:]
    cell.formula, cell.formula_type = text, kind
    if kind == "shared":
        si = f.get("si", "")
        if not si.isdigit():
            return
        cell.shared_index = index = int(si)
        if text is not None and f.get("ref") is not None:
            shared[index] = SharedFormula(index, cell.ref, f.get("ref", ""), text)
        if index in shared:
            cell.shared_master = shared[index].master
        else:
            pending.append(cell)
    elif kind == "array":
        cell.array_ref = f.get("ref") or cell.ref
        arrays.append(cell)
    elif kind == "dataTable":  # a what-if table: its area, input cells and options
        cell.array_ref = f.get("ref") or cell.ref
        cell.data_table = {k: f[k] for k in ("r1", "r2", "dt2D", "dtr", "del1", "del2")
                           if k in f}


def _mark_arrays(sheet: Sheet, arrays: list[Cell]) -> None:
    """Point the other cells an array formula fills at its master cell."""
    budget = 4 * len(sheet.cells) + 1_000_000  # ranges of a sane sheet cover its cells once
    for master in arrays:
        first, _, last = (master.array_ref or "").replace("$", "").partition(":")
        if not last or not _REF.fullmatch(first) or not _REF.fullmatch(last):
            continue
        (r1, c1), (r2, c2) = _split_ref(first), _split_ref(last)
        budget -= (r2 - r1 + 1) * (c2 - c1 + 1)
        if budget < 0:
            log.warning("%s: array formula ranges cover too many cells; stopped at %s",
                        sheet.name, master.ref)
            return
        for row in range(r1, r2 + 1):
            for col in range(c1, c2 + 1):
                cell = sheet.cells.get(f"{column_letters(col)}{row}")
                if cell is not None and cell is not master:
                    cell.array_master = master.ref


def _split_ref(ref: str, pkg: Package | None = None, where: str = "") -> tuple[int, int]:
    """(row, col) of an A1 ref such as 'B2'."""
    m = _REF.fullmatch(ref.replace("$", ""))
    if m is None:
        if pkg is None:
            raise ValueError(ref)
        raise pkg.error(where, f"bad cell reference {ref!r}")
    letters = m.group(1).upper()
    col = 0
    for ch in letters:
        col = col * 26 + ord(ch) - 64
    if col <= MAX_COL:
        _COLS[letters] = col
    return int(m.group(2)), col
