"""``audit --annotate OUT.xlsx``: a copy of the workbook with every disagreement and
finding highlighted (a fill) and explained (a cell comment).

The copy is made by editing the package's XML, never by loading and saving it with a
spreadsheet library: styles.xml gains two fills and, for each cell format a flagged cell
used, a copy of that format with the fill; a flagged cell's ``s`` attribute points at the
copy (nothing else of the cell is touched, so every formula and cached value stays byte
for byte as it was and a viewer that does not calculate shows the same numbers); each
flagged sheet gets a comments part and its VML drawing, or has ours added to the ones it
has. Written atomically; an existing file is replaced only with ``force``.
"""

from __future__ import annotations

import posixpath
import re
import zipfile
from collections import defaultdict
from pathlib import Path
from xml.parsers import expat

from ..errors import OutputExistsError, WorkbookGenError, WorkbookReadError
from ..files import refuse_existing, write_atomically
from ..xlsx.limits import Package
from . import notes as parts
from .grid import show_value
from .report import AuditReport

_REL = "http://schemas.openxmlformats.org/officeDocument/2006/relationships"
_A1 = re.compile(r"\$?([A-Z]{1,3})\$?([0-9]{1,7})")


def check_target(source: str | Path, target: str | Path, *, force: bool) -> Path:
    """Refuse, before any work, a target that exists (without ``force``), is the source
    itself, or has another suffix than the source (an .xlsm keeps its macros)."""
    source, target = Path(source), Path(target)
    if target.suffix.lower() != source.suffix.lower():
        raise WorkbookGenError(f"--annotate {target}: name it {source.suffix} like "
                               f"{source.name} (the package's content type follows it)")
    if target.exists() and source.exists() and target.resolve() == source.resolve():
        raise OutputExistsError(f"--annotate {target}: that is the audited file itself; "
                                "name a copy")
    refuse_existing(target, force)
    return target


def notes_of(report: AuditReport) -> dict[tuple[str, str], tuple[str, list[str]]]:
    """{(sheet, "B2"): (fill, [texts])}: "disagree" wins over "finding" for the fill."""
    out: dict[tuple[str, str], tuple[str, list[str]]] = {}

    def add(cell: str, kind: str, text: str) -> None:
        where = split_cell(cell)
        if where is None:
            return  # a defined name or a part of the file: no cell to mark
        fill, texts = out.get(where, ("finding", []))
        out[where] = ("disagree" if "disagree" in (fill, kind) else "finding", texts + [text])

    for m in report.mismatches:
        add(m.cell, "disagree", f"disagrees: the file holds {show_value(m.cached)}, the formula "
                                f"gives {show_value(m.recomputed)}"
                                + ("" if m.root else " (it reads a cell that disagrees)"))
    if report.engine is not None:
        for m in report.engine.mismatches:
            add(m.cell, "disagree", f"{report.engine.engine} computes {show_value(m.cached)}, "
                                    f"the audit {show_value(m.recomputed)}")
    for f in report.findings:
        add(f.cell, "finding", f"{f.kind}: {f.message}")
    return out


def split_cell(cell: str) -> tuple[str, str] | None:
    """'Sheet 1'!B2 -> ("Sheet 1", "B2"); None for what is not a cell."""
    if cell.startswith("'"):
        end = cell.find("'!")
        while end > 0 and cell[end - 1:end + 1] == "''" and cell[end - 2:end] != "''":
            end = cell.find("'!", end + 1)
        sheet, ref = cell[1:end].replace("''", "'"), cell[end + 2:]
    else:
        sheet, _, ref = cell.rpartition("!")
    ref = ref.replace("$", "")
    return (sheet, ref) if sheet and _A1.fullmatch(ref) else None


def annotate(source: str | Path, report: AuditReport, target: str | Path, *,
             force: bool = False) -> Path:
    """Write the annotated copy of ``source`` to ``target``; returns ``target``."""
    target = check_target(source, target, force=force)
    by_sheet: dict[str, dict[str, tuple[str, list[str]]]] = defaultdict(dict)
    for (sheet, ref), note in notes_of(report).items():
        by_sheet[sheet.casefold()][ref] = note
    edited = _edit(Path(source), by_sheet)
    return write_atomically(target, lambda temp: _write(Path(source), temp, edited),
                            force=force)


def _write(source: Path, temp: Path, edited: dict[str, bytes]) -> None:
    """The source's members in their order, edited ones replaced, new ones appended."""
    with zipfile.ZipFile(source) as zin, zipfile.ZipFile(temp, "w") as zout:
        names = set()
        for info in zin.infolist():
            names.add(info.filename)
            data = edited.get(info.filename)
            zout.writestr(info, data if data is not None else zin.read(info.filename),
                          compress_type=info.compress_type)
        for name, data in edited.items():
            if name not in names:
                zout.writestr(name, data, compress_type=zipfile.ZIP_DEFLATED)


