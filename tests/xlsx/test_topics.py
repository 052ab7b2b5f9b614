"""xlsx/topics.py: the real-time data a workbook caches for its RTD calls
(xl/volatileDependencies.xml, ECMA-376 Part 1, 18.17), read as {ProgID: {(server,
topics...): last value}}: numbers, text, booleans and errors by the tp's type, ProgIDs
case-folded, other volTypes ignored. The part is written here into a workbook openpyxl
saved (its relationship and content type added as Excel adds them); and the corpus's
Open XML SDK file that Excel saved with one."""

from __future__ import annotations

import zipfile

import openpyxl

from corpus_audits import CORPUS
from workbook_gen.xlerror import ExcelError
from workbook_gen.xlsx import read_workbook

MAIN = "http://schemas.openxmlformats.org/spreadsheetml/2006/main"
REL = "http://schemas.openxmlformats.org/officeDocument/2006/relationships/volatileDependencies"
TYPE = "application/vnd.openxmlformats-officedocument.spreadsheetml.volatileDependencies+xml"
VOL = f"""<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<volTypes xmlns="{MAIN}">
 <volType type="realTimeData">
  <main first="My.Server">
   <tp><v>42.5</v><stp></stp><stp>IBM</stp><stp>Last</stp><tr r="A1" s="0"/></tp>
   <tp t="s"><v>open</v><stp></stp><stp>IBM</stp><stp>Status</stp><tr r="A2" s="0"/></tp>
   <tp t="b"><v>1</v><stp>srv</stp><stp>flag</stp><tr r="A3" s="0"/></tp>
  </main>
  <main first="other.rtd">
   <tp t="e"><v>#N/A</v><stp></stp><stp>x</stp><tr r="B1" s="0"/></tp>
  </main>
 </volType>
 <volType type="olapFunctions">
  <main first="ignored"><tp><v>1</v><stp>a</stp><tr r="C1" s="0"/></tp></main>
 </volType>
</volTypes>"""


def with_topics(path):
    book = openpyxl.Workbook()
    book.active["A1"] = 1
    book.save(path)
    with zipfile.ZipFile(path) as z:
        parts = {n: z.read(n) for n in z.namelist()}
    rels = parts["xl/_rels/workbook.xml.rels"].decode()
    rels = rels.replace("</Relationships>", f'<Relationship Id="rIdVol" Type="{REL}" '
                                            'Target="volatileDependencies.xml"/></Relationships>')
    types = parts["[Content_Types].xml"].decode()
    types = types.replace("</Types>", '<Override PartName="/xl/volatileDependencies.xml" '
                                      f'ContentType="{TYPE}"/></Types>')
    parts.update({"xl/_rels/workbook.xml.rels": rels.encode(), "[Content_Types].xml": types.encode(),
                  "xl/volatileDependencies.xml": VOL.encode()})
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        for name, data in parts.items():
            z.writestr(name, data)
    return path


def test_topics_by_server_and_strings(tmp_path):
    book = read_workbook(with_topics(tmp_path / "rtd.xlsx"))
    assert book.topics == {
        "my.server": {("", "IBM", "Last"): 42.5, ("", "IBM", "Status"): "open",
                      ("srv", "flag"): True},
        "other.rtd": {("", "x"): ExcelError.NA},
    }


def test_a_file_without_the_part_has_none(tmp_path):
    book = openpyxl.Workbook()
    book.save(tmp_path / "plain.xlsx")
    assert read_workbook(tmp_path / "plain.xlsx").topics == {}


def test_the_corpus_file_excel_saved():
    book = read_workbook(CORPUS / "openxmlsdk__VolTypes.xlsx")
    assert book.topics == {"1223": {("", "1"): ExcelError.NA}}
