"""The parts an annotated copy adds or extends: fills and cell formats in styles.xml, a
comments part and its VML drawing (the shapes Excel shows comments with), relationships
and content types. Text in, text out: every byte of a part outside the places edited
stays as it was.
"""

from __future__ import annotations

import re
from xml.sax.saxutils import escape, quoteattr

AUTHOR = "workbook-gen audit"
FILLS = {"disagree": "FFFFC7CE", "finding": "FFFFEB9C"}  # light red, light yellow

NS_MAIN = "http://schemas.openxmlformats.org/spreadsheetml/2006/main"
REL_COMMENTS = "http://schemas.openxmlformats.org/officeDocument/2006/relationships/comments"
REL_VML = "http://schemas.openxmlformats.org/officeDocument/2006/relationships/vmlDrawing"
REL_STYLES = "http://schemas.openxmlformats.org/officeDocument/2006/relationships/styles"
CT_COMMENTS = "application/vnd.openxmlformats-officedocument.spreadsheetml.comments+xml"
CT_VML = "application/vnd.openxmlformats-officedocument.vmlDrawing"
CT_STYLES = "application/vnd.openxmlformats-officedocument.spreadsheetml.styles+xml"
NEW_STYLES = (f'<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n<styleSheet '
              f'xmlns="{NS_MAIN}"><fonts count="1"><font><sz val="11"/><name val="Calibri"/>'
              '</font></fonts><fills count="2"><fill><patternFill patternType="none"/></fill>'
              '<fill><patternFill patternType="gray125"/></fill></fills><borders count="1">'
              '<border><left/><right/><top/><bottom/><diagonal/></border></borders>'
              '<cellStyleXfs count="1"><xf numFmtId="0" fontId="0" fillId="0" borderId="0"/>'
              '</cellStyleXfs><cellXfs count="1"><xf numFmtId="0" fontId="0" fillId="0" '
              'borderId="0" xfId="0"/></cellXfs></styleSheet>')


class PartError(ValueError):
    """A part this module cannot edit safely."""


def _block(text: str, name: str) -> re.Match | None:
    """``<name ...>...</name>`` (any prefix), or a self-closed ``<name .../>``."""
    return re.search(rf"<((?:[\w.-]+:)?){name}\b([^>]*?)(?:/>|>(.*?)</\1{name}>)", text, re.S)


def _elements(inner: str, prefix: str, name: str) -> list[str]:
    return re.findall(rf"<{prefix}{name}\b[^>]*?/>|<{prefix}{name}\b[^>]*>.*?</{prefix}{name}>",
                      inner, re.S)


def _with_count(attrs: str, count: int) -> str:
    if re.search(r'\bcount\s*=\s*["\'][^"\']*["\']', attrs):
        return re.sub(r'\bcount\s*=\s*["\'][^"\']*["\']', f'count="{count}"', attrs)
    return f' count="{count}"{attrs}'


def _set_attr(tag: str, name: str, value: str) -> str:
    """A start tag (or empty element) with attribute ``name`` set to ``value``."""
    pattern = rf'(\s{name}\s*=\s*)(["\'])[^"\']*\2'
    if re.search(pattern, tag):
        return re.sub(pattern, lambda m: f'{m.group(1)}"{value}"', tag, count=1)
    end = len(tag) - (2 if tag.endswith("/>") else 1)
    return f'{tag[:end]} {name}="{value}"{tag[end:]}'


