"""Values a workbook reads from outside itself, checked against what the file caches of them.

- cube functions (CUBEMEMBER, CUBEVALUE, CUBEMEMBERPROPERTY) against the OLAP tuple cache
  Excel keeps for them (a pivot cache with ``tupleCache="1"``);
- references to other workbooks (``[1]Sheet!A1``, ``[1]!Name``) against the cells the
  externalLink part caches;
- data tables (``<f t="dataTable">``) recomputed with their input cells replaced.

The expected values are Excel's own: the values it cached in the corpus files (read from
the files here), and for the small workbooks built here, values Excel's documented
semantics give. Tampered copies show that a recomputed value comes from the file's cache
(or the table's formula), never from the cell's own cached value.
"""

from __future__ import annotations

import re
import zipfile
from pathlib import Path

import pytest

from workbook_gen.auditor import audit
from workbook_gen.formula.parser import parse
from workbook_gen.formula.tokenizer import tokenize
from workbook_gen.xlsx import read_workbook

from test_xlsx_reader import MAIN, PKG, REL, _package

CORPUS = Path("/work/shared/corpus/xlsx")
CONNECTION = CORPUS / "openxmlsdk__Connection.xlsx"
DATA_TABLES = CORPUS / "closedxml__DataTableFormula-Excel-Input.xlsx"


def _tampered(src: Path, dst: Path, part: str, old: str, new: str) -> Path:
    """A copy of ``src`` with ``old`` replaced once by ``new`` in ``part``."""
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        for info in zin.infolist():
            data = zin.read(info.filename)
            if info.filename == part:
                text = data.decode("utf-8")
                assert text.count(old) >= 1, (part, old)
                data = text.replace(old, new, 1).encode("utf-8")
            zout.writestr(info, data)
    return dst


def _cells(path: Path, sheet_part: str) -> dict[str, tuple[str, str]]:
    """{ref: (formula text, cached value)} of a sheet's formula cells, read here."""
    with zipfile.ZipFile(path) as z:
        xml = z.read(sheet_part).decode("utf-8")
    out = {}
    for ref, body in re.findall(r'<c r="([A-Z]+\d+)"[^>]*>(.*?)</c>', xml):
        f = re.search(r"<f[^>]*>([^<]*)</f>|<f[^>]*/>", body)
        v = re.search(r"<v>([^<]*)</v>", body)
        if f:
            out[ref] = (f.group(1) or "", v.group(1) if v else "")
    return out


@pytest.fixture(scope="module")
def connection_report():
    if not CONNECTION.exists():
        pytest.skip("corpus not present")
    return audit(CONNECTION)


# ------------------------------------------------------------------------- cube functions

def test_cube_members_and_values_agree_with_excel_from_the_olap_cache(connection_report):
    report = connection_report
    cells = _cells(CONNECTION, "xl/worksheets/sheet1.xml")
    members = [r for r, (f, _) in cells.items() if f.startswith("CUBEMEMBER(")]
    values = [r for r, (f, _) in cells.items() if r[0] == "D" and not f.startswith("CUBEM")]
    properties = [r for r, (f, _) in cells.items() if f.startswith("CUBEMEMBERPROPERTY(")]
    assert (len(members), len(values), len(properties)) == (391, 390, 385)
    assert report.formula_cells == 1166
    assert report.mismatches == []
    skipped = report.not_checked
    # every member and every value the cache answers is checked
    assert not any(f"Sheet1!{r}" in skipped for r in members)
    assert [r for r in values if f"Sheet1!{r}" in skipped] == ["D391"]
    assert report.cells_checked == len(members) + len(values) - 1
    # D391 asks for (Sales Amount, All Products): the cache has no such tuple, and Excel
    # cached #N/A there, which says nothing either way
    assert cells["D391"][1] == "#N/A"
    assert skipped["Sheet1!D391"] == (
        "CUBEVALUE: the tuple ([Measures].[Sales Amount], [Product].[Product Categories]."
        "[All Products]) is not in the file's OLAP cache")
    # the properties are asked by short name; Excel cached #N/A for every one of them
    assert {cells[r][1] for r in properties} == {"#N/A"}
    assert skipped["Sheet1!B3"].startswith(
        "CUBEMEMBERPROPERTY: the file's OLAP cache holds no property 'Category' of "
        "[Product].[Product Categories].[Subcategory].&[26] (it holds: [Product].[Product "
        "Categories].[Subcategory].[Category])")