class _Edits:
    """Parts read once and edited as text."""

    def __init__(self, pkg: Package):
        self.pkg, self.text, self.new = pkg, {}, set()

    def get(self, part: str) -> str | None:
        if part not in self.text:
            name = self.pkg.find(part)
            self.text[part] = self.pkg.read_bytes(name).decode("utf-8") if name else None
        return self.text[part]

    def put(self, part: str, text: str) -> None:
        if self.pkg.find(part) is None:
            self.new.add(part)
        self.text[part] = text

    def unused(self, pattern: str) -> str:
        n = 1
        while self.pkg.find(pattern % n) or pattern % n in self.text:
            n += 1
        return pattern % n


def _rels_part(part: str) -> str:
    folder, base = posixpath.split(part)
    return posixpath.join(folder, "_rels", base + ".rels")


def _relationships(text: str | None, folder: str) -> list[tuple[str, str, str]]:
    """(id, type, part) of each internal relationship."""
    out = []
    for attrs in re.findall(r"<Relationship\b([^>]*)/?>", text or ""):
        get = dict(re.findall(r'(\w+)\s*=\s*["\']([^"\']*)["\']', attrs))
        if get.get("TargetMode") == "External":
            continue
        target = get.get("Target", "")
        full = target.lstrip("/") if target.startswith("/") else posixpath.normpath(
            posixpath.join(folder, target))
        out.append((get.get("Id", ""), get.get("Type", ""), full))
    return out


def _edit(source: Path, by_sheet: dict) -> dict[str, bytes]:
    with Package(source) as pkg:
        edits = _Edits(pkg)
        root_rels = _relationships(edits.get("_rels/.rels"), "")
        book = next((p for _, t, p in root_rels if t.endswith("/officeDocument")),
                    "xl/workbook.xml")
        folder = posixpath.dirname(book)
        book_rels = _relationships(edits.get(_rels_part(book)), folder)
        targets = {rid: part for rid, _, part in book_rels}
        workbook = edits.get(book) or ""
        sheets = {}
        for attrs in re.findall(r"<(?:[\w.-]+:)?sheet\b([^>]*)/?>", workbook):
            name = re.search(r'\bname\s*=\s*"([^"]*)"', attrs)
            rid = re.search(r'\b[\w.-]+:id\s*=\s*"([^"]*)"', attrs)
            if name and rid and rid.group(1) in targets:
                sheets[_unescape(name.group(1)).casefold()] = targets[rid.group(1)]
        styles_part = next((p for _, t, p in book_rels if t == parts.REL_STYLES), None)
        overrides: dict[str, str] = {}
        if styles_part is None or edits.get(styles_part) is None:
            styles_part = edits.unused("xl/styles%d.xml")
            edits.put(styles_part, parts.NEW_STYLES)
            rels, _ = parts.add_relationship(edits.get(_rels_part(book)), parts.REL_STYLES,
                                             posixpath.relpath(styles_part, folder))
            edits.put(_rels_part(book), rels)
            overrides[styles_part] = parts.CT_STYLES
        marks = {}
        for sheet, cell_notes in by_sheet.items():
            if sheet in sheets:
                marks[sheets[sheet]] = cell_notes
        bases = {sheet: _styles_used(edits.get(p) or "", notes) for p, notes in marks.items()
                 for sheet in [p]}
        styles, index = parts.add_fills(edits.get(styles_part),
                                        {s for used in bases.values() for s in used.values()})
        edits.put(styles_part, styles)
        vml = False
        for part, cell_notes in marks.items():
            vml |= _annotate_sheet(edits, part, cell_notes, index, overrides)
        types = edits.get("[Content_Types].xml")
        if types is None:
            raise WorkbookReadError(f"{source}: [Content_Types].xml is missing")
        edits.put("[Content_Types].xml", parts.add_content_types(types, overrides, vml))
        return {p: t.encode("utf-8") for p, t in edits.text.items()
                if t is not None and (p in edits.new or t != _original(pkg, p))}


def _original(pkg: Package, part: str) -> str | None:
    name = pkg.find(part)
    return pkg.read_bytes(name).decode("utf-8") if name else None


def _unescape(text: str) -> str:
    return (text.replace("&quot;", '"').replace("&apos;", "'").replace("&lt;", "<")
            .replace("&gt;", ">").replace("&amp;", "&"))


def _cell_tags(xml: str):
    """(start, end, ref, style) of every <c> start tag, located by expat (prefixes,
    quoting and attribute order as the file has them)."""
    data = xml.encode("utf-8")
    found = []
    parser = expat.ParserCreate()

    def start(name, attrs):
        if name.rpartition(":")[2] == "c":
            at = parser.CurrentByteIndex
            found.append((at, data.index(b">", at) + 1, attrs.get("r"), attrs.get("s", "0")))
    parser.StartElementHandler = start
    parser.Parse(data, True)
    return data, found