def add_fills(styles: str, bases: set[int]) -> tuple[str, dict[tuple[int, str], int]]:
    """Two solid fills, and for each base cell format in ``bases`` a copy of it with
    each fill: {(base, "disagree"|"finding"): new cellXfs index}."""
    fills = _block(styles, "fills")
    xfs = _block(styles, "cellXfs")
    if xfs is None:
        raise PartError("styles.xml has no cellXfs")
    prefix = xfs.group(1)
    if fills is None:
        default = (f'<{prefix}fills count="2"><{prefix}fill><{prefix}patternFill '
                   f'patternType="none"/></{prefix}fill><{prefix}fill><{prefix}patternFill '
                   f'patternType="gray125"/></{prefix}fill></{prefix}fills>')
        anchor = _block(styles, "borders") or _block(styles, "cellStyleXfs") or xfs
        styles = styles[:anchor.start()] + default + styles[anchor.start():]
        fills, xfs = _block(styles, "fills"), _block(styles, "cellXfs")
    existing = _elements(fills.group(3) or "", prefix, "fill")
    fill_ids = {}
    added = ""
    for n, (name, rgb) in enumerate(FILLS.items()):
        fill_ids[name] = len(existing) + n
        added += (f'<{prefix}fill><{prefix}patternFill patternType="solid"><{prefix}fgColor '
                  f'rgb="{rgb}"/><{prefix}bgColor indexed="64"/></{prefix}patternFill>'
                  f'</{prefix}fill>')
    new_fills = (f"<{prefix}fills{_with_count(fills.group(2), len(existing) + len(FILLS))}>"
                 f"{fills.group(3) or ''}{added}</{prefix}fills>")
    styles = styles[:fills.start()] + new_fills + styles[fills.end():]

    xfs = _block(styles, "cellXfs")
    formats = _elements(xfs.group(3) or "", prefix, "xf")
    index: dict[tuple[int, str], int] = {}
    added = ""
    for base in sorted(bases):
        source = formats[base] if 0 <= base < len(formats) else (
            formats[0] if formats else f'<{prefix}xf numFmtId="0" fontId="0" fillId="0" '
                                       'borderId="0" xfId="0"/>')
        start = source[:source.index(">") + 1]
        for name in FILLS:
            tag = _set_attr(_set_attr(start, "fillId", str(fill_ids[name])), "applyFill", "1")
            index[(base, name)] = len(formats) + len(index)
            added += tag + source[len(start):]
    new_xfs = (f"<{prefix}cellXfs{_with_count(xfs.group(2), len(formats) + len(index))}>"
               f"{xfs.group(3) or ''}{added}</{prefix}cellXfs>")
    return styles[:xfs.start()] + new_xfs + styles[xfs.end():], index


def _runs(text: str) -> str:
    return (f'<r><rPr><b/><sz val="9"/></rPr><t xml:space="preserve">{escape(AUTHOR)}:</t></r>'
            f'<r><rPr><sz val="9"/></rPr><t xml:space="preserve">\n{escape(text)}</t></r>')


def new_comments(notes: dict[str, str]) -> str:
    body = "".join(f'<comment ref="{ref}" authorId="0"><text>{_runs(text)}</text></comment>'
                   for ref, text in notes.items())
    return (f'<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n<comments '
            f'xmlns="{NS_MAIN}"><authors><author>{AUTHOR}</author></authors>'
            f'<commentList>{body}</commentList></comments>')


def extend_comments(xml: str, notes: dict[str, str]) -> tuple[str, list[str]]:
    """Our notes added to a comments part: appended to a cell's comment when it has
    one, else a new comment. Returns the part and the refs that got a new comment
    (they need a VML shape)."""
    authors = _block(xml, "authors")
    listing = _block(xml, "commentList")
    if authors is None or listing is None:
        raise PartError("comments part without authors or commentList")
    prefix = authors.group(1)
    names = _elements(authors.group(3) or "", prefix, "author")
    author_id = len(names)
    xml = (xml[:authors.start()]
           + f"<{prefix}authors{authors.group(2)}>{authors.group(3) or ''}"
             f"<{prefix}author>{AUTHOR}</{prefix}author></{prefix}authors>"
           + xml[authors.end():])
    listing = _block(xml, "commentList")
    inner = listing.group(3) or ""
    fresh = []
    for ref, text in notes.items():
        found = re.search(rf'<{prefix}comment\b[^>]*\bref\s*=\s*["\']{ref}["\'][^>]*>(.*?)'
                          rf'</{prefix}text>', inner, re.S)
        runs = _runs(text).replace("<r>", f"<{prefix}r>").replace("</r>", f"</{prefix}r>") \
            .replace("<rPr>", f"<{prefix}rPr>").replace("</rPr>", f"</{prefix}rPr>") \
            .replace("<b/>", f"<{prefix}b/>").replace("<sz ", f"<{prefix}sz ") \
            .replace("<t ", f"<{prefix}t ").replace("</t>", f"</{prefix}t>")
        if found:
            at = found.end() - len(f"</{prefix}text>")
            inner = inner[:at] + runs + inner[at:]
        else:
            inner += (f'<{prefix}comment ref="{ref}" authorId="{author_id}"><{prefix}text>'
                      f"{runs}</{prefix}text></{prefix}comment>")
            fresh.append(ref)
    xml = (xml[:listing.start()] + f"<{prefix}commentList{listing.group(2)}>{inner}"
           f"</{prefix}commentList>" + xml[listing.end():])
    return xml, fresh