def test_a_cube_value_is_read_from_the_tuple_cache_not_from_the_cell(tmp_path):
    # D2 = CUBEVALUE(conn, $A2, D$1), cached 1272057.8877997734; the tuple cache's entry
    # for (Sales Amount, Accessories) changed to 7: D2 must now disagree, recomputed 7
    path = _tampered(CONNECTION, tmp_path / "c.xlsx", "xl/pivotCache/pivotCacheDefinition1.xml",
                     '<n v="1272057.8877997734"><tpls c="2"><tpl fld="0" item="0"/>'
                     '<tpl fld="1" item="0"/>',
                     '<n v="7"><tpls c="2"><tpl fld="0" item="0"/><tpl fld="1" item="0"/>')
    [m] = audit(path).mismatches
    assert (m.cell, m.cached, m.recomputed) == ("Sheet1!D2", 1272057.8877997734, 7.0)


def test_a_cube_member_caption_is_read_from_the_cache_not_from_the_cell(tmp_path):
    path = _tampered(CONNECTION, tmp_path / "c.xlsx", "xl/pivotCache/pivotCacheDefinition1.xml",
                     'c="Accessories"', 'c="Accessoires"')
    [m] = audit(path).mismatches
    assert (m.cell, m.cached, m.recomputed) == ("Sheet1!A2", "Accessories", "Accessoires")


def _olap_book(tmp_path: Path, sheet: str) -> Path:
    """A workbook with connection "Sales" and its cube-function cache: members Sales
    Amount (field 0) and Bikes, Clothing (field 1); tuple (Sales Amount, Bikes) = 120;
    Bikes' Category property (field 2) = "Cycling"."""
    pivot = (f'<pivotCacheDefinition xmlns="{MAIN}" tupleCache="1" recordCount="0">'
             '<cacheSource type="external" connectionId="4"/><cacheFields count="3">'
             '<cacheField name="[Measures].[MeasuresLevel]" hierarchy="0"><sharedItems>'
             '<s v="[Measures].[Sales Amount]" c="Sales Amount"/></sharedItems></cacheField>'
             '<cacheField name="[Product].[Cat].[Name]" hierarchy="1" level="1" '
             'mappingCount="1"><sharedItems><s v="[Product].[Cat].&amp;[1]" c="Bikes" cp="1">'
             '<x v="0"/></s><s v="[Product].[Cat].&amp;[2]" c="Clothing" cp="1"><x v="0"/></s>'
             '</sharedItems></cacheField>'
             '<cacheField name="[Product].[Cat].[Name].[Category]" hierarchy="1" level="1" '
             'memberPropertyField="1"><sharedItems><s v="Cycling"/></sharedItems></cacheField>'
             '</cacheFields><cacheHierarchies count="2"><cacheHierarchy uniqueName="[Measures]"/>'
             '<cacheHierarchy uniqueName="[Product].[Cat]" allUniqueName="[Product].[Cat].[All]"/>'
             '</cacheHierarchies><tupleCache><entries count="1"><n v="120"><tpls c="2">'
             '<tpl fld="0" item="0"/><tpl fld="1" item="0"/></tpls></n></entries>'
             '<queryCache count="3"><query mdx="[Measures].[Sales Amount]"><tpls c="1">'
             '<tpl fld="0" item="0"/></tpls></query><query mdx="[Product].[Cat].&amp;[1]">'
             '<tpls c="1"><tpl fld="1" item="0"/></tpls></query>'
             '<query mdx="[Product].[Cat].&amp;[2]"><tpls c="1"><tpl fld="1" item="1"/></tpls>'
             '</query></queryCache></tupleCache></pivotCacheDefinition>')
    connections = (f'<connections xmlns="{MAIN}"><connection id="4" name="Sales" type="5"/>'
                   "</connections>")
    workbook = (f'<workbook xmlns="{MAIN}" xmlns:r="{REL}"><sheets><sheet name="S" sheetId="1" '
                'r:id="rId1"/></sheets><pivotCaches><pivotCache cacheId="1" r:id="rId8"/>'
                "</pivotCaches></workbook>")
    rels = (f'<Relationship Id="rId8" Type="{REL}/pivotCacheDefinition" '
            'Target="pivotCache/pivotCacheDefinition1.xml"/>'
            f'<Relationship Id="rId9" Type="{REL}/connections" Target="connections.xml"/>')
    return _package(tmp_path / "olap.xlsx", {"S": sheet}, workbook=workbook, extra_rels=rels,
                    extra={"xl/pivotCache/pivotCacheDefinition1.xml": pivot,
                           "xl/connections.xml": connections})


