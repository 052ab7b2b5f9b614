"""Streaming reader of an xlsx workbook: cells with cached values and formula text.

Any xlsx is read (ours, Excel's, LibreOffice's), never evaluated.  Sheets come from
xl/workbook.xml and its relationships (not from file names); chartsheets and other
non-worksheets are listed in ``Workbook.other_sheets`` only.  Shared formulas keep
their text on the master cell: a follower has ``formula`` None, ``shared_index``
and ``shared_master``; ``Sheet.formula_source(cell)`` gives ``(text, origin_ref)``
and the formula parser shifts the text's relative references from ``origin_ref``
to the cell.  Formula text is as stored: no leading '=', future functions keep
their ``_xlfn.`` prefix.  Cells with neither a value nor a formula are skipped.
"""

from __future__ import annotations

import gc
import logging
import posixpath
import re
from pathlib import Path
from xml.etree.ElementTree import Element, ParseError, fromstring

from workbook_gen.errors import WorkbookReadError
from workbook_gen.xlerror import ExcelError
from workbook_gen.xlsx.limits import MAX_CELLS, MAX_RATIO, MAX_UNCOMPRESSED, Package
from workbook_gen.xlsx.model import (MAX_COL, Cell, ExternalLink, SharedFormula, Sheet,
                                     TableDef, Value, Workbook, column_letters)

log = logging.getLogger(__name__)

MAX_ROW = 1_048_576
_MAIN_NS = ("http://schemas.openxmlformats.org/spreadsheetml/2006/main",
            "http://purl.oclc.org/ooxml/spreadsheetml/main")  # transitional, strict
_REL_NS = ("http://schemas.openxmlformats.org/officeDocument/2006/relationships",
           "http://purl.oclc.org/ooxml/officeDocument/relationships")
_PKG_REL_NS = "http://schemas.openxmlformats.org/package/2006/relationships"
_LOCAL = {f"{{{ns}}}{name}": name for ns in _MAIN_NS
          for name in ("row", "c", "v", "f", "is", "t", "r", "si", "dimension")}
_RID = tuple(f"{{{ns}}}id" for ns in _REL_NS)
_REF = re.compile(r"([A-Za-z]{1,3})([0-9]{1,7})")
_ESCAPE = re.compile(r"_x([0-9A-Fa-f]{4})_")
_UPPER = "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
_COLS: dict[str, int] = {}


MISSING_PART = "missing"  # other_sheets kind of a sheet listed without a part


def read_workbook(path: str | Path, *, max_cells: int = MAX_CELLS,
                  max_uncompressed: int = MAX_UNCOMPRESSED,
                  max_ratio: float = MAX_RATIO) -> Workbook:
    """Read every worksheet's cells, the defined names and external links of ``path``.

    Raises WorkbookReadError (one line, naming the file and the part) for a file that
    is not a zip, lacks xl/workbook.xml, has broken or hostile XML, a part whose
    declared size or compression ratio is absurd, or more than ``max_cells`` cells.
    """
    paused = gc.isenabled()
    gc.disable()  # cells hold no cycles; a collector rescanning them doubles the time
    try:
        return _read(Package(path, max_uncompressed=max_uncompressed, max_ratio=max_ratio),
                     str(path), max_cells)
    finally:
        if paused:
            gc.enable()