_VML_NS = ('xmlns:v="urn:schemas-microsoft-com:vml" '
           'xmlns:o="urn:schemas-microsoft-com:office:office" '
           'xmlns:x="urn:schemas-microsoft-com:office:excel"')
_SHAPETYPE = ('<v:shapetype id="_x0000_t202" coordsize="21600,21600" o:spt="202" '
              'path="m,l,21600r21600,l21600,xe"><v:stroke joinstyle="miter"/>'
              '<v:path gradientshapeok="t" o:connecttype="rect"/></v:shapetype>')


def _shape(number: int, row: int, col: int, declare: bool) -> str:
    """A hidden note shape for cell (row, col), 1-based, as Excel writes them."""
    ns = " " + _VML_NS if declare else ""
    anchor = f"{col}, 15, {max(row - 2, 0)}, 10, {col + 2}, 15, {max(row - 2, 0) + 4}, 4"
    return (f'<v:shape id="_x0000_s{number}" type="#_x0000_t202"{ns} style="position:absolute;'
            f'margin-left:59.25pt;margin-top:1.5pt;width:240pt;height:80pt;z-index:{number};'
            f'visibility:hidden" fillcolor="#ffffe1" o:insetmode="auto"><v:fill '
            f'color2="#ffffe1"/><v:shadow on="t" color="black" obscured="t"/><v:path '
            f'o:connecttype="none"/><v:textbox style="mso-direction-alt:auto"><div '
            f'style="text-align:left"></div></v:textbox><x:ClientData ObjectType="Note">'
            f'<x:MoveWithCells/><x:SizeWithCells/><x:Anchor>{anchor}</x:Anchor>'
            f'<x:AutoFill>False</x:AutoFill><x:Row>{row - 1}</x:Row><x:Column>{col - 1}'
            f'</x:Column></x:ClientData></v:shape>')


def new_vml(cells: list[tuple[int, int]], first_id: int = 1025) -> str:
    shapes = "".join(_shape(first_id + i, r, c, False) for i, (r, c) in enumerate(cells))
    return (f'<xml {_VML_NS}><o:shapelayout v:ext="edit"><o:idmap v:ext="edit" data="1"/>'
            f"</o:shapelayout>{_SHAPETYPE}{shapes}</xml>")


def extend_vml(vml: str, cells: list[tuple[int, int]]) -> str:
    """Note shapes for ``cells`` added to an existing VML drawing."""
    used = [int(n) for n in re.findall(r"_x0000_s(\d+)", vml)]
    first = max(used, default=1024) + 1
    declared = all(f'xmlns:{p}=' in vml for p in ("v", "o", "x"))
    shapes = "".join(_shape(first + i, r, c, not declared) for i, (r, c) in enumerate(cells))
    if "_x0000_t202" not in vml:
        shapes = (_SHAPETYPE if declared else _SHAPETYPE.replace(
            "<v:shapetype ", f"<v:shapetype {_VML_NS} ", 1)) + shapes
    end = vml.rfind("</xml>")
    if end < 0:
        raise PartError("VML drawing without its closing </xml>")
    return vml[:end] + shapes + vml[end:]


def add_relationship(rels: str | None, rel_type: str, target: str) -> tuple[str, str]:
    """(the relationships part with a new one, its id)."""
    if rels is None:
        rels = ('<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n<Relationships '
                'xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
                '</Relationships>')
    used = set(re.findall(r'\bId\s*=\s*["\']([^"\']*)["\']', rels))
    n = 1
    while f"rId{n}" in used:
        n += 1
    rid = f"rId{n}"
    at = rels.rfind("</Relationships>")
    if at < 0:
        raise PartError("relationships part without </Relationships>")
    entry = f'<Relationship Id="{rid}" Type="{rel_type}" Target={quoteattr(target)}/>'
    return rels[:at] + entry + rels[at:], rid


def add_content_types(types: str, overrides: dict[str, str], vml: bool) -> str:
    added = ""
    if vml and not re.search(r'<Default\b[^>]*Extension\s*=\s*["\']vml["\']', types, re.I):
        added += f'<Default Extension="vml" ContentType="{CT_VML}"/>'
    for part, content_type in overrides.items():
        added += f'<Override PartName="/{part}" ContentType="{content_type}"/>'
    at = types.rfind("</Types>")
    if at < 0:
        raise PartError("[Content_Types].xml without </Types>")
    return types[:at] + added + types[at:]