def _f(ref: str, formula: str, value: str, t: str = "") -> str:
    kind = f' t="{t}"' if t else ""
    return f'<c r="{ref}"{kind}><f>{formula.replace("&", "&amp;")}</f><v>{value}</v></c>'


def test_cube_functions_on_a_small_cache_and_what_it_does_not_hold(tmp_path):
    sheet = ('<row r="1">'
             + _f("A1", 'CUBEMEMBER("Sales","[Measures].[Sales Amount]")', "Sales Amount", "str")
             + _f("B1", 'CUBEMEMBER("Sales","[Product].[Cat].&[1]")', "Bikes", "str")
             + _f("C1", 'CUBEVALUE("Sales",A1,B1)', "120")
             + _f("D1", 'CUBEVALUE("Sales","[Measures].[Sales Amount]","[Product].[Cat].&[1]")',
                  "120")
             + _f("E1", "C1*2", "240")
             + _f("F1", 'CUBEMEMBER("Sales","[Product].[Cat].&[2]","Togs")', "Togs", "str")
             + "</row><row r=\"2\">"
             + _f("A2", 'CUBEVALUE("Sales",A1,F1)', "75")  # not in the cache
             + _f("B2", "A2+1", "76")
             + _f("C2", 'CUBEMEMBER("Sales","[Product].[Cat].&[9]")', "Shoes", "str")
             + _f("D2", 'CUBEMEMBER("Other","[Measures].[Sales Amount]")', "Sales Amount",
                  "str")
             + _f("E2", 'CUBEMEMBERPROPERTY("Sales","[Product].[Cat].&[1]",'
                  '"[Product].[Cat].[Name].[Category]")', "Cycling", "str")
             + _f("F2", 'CUBEMEMBERPROPERTY("Sales","[Product].[Cat].&[1]","Colour")', "Red",
                  "str")
             + "</row>")
    report = audit(_olap_book(tmp_path, sheet))
    assert report.mismatches == []
    assert report.cells_checked == 7  # A1 B1 C1 D1 E1 F1 E2
    skipped = report.not_checked
    assert skipped["S!A2"] == ("CUBEVALUE: the tuple ([Measures].[Sales Amount], "
                               "[Product].[Cat].&[2]) is not in the file's OLAP cache")
    assert skipped["S!B2"] == f"depends on S!A2: {skipped['S!A2']}"
    assert skipped["S!C2"] == ("CUBEMEMBER: the member expression '[Product].[Cat].&[9]' is "
                               "not in the file's OLAP cache")
    assert skipped["S!D2"] == "CUBEMEMBER: the file keeps no OLAP cache for connection 'Other'"
    assert skipped["S!F2"].startswith("CUBEMEMBERPROPERTY: the file's OLAP cache holds no "
                                      "property 'Colour' of [Product].[Cat].&[1]")
    assert set(skipped) == {"S!A2", "S!B2", "S!C2", "S!D2", "S!F2"}