def _read(pkg: Package, path: str, max_cells: int) -> Workbook:
    with pkg:
        wb_part = _workbook_part(pkg)
        rels = _relationships(pkg, wb_part)
        root = pkg.parse(wb_part)
        book = Workbook(path, [], {}, [], [])
        pr = _child(root, "workbookPr")
        book.date1904 = pr is not None and pr.get("date1904", "0") in ("1", "true")
        sheet_parts: list[tuple[Sheet, str]] = []
        by_index: dict[int, Sheet] = {}
        for index, el in enumerate(_children(_child(root, "sheets"), "sheet")):
            name = el.get("name") or f"#{index + 1}"
            if _rid(el) not in rels:  # (a macro sheet whose part a tool dropped): unreadable
                book.other_sheets.append((name, MISSING_PART))
                continue
            kind, part = rels[_rid(el)]
            if kind != "worksheet":
                book.other_sheets.append((name, kind or "unknown"))
                continue
            if part is None or part.startswith("external:"):
                raise pkg.error(wb_part, f"sheet {name!r}: its part is missing from the zip")
            sheet = Sheet(name, index, el.get("state", "visible"))
            book.sheets.append(sheet)
            by_index[index] = sheet
            sheet_parts.append((sheet, part))
        _read_defined_names(root, book, by_index)
        for n, el in enumerate(_children(_child(root, "externalReferences"), "externalReference")):
            part = rels.get(_rid(el), (None, None))[1]
            book.external_links.append(_external_link(pkg, n + 1, part))
        book.vba_project = next((p for k, p in rels.values() if k == "vbaProject" and p
                                 and not p.startswith("external:")), None)
        sst_part = next((p for k, p in rels.values() if k == "sharedStrings" and p
                        and not p.startswith("external:")), None)
        book.application = _application(pkg)
        strings = _shared_strings(pkg, sst_part, max_cells) if sst_part else []
        budget = max_cells
        for sheet, part in sheet_parts:
            budget -= _read_sheet(pkg, part, sheet, strings, budget, max_cells)
            _read_tables(pkg, part, sheet)
        return book


def _application(pkg: Package) -> str | None:
    """The ``Application`` of the extended properties (docProps/app.xml), or None."""
    part = None
    if pkg.find("_rels/.rels"):
        part = next((p for kind, p in _relationships(pkg, "").values()
                     if kind == "extended-properties" and p and not p.startswith("external:")),
                    None)
    part = part or pkg.find("docProps/app.xml")
    if part is None:
        return None
    try:
        el = _child(pkg.parse(part), "Application")
    except WorkbookReadError:  # a broken property part says nothing about the cells
        return None
    text = (el.text or "").strip() if el is not None else ""
    return text or None


def _read_tables(pkg: Package, part: str, sheet: Sheet) -> None:
    """The tables of a sheet (structured references name them)."""
    for kind, target in _relationships(pkg, part).values():
        if kind != "table" or target is None or target.startswith("external:"):
            continue
        root = pkg.parse(target)
        name = root.get("displayName") or root.get("name")
        ref = root.get("ref")
        if not name or not ref:
            continue
        columns = [c.get("name", "") for c in _children(_child(root, "tableColumns"),
                                                         "tableColumn")]
        header = root.get("headerRowCount", "1")
        totals = root.get("totalsRowCount", "0")
        sheet.tables.append(TableDef(name, ref, columns,
                                     int(header) if header.isdigit() else 1,
                                     int(totals) if totals.isdigit() else 0))


def _workbook_part(pkg: Package) -> str:
    if pkg.find("_rels/.rels"):
        for kind, part in _relationships(pkg, "").values():
            if kind == "officeDocument" and part:
                return part
    part = pkg.find("xl/workbook.xml")
    if part is None:
        raise pkg.error("xl/workbook.xml", "missing: not a spreadsheet package")
    return part


def _relationships(pkg: Package, source: str) -> dict[str, tuple[str, str | None]]:
    """rId -> (kind, member) for the rels of part ``source`` (kind: last word of Type)."""
    folder, base = posixpath.split(source)
    rels_part = pkg.find(posixpath.join(folder, "_rels", base + ".rels"))
    out: dict[str, tuple[str, str | None]] = {}
    if rels_part is None:
        return out
    for el in pkg.parse(rels_part).iter(f"{{{_PKG_REL_NS}}}Relationship"):
        target = el.get("Target", "")
        kind = el.get("Type", "").rsplit("/", 1)[-1]
        if el.get("TargetMode") == "External":
            out[el.get("Id", "")] = (kind, "external:" + target)
            continue
        full = target if target.startswith("/") else posixpath.join(folder, target)
        out[el.get("Id", "")] = (kind, pkg.find(full))
    return out


def _read_defined_names(root: Element, book: Workbook, by_index: dict[int, Sheet]) -> None:
    for el in _children(_child(root, "definedNames"), "definedName"):
        name, text = el.get("name"), (el.text or "").strip()
        if not name:
            continue
        local = el.get("localSheetId")
        if local is None:
            book.defined_names[name] = text
        elif local.isdigit() and int(local) in by_index:
            by_index[int(local)].defined_names[name] = text
        else:
            log.info("%s: defined name %s belongs to no worksheet (localSheetId=%s)",
                     book.path, name, local)


