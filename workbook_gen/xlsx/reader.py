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
from pathlib import Path
from xml.etree.ElementTree import Element

from workbook_gen.errors import WorkbookReadError
from workbook_gen.xlsx.apart import read_apart
from workbook_gen.xlsx.filters import sheet_filter, table_filter
from workbook_gen.xlsx.limits import MAX_CELLS, MAX_RATIO, MAX_UNCOMPRESSED, Package
from workbook_gen.xlsx.model import ExternalLink, Sheet, TableDef, Workbook
from workbook_gen.xlsx.olap import read_olap
from workbook_gen.xlsx.topics import read_topics
from workbook_gen.xlsx.sheetdata import _LOCAL, _text_of, read_sheet

log = logging.getLogger(__name__)

_REL_NS = ("http://schemas.openxmlformats.org/officeDocument/2006/relationships",
           "http://purl.oclc.org/ooxml/officeDocument/relationships")
_PKG_REL_NS = "http://schemas.openxmlformats.org/package/2006/relationships"
_RID = tuple(f"{{{ns}}}id" for ns in _REL_NS)


MISSING_PART = "missing"  # other_sheets kind of a sheet listed without a part


def read_workbook(path: str | Path, *, max_cells: int = MAX_CELLS,
                  max_uncompressed: int = MAX_UNCOMPRESSED,
                  max_ratio: float = MAX_RATIO, ready=None, prepare=None) -> Workbook:
    """Read every worksheet's cells, the defined names and external links of ``path``.

    ``ready(sheet)`` is called with each worksheet, in order, as soon as it and the
    worksheets before it are read (while a large workbook's other sheets are still read
    on the other core); a sheet read again after a failed read on two cores is given
    again. ``prepare(sheet)`` is called in the process that read the sheet (a forked child
    for a share of a large workbook), right after; what it returns (to be pickled) is
    ``sheet.prepared`` (the child makes it while this process takes the cells it sent:
    asking for it may wait).

    Raises WorkbookReadError (one line, naming the file and the part) for a file that
    is not a zip, lacks xl/workbook.xml, has broken or hostile XML, a part whose
    declared size or compression ratio is absurd, or more than ``max_cells`` cells.
    """
    paused = gc.isenabled()
    gc.disable()  # cells hold no cycles; a collector rescanning them doubles the time
    try:
        return _read(Package(path, max_uncompressed=max_uncompressed, max_ratio=max_ratio),
                     str(path), max_cells, ready or _nothing, prepare or _nothing)
    finally:
        if paused:
            gc.enable()


def _nothing(sheet: Sheet) -> None:
    return None


def _read(pkg: Package, path: str, max_cells: int, ready, prepare) -> Workbook:
    with pkg:
        wb_part = _workbook_part(pkg)
        rels = _relationships(pkg, wb_part)
        root = pkg.parse(wb_part)
        book = Workbook(path, [], {}, [], [])
        pr = _child(root, "workbookPr")
        book.date1904 = pr is not None and pr.get("date1904", "0") in ("1", "true")
        calc = _child(root, "calcPr")
        book.iterate = calc is not None and calc.get("iterate", "0") in ("1", "true")
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
        book.olap = read_olap(pkg, root, rels, _rid)
        book.topics = read_topics(pkg, rels)
        book.vba_project = next((p for k, p in rels.values() if k == "vbaProject" and p
                                 and not p.startswith("external:")), None)
        sst_part = next((p for k, p in rels.values() if k == "sharedStrings" and p
                        and not p.startswith("external:")), None)
        book.application = _application(pkg)
        strings = _shared_strings(pkg, sst_part, max_cells) if sst_part else []
        if read_apart(pkg, sheet_parts, strings, max_cells, ready, prepare):  # on two cores
            for sheet, part in sheet_parts:
                _read_tables(pkg, part, sheet)
            return book
        budget = max_cells
        for sheet, part in sheet_parts:
            budget -= read_sheet(pkg, part, sheet, strings, budget, max_cells)
            _read_tables(pkg, part, sheet)
            sheet.prepared = prepare(sheet)
            ready(sheet)
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
    """The tables of a sheet (structured references name them), and for a sheet with
    hidden rows the filters that may have hidden them."""
    if sheet.hidden_rows:
        sheet.filter_ref = sheet_filter(pkg, part)
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
                                     int(totals) if totals.isdigit() else 0,
                                     table_filter(root)))


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
        elif local == "definedName" and el.get("name") and el.get("refersTo") is not None:
            sheet_id = el.get("sheetId", "")
            link.names[(el.get("name", "").casefold(),
                        int(sheet_id) if sheet_id.isdigit() else None)] = el.get("refersTo", "")
        elif local == "sheetData" and el.get("sheetId", "").isdigit():
            link.cells[int(el.get("sheetId", ""))] = _external_cells(el)
    return link


def _external_cells(sheet_data: Element) -> dict[tuple[int, int], object]:
    """{(row, col): value} of one sheet's cached cells (``<cell r t><v>``)."""
    from workbook_gen.xlsx.sheetdata import _split_ref, _value
    out: dict[tuple[int, int], object] = {}
    for el in sheet_data.iter():
        if el.tag.rpartition("}")[2] != "cell" or not el.get("r"):
            continue
        v = next((c.text for c in el if c.tag.rpartition("}")[2] == "v"), None)
        kind = el.get("t", "n")
        try:
            value = None if v is None else _value(
                "str" if kind in ("s", "inlineStr") else kind, v, None, [])
            out[_split_ref(el.get("r", ""))] = value
        except (ValueError, IndexError):
            continue  # a cell the cache garbles: absent, so not answered
    return out


def _shared_strings(pkg: Package, part: str, limit: int) -> list[str]:
    strings: list[str] = []
    for el in pkg.iter_xml(part):
        if _LOCAL.get(el.tag) == "si":
            strings.append(_text_of(el))
            el.clear()
            if len(strings) > limit:
                raise pkg.error(part, f"more than {limit} shared strings (max_cells)")
    return strings



def _child(el: Element | None, name: str) -> Element | None:
    if el is None:
        return None
    return next((c for c in el if c.tag.rpartition("}")[2] == name), None)


def _children(el: Element | None, name: str) -> list[Element]:
    return [] if el is None else [c for c in el if c.tag.rpartition("}")[2] == name]


def _rid(el: Element) -> str:
    return next((el.get(k) for k in _RID if el.get(k) is not None), "")
