"""auditor/notes.py: the parts an annotated copy adds or extends, text in, text out.

The parts are those XlsxWriter writes (a cell format, a comment by another author and its
VML shape); after editing them the package is read back by openpyxl, the reference for
what a reader makes of the fills, formats and comments. Counts and ids are checked
against ElementTree parsing the edited parts."""

from __future__ import annotations

import re
import zipfile
from xml.etree import ElementTree

import openpyxl
import pytest
import xlsxwriter

from workbook_gen.auditor.notes import (AUTHOR, CT_COMMENTS, FILLS, NEW_STYLES, NS_MAIN,
                                        REL_COMMENTS, PartError, add_content_types, add_fills,
                                        add_relationship, extend_comments, extend_vml,
                                        new_comments, new_vml)

SHEET = "xl/worksheets/sheet1.xml"
M = "{%s}" % NS_MAIN


def _book(path, comment: bool):
    book = xlsxwriter.Workbook(str(path))
    s = book.add_worksheet("S")
    s.write_number("A1", 1, book.add_format({"bold": True}))
    s.write_string("B2", "x")
    if comment:
        s.write_comment("B2", "theirs", {"author": "Ann"})
    s.write_number("C3", 5)
    book.close()
    with zipfile.ZipFile(path) as z:
        return {n: z.read(n).decode() for n in z.namelist()}


def _save(path, parts):
    with zipfile.ZipFile(path, "w") as z:
        for name, text in parts.items():
            z.writestr(name, text)
    return openpyxl.load_workbook(path)["S"]


def _style(sheet_xml: str, ref: str, index: int) -> str:
    return re.sub(rf'<c r="{ref}"( s="\d+")?', f'<c r="{ref}" s="{index}"', sheet_xml)


@pytest.fixture(scope="module")
def extended(tmp_path_factory):
    folder = tmp_path_factory.mktemp("notes")
    parts = _book(folder / "with.xlsx", comment=True)
    styles, index = add_fills(parts["xl/styles.xml"], {0, 1})
    parts["xl/styles.xml"] = styles
    parts[SHEET] = _style(_style(parts[SHEET], "C3", index[(0, "disagree")]),
                          "A1", index[(1, "finding")])
    parts["xl/comments1.xml"], fresh = extend_comments(
        parts["xl/comments1.xml"], {"B2": "cached 1, recomputed 2 & <3>", "C3": "new note"})
    parts["xl/drawings/vmlDrawing1.vml"] = extend_vml(parts["xl/drawings/vmlDrawing1.vml"],
                                                      [(3, 3)])
    return parts, index, fresh, _save(folder / "annotated.xlsx", parts)


def test_fills_and_formats_read_back_by_openpyxl(extended):
    parts, index, _, ws = extended
    assert ws["C3"].fill.fill_type == "solid" and ws["C3"].fill.fgColor.rgb == FILLS["disagree"]
    assert ws["A1"].fill.fgColor.rgb == FILLS["finding"] and ws["A1"].font.b  # bold kept
    assert not ws["B2"].fill.fill_type
    root = ElementTree.fromstring(parts["xl/styles.xml"])
    fills, xfs = root.find(M + "fills"), root.find(M + "cellXfs")
    assert int(fills.get("count")) == len(fills) == 4      # none, gray125, and our two
    assert int(xfs.get("count")) == len(xfs) == 2 + 4       # two formats, two copies each
    assert sorted(index.values()) == [2, 3, 4, 5]
    assert xfs[index[(1, "disagree")]].get("fillId") == "2"
    assert xfs[index[(1, "disagree")]].get("applyFill") == "1"


def test_comments_appended_and_added_read_back_by_openpyxl(extended):
    parts, _, fresh, ws = extended
    assert fresh == ["C3"]
    b2 = ws["B2"].comment.text
    assert "theirs" in b2 and b2.endswith(f"{AUTHOR}:\ncached 1, recomputed 2 & <3>")
    assert ws["C3"].comment.text == f"{AUTHOR}:\nnew note"
    assert ws["C3"].comment.author == AUTHOR
    vml = parts["xl/drawings/vmlDrawing1.vml"]
    ids = re.findall(r'id="_x0000_s(\d+)"', vml)
    assert len(ids) == len(set(ids)) == 2                  # the new shape's id is fresh
    assert "<x:Row>2</x:Row><x:Column>2</x:Column>" in vml  # C3, 0-based


def test_a_workbook_without_comments_gets_its_parts(tmp_path):
    parts = _book(tmp_path / "plain.xlsx", comment=False)
    assert "xl/worksheets/_rels/sheet1.xml.rels" not in parts
    rels, rid = add_relationship(None, REL_COMMENTS, "../comments1.xml")
    parts["xl/worksheets/_rels/sheet1.xml.rels"] = rels
    parts["xl/comments1.xml"] = new_comments({"A1": "checked", "C3": "x < y"})
    parts["[Content_Types].xml"] = add_content_types(
        parts["[Content_Types].xml"], {"xl/comments1.xml": CT_COMMENTS}, vml=True)
    ws = _save(tmp_path / "noted.xlsx", parts)
    assert rid == "rId1"
    assert ws["A1"].comment.text == f"{AUTHOR}:\nchecked"
    assert ws["C3"].comment.text == f"{AUTHOR}:\nx < y"
    vml = new_vml([(1, 1), (3, 3)])
    ElementTree.fromstring(vml)  # well-formed
    assert re.findall(r'id="_x0000_s(\d+)"', vml) == ["1025", "1026"]


def test_relationships_content_types_and_refusals():
    rels, _ = add_relationship(None, "t", "a.xml")
    rels, rid = add_relationship(rels.replace('rId1"', 'rId3"'), "t", 'b"q.xml')
    assert rid == "rId1"
    root = ElementTree.fromstring(rels)
    assert [r.get("Target") for r in root] == ["a.xml", 'b"q.xml']
    types = ('<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
             '<Default Extension="VML" ContentType="x"/></Types>')
    assert add_content_types(types, {}, vml=True) == types  # (case-insensitive, once)
    assert add_content_types(types, {"p.xml": "c"}, vml=False).count("<Override") == 1
    styles, index = add_fills(NEW_STYLES, {0})
    assert len(ElementTree.fromstring(styles).find(M + "fills")) == 4 and index[(0, "finding")] == 2
    no_fills = re.sub(r"<fills.*?</fills>", "", NEW_STYLES)
    fills = ElementTree.fromstring(add_fills(no_fills, set())[0]).find(M + "fills")
    assert int(fills.get("count")) == len(fills) == 4
    with pytest.raises(PartError):
        add_fills(re.sub(r"<cellXfs.*?</cellXfs>", "", NEW_STYLES), {0})
    with pytest.raises(PartError):
        extend_vml("<xml>", [(1, 1)])
    with pytest.raises(PartError):
        extend_comments("<comments/>", {"A1": "x"})
    with pytest.raises(PartError):
        add_relationship("<Relationships/>", "t", "a")
    with pytest.raises(PartError):
        add_content_types("<Types/>", {}, vml=True)