def _external_link(pkg: Package, index: int, part: str | None) -> ExternalLink:
    link = ExternalLink(index, part or "", None)
    if part is None or part.startswith("external:"):
        return link
    rels = _relationships(pkg, part)
    for el in pkg.parse(part).iter():
        local = el.tag.rpartition("}")[2]
        if local == "externalBook":
            target = rels.get(_rid(el), (None, None))[1]
            link.target = target.removeprefix("external:") if target else None
        elif local == "sheetName" and el.get("val") is not None:
            link.sheet_names.append(el.get("val", ""))
    return link


def _shared_strings(pkg: Package, part: str, limit: int) -> list[str]:
    strings: list[str] = []
    for el in pkg.iter_xml(part):
        if _LOCAL.get(el.tag) == "si":
            strings.append(_text_of(el))
            el.clear()
            if len(strings) > limit:
                raise pkg.error(part, f"more than {limit} shared strings (max_cells)")
    return strings


def _text_of(el: Element) -> str:
    """Text of an <si> or <is>: its <t>, or its rich-text runs' <t>; phonetic runs skipped."""
    parts = []
    for child in el:
        tag = _LOCAL.get(child.tag)
        if tag == "t":
            parts.append(child.text or "")
        elif tag == "r":
            parts.extend(t.text or "" for t in child if _LOCAL.get(t.tag) == "t")
    text = "".join(parts)
    return _ESCAPE.sub(lambda m: chr(int(m.group(1), 16)), text) if "_x" in text else text


def _read_sheet(pkg: Package, part: str, sheet: Sheet, strings: list[str], budget: int,
                max_cells: int) -> int:
    """Fill ``sheet.cells`` from ``part``; returns the number of <c> elements read."""
    local, cells, shared, cols = _LOCAL, sheet.cells, sheet.shared_formulas, _COLS
    where = f"{part} ({sheet.name})"
    count = row_no = n_rows = 0
    pending: list[Cell] = []
    arrays: list[Cell] = []
    for row in _rows(pkg, part, sheet):
        n_rows += 1
        r = row.get("r")
        row_no = int(r) if r and r.isdigit() else row_no + 1
        if row_no > MAX_ROW or n_rows > MAX_ROW:
            raise pkg.error(where, f"row {row_no} beyond Excel's {MAX_ROW} rows")
        col = 0
        for c in row:
            if local.get(c.tag) != "c":
                continue
            count += 1
            if count > budget:
                raise pkg.error(where, f"more than {max_cells} cells (max_cells); "
                                       "raise max_cells to read this workbook")
            ref = c.get("r")
            if ref is None:
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
                _formula(cell, f, shared, pending, arrays)
            cells[ref] = cell
        row.clear()
    for cell in pending:
        if cell.shared_index not in shared:
            raise pkg.error(where, f"cell {cell.ref}: shared formula si={cell.shared_index} "
                                   "has no master")
        cell.shared_master = shared[cell.shared_index].master
    _mark_arrays(sheet, arrays)
    return count


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
    end_data = b"</" + prefix + b"sheetData>"
    row_end = b"</" + prefix + b"row>"
    buf = head[m.end():]
    done = False
    while True:
        stop = buf.find(end_data)
        if stop >= 0:
            batch, buf, done = buf[:stop], b"", True
        else:
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
        try:
            wrapper = fromstring(start_tag + batch + close_root)
        except ParseError as exc:
            raise pkg.error(part, f"broken XML: {exc}") from None
        yield from wrapper
        if done:
            for _ in chunks:  # the rest of the part still counts against the budget
                pass
            return


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


def _value(kind: str, v: str | None, inline: Element | None, strings: list[str]) -> Value:
    if kind == "n":
        return float(v) if v else None
    if kind == "s":
        if not v:
            return None
        if (index := int(v)) < 0:
            raise IndexError(index)
        return strings[index]
    if kind == "str":
        return v
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
    kind = f.get("t", "normal")
    text = f.text or None
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


def _child(el: Element | None, name: str) -> Element | None:
    if el is None:
        return None
    return next((c for c in el if c.tag.rpartition("}")[2] == name), None)


def _children(el: Element | None, name: str) -> list[Element]:
    return [] if el is None else [c for c in el if c.tag.rpartition("}")[2] == name]


def _rid(el: Element) -> str:
    return next((el.get(k) for k in _RID if el.get(k) is not None), "")