def _styles_used(xml: str, cell_notes: dict) -> dict[str, int]:
    _, tags = _cell_tags(xml)
    return {ref: int(s) if s.isdigit() else 0 for _, _, ref, s in tags if ref in cell_notes}


def _annotate_sheet(edits: _Edits, part: str, cell_notes: dict, index: dict,
                    overrides: dict) -> bool:
    """Restyle the flagged cells of one sheet and add their comments; True if a VML
    drawing was made."""
    data, tags = _cell_tags(edits.get(part))
    pieces, at, marked = [], 0, {}
    for start, end, ref, style in tags:
        if ref not in cell_notes:
            continue
        fill, texts = cell_notes[ref]
        base = int(style) if style.isdigit() else 0
        tag = data[start:end].decode("utf-8")
        pieces += [data[at:start], parts._set_attr(tag, "s", str(index[(base, fill)]))
                   .encode("utf-8")]
        at = end
        marked[ref] = "\n".join(texts)
    pieces.append(data[at:])
    xml = b"".join(pieces).decode("utf-8")
    if not marked:
        return False
    folder = posixpath.dirname(part)
    rels_part = _rels_part(part)
    rels = _relationships(edits.get(rels_part), folder)
    comments = next((p for _, t, p in rels if t == parts.REL_COMMENTS), None)
    legacy = re.search(r'<(?:[\w.-]+:)?legacyDrawing\b[^>]*?\b[\w.-]+:id\s*=\s*"([^"]*)"', xml)
    vml_part = next((p for rid, _, p in rels if legacy and rid == legacy.group(1)), None)
    cells = [_row_col(ref) for ref in marked]
    made_vml = False
    if comments is not None and edits.get(comments) is not None:
        text, fresh = parts.extend_comments(edits.get(comments), marked)
        edits.put(comments, text)
        cells = [_row_col(ref) for ref in fresh]
    else:
        comments = edits.unused("xl/comments%d.xml")
        edits.put(comments, parts.new_comments(marked))
        text, _ = parts.add_relationship(edits.get(rels_part), parts.REL_COMMENTS,
                                         posixpath.relpath(comments, folder))
        edits.put(rels_part, text)
        overrides[comments] = parts.CT_COMMENTS
    if vml_part is not None and edits.get(vml_part) is not None:
        edits.put(vml_part, parts.extend_vml(edits.get(vml_part), cells))
    else:
        vml_part = edits.unused("xl/drawings/vmlDrawing%d.vml")
        edits.put(vml_part, parts.new_vml(cells))
        text, rid = parts.add_relationship(edits.get(rels_part), parts.REL_VML,
                                           posixpath.relpath(vml_part, folder))
        edits.put(rels_part, text)
        xml = _add_legacy_drawing(xml, rid)
        made_vml = True
    edits.put(part, xml)
    return made_vml


# children of <worksheet> that come after <legacyDrawing> (ECMA-376 CT_Worksheet order)
_AFTER = ("legacyDrawingHF", "drawingHF", "picture", "oleObjects", "controls",
          "webPublishItems", "tableParts", "extLst")


def _add_legacy_drawing(xml: str, rid: str) -> str:
    """``<legacyDrawing r:id=.../>`` at its place among the worksheet's children."""
    data = xml.encode("utf-8")
    root = {}
    depth = [0]
    parser = expat.ParserCreate()
    insert = []

    def start(name, attrs):
        depth[0] += 1
        local = name.rpartition(":")[2]
        if depth[0] == 1:
            root["prefix"] = name[:len(name) - len(local)]
            root["r"] = next((k.partition(":")[2] for k, v in attrs.items()
                              if k.startswith("xmlns:") and v == _REL), None)
        elif depth[0] == 2 and local in _AFTER and not insert:
            insert.append(parser.CurrentByteIndex)

    def end(name):
        depth[0] -= 1
        if depth[0] == 0 and not insert:
            insert.append(parser.CurrentByteIndex)
    parser.StartElementHandler, parser.EndElementHandler = start, end
    parser.Parse(data, True)
    if root.get("r"):
        element = f'<{root["prefix"]}legacyDrawing {root["r"]}:id="{rid}"/>'
    else:
        element = f'<{root["prefix"]}legacyDrawing xmlns:r="{_REL}" r:id="{rid}"/>'
    at = insert[0]
    return (data[:at] + element.encode("utf-8") + data[at:]).decode("utf-8")


def _row_col(ref: str) -> tuple[int, int]:
    m = _A1.fullmatch(ref)
    col = 0
    for ch in m.group(1):
        col = col * 26 + ord(ch) - 64
    return int(m.group(2)), col
