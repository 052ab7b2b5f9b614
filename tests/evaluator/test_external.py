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

from tests.xlsx.test_reader import MAIN, PKG, REL, _package

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
        "CUBEVALUE: the tuple is not in the file's OLAP cache: ([Measures].[Sales Amount], "
        "[Product].[Product Categories].[All Products])")
    # the summary groups the reasons by what is missing, not by cell
    assert [n for _, n in report.not_checked_reasons()] == [350, 35, 1]
    assert report.not_checked_reasons()[2][0] == (
        "CUBEVALUE: the tuple is not in the file's OLAP cache")
    # the properties are asked by short name; Excel cached #N/A for every one of them
    assert {cells[r][1] for r in properties} == {"#N/A"}
    assert skipped["Sheet1!B3"] == (
        "CUBEMEMBERPROPERTY: no property 'Category' in the file's OLAP cache (it holds "
        "[Product].[Product Categories].[Subcategory].[Category]): "
        "[Product].[Product Categories].[Subcategory].&[26]")


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
    # A1 B1 C1 D1 E1 F1 E2, and B2 from A2's cached value (the consistency rule: a cell
    # that cannot be recomputed holds its cached value for its readers)
    assert report.cells_checked == 8
    skipped = report.not_checked
    assert skipped["S!A2"] == ("CUBEVALUE: the tuple is not in the file's OLAP cache: "
                               "([Measures].[Sales Amount], [Product].[Cat].&[2])")
    assert skipped["S!C2"] == ("CUBEMEMBER: a member expression not in the file's OLAP cache: "
                               "'[Product].[Cat].&[9]'")
    assert skipped["S!D2"] == "CUBEMEMBER: no OLAP cache in the file for connection 'Other'"
    assert skipped["S!F2"] == ("CUBEMEMBERPROPERTY: no property 'Colour' in the file's OLAP "
                               "cache (it holds [Product].[Cat].[Name].[Category]): "
                               "[Product].[Cat].&[1]")
    assert set(skipped) == {"S!A2", "S!C2", "S!D2", "S!F2"}


# ---------------------------------------------------------------- other workbooks' cells

@pytest.mark.parametrize("name,checked", [
    ("npoi__ref-56737.xlsx", 7), ("npoi__ref2-56737.xlsx", 10), ("npoi__xinstall.xlsx", 2)])
def test_external_references_agree_with_excel_from_the_link_cache(name, checked):
    path = CORPUS / name
    if not path.exists():
        pytest.skip("corpus not present")
    report = audit(path)
    # every formula there reads another workbook ([1]Uses!$A$1, [1]Defines!NR_To_A1,
    # [1]!NR_Global_B2, '[1]Params Tab 1'!$B$1): all answered by the cache, as Excel
    # cached them
    assert (report.formula_cells, report.cells_checked, report.mismatches,
            report.not_checked) == (checked, checked, [], {})


def test_external_cells_the_cache_lacks_are_not_checked():
    report = audit(CORPUS / "formulas__test.xlsx")
    cells = _cells(CORPUS / "formulas__test.xlsx", "xl/worksheets/sheet17.xml")
    # B17 =[1]Sheet1!$A$1+1 (cached 3), B18 =[1]Sheet1!$A$1+[1]Sheet1!$A$2 (4), O13 =m
    # (a name [1]Sheet1!$A$1: 2): the link caches A1 = A2 = 2
    assert [cells[r] for r in ("B17", "B18", "O13")] == [
        ("[1]Sheet1!$A$1+1", "3"), ("[1]Sheet1!$A$1+[1]Sheet1!$A$2", "4"), ("m", "2")]
    for ref in ("B17", "B18", "O13"):
        assert f"CORE!{ref}" not in report.not_checked
        assert f"CORE!{ref}" not in {m.cell for m in report.mismatches}
    assert report.not_checked["CORE!P17"] == (
        "external reference: a cell not in the file's cache of MISSING: [2]MISSING!A1")
    assert report.not_checked["CORE!P16"] == (
        "external name: not in the file's cache of MISSING: [2]!A")


def _linked_book(tmp_path: Path, sheet: str) -> Path:
    """A workbook linking to prices.xlsx, whose cached cells are Prices!A1 = 3, A2 = 4,
    B1 = "kg" and the name Rate (Prices!$A$2)."""
    workbook = (f'<workbook xmlns="{MAIN}" xmlns:r="{REL}"><sheets><sheet name="S" sheetId="1" '
                'r:id="rId1"/></sheets><externalReferences><externalReference r:id="rId9"/>'
                "</externalReferences></workbook>")
    link = (f'<externalLink xmlns="{MAIN}" xmlns:r="{REL}"><externalBook r:id="rId1">'
            '<sheetNames><sheetName val="Other"/><sheetName val="Prices"/></sheetNames>'
            "<definedNames><definedName name=\"Rate\" refersTo=\"=Prices!$A$2\"/>"
            "</definedNames><sheetDataSet><sheetData sheetId=\"0\"/><sheetData sheetId=\"1\">"
            '<row r="1"><cell r="A1"><v>3</v></cell><cell r="B1" t="str"><v>kg</v></cell>'
            '</row><row r="2"><cell r="A2"><v>4</v></cell></row></sheetData></sheetDataSet>'
            "</externalBook></externalLink>")
    link_rels = (f'<Relationships xmlns="{PKG}"><Relationship Id="rId1" Type="{REL}/'
                 'externalLinkPath" Target="prices.xlsx" TargetMode="External"/>'
                 "</Relationships>")
    return _package(tmp_path / "linked.xlsx", {"S": sheet}, workbook=workbook,
                    extra={"xl/externalLinks/externalLink1.xml": link,
                           "xl/externalLinks/_rels/externalLink1.xml.rels": link_rels},
                    extra_rels=f'<Relationship Id="rId9" Type="{REL}/externalLink" '
                               'Target="externalLinks/externalLink1.xml"/>')


def test_external_references_on_a_small_cache(tmp_path):
    sheet = ('<row r="1">' + _f("A1", "[1]Prices!A1*2", "6") + _f("B1", "SUM([1]Prices!A1:A2)", "7")
             + _f("C1", "[1]!Rate+[1]Prices!$A$1", "7")
             + _f("D1", "'[1]Prices'!B1&\"!\"", "kg!", "str")
             + _f("E1", "[1]Prices!A1*3", "10")  # Excel would cache 9: a true disagreement
             + '</row><row r="2">'
             + _f("A2", "[1]Prices!A9", "0") + _f("B2", "SUM([1]Prices!A1:A3)", "7")
             + _f("C2", "[1]Missing!A1", "1") + _f("D2", "[2]Prices!A1", "1")
             + _f("E2", "[1]Other!A1", "1") + _f("F2", "[1]!Nothing", "1") + "</row>")
    path = _linked_book(tmp_path, sheet)
    [link] = read_workbook(path).external_links
    assert link.cells == {0: {}, 1: {(1, 1): 3.0, (1, 2): "kg", (2, 1): 4.0}}
    report = audit(path)
    assert [(m.cell, m.cached, m.recomputed) for m in report.mismatches] == [("S!E1", 10.0, 9.0)]
    assert report.cells_checked == 5
    cache = "a cell not in the file's cache of prices.xlsx"
    assert report.not_checked == {
        "S!A2": f"external reference: {cache}: [1]Prices!A9",
        "S!B2": f"external reference: {cache}: [1]Prices!A3",
        "S!C2": "external reference: no such sheet in the file's cache of prices.xlsx: "
                "[1]Missing",
        "S!D2": "external reference: the file lists no such workbook: [2]Prices",
        "S!E2": f"external reference: {cache}: [1]Other!A1",
        "S!F2": "external name: not in the file's cache of prices.xlsx: [1]!Nothing"}


@pytest.mark.parametrize("text", ["=[1]Sheet1!A1", "=[1]Sheet1!$A$1:$B$2+1", "=[12]!Rate",
                                  "=[1]Defines!NR_To_A1", "=SUM([1]Data!A:A)",
                                  "='[1]My sheet'!B2"])
def test_external_references_parse_and_render_back(text):
    tokens = tokenize(text)
    assert "".join(t.text for t in tokens) == text
    assert any(t.text.startswith(("[1]", "[12]", "'[1]")) for t in tokens)
    parse(text)


# --------------------------------------------------------------------------- data tables

def test_data_tables_agree_with_excel():
    if not DATA_TABLES.exists():
        pytest.skip("corpus not present")
    report = audit(DATA_TABLES)
    # 9 formulas and 9 tables (45 cells, each compared with the value Excel cached; a
    # table counts once, at its anchor, as the file stores it); a table whose input cell
    # was deleted is #REF! in every cell (as all five are cached)
    assert (report.formula_cells, report.cells_checked, report.mismatches,
            report.not_checked) == (18, 18, [], {})


def test_a_data_table_cell_is_recomputed_not_read_back(tmp_path):
    # '1D Row'!C5: formula C3 =A1*10 with A1 := B5 (2): 20. Cached as 21 it disagrees.
    path = _tampered(DATA_TABLES, tmp_path / "dt.xlsx", "xl/worksheets/sheet1.xml",
                     '<c r="C5"><v>20</v>', '<c r="C5"><v>21</v>')
    [m] = audit(path).mismatches
    assert (m.cell, m.formula, m.cached, m.recomputed) == ("'1D Row'!C5", "{=TABLE(,A1)}",
                                                           21.0, 20.0)


def test_a_two_dimensional_table_through_a_chain_of_formulas(tmp_path):
    # B1 rate, B2 years; D1 =B1*B2 (between the inputs and the formula), A4 =D1+1:
    # rows 5-6 vary the rate (column input B1), columns B-C the years (row input B2)
    rows = ('<row r="1"><c r="B1"><v>0.5</v></c>' + _f("D1", "B1*B2", "1") + "</row>"
            '<row r="2"><c r="B2"><v>2</v></c></row>'
            '<row r="4">' + _f("A4", "D1+1", "2") + '<c r="B4"><v>10</v></c><c r="C4"><v>20</v>'
            "</c></row>"
            '<row r="5"><c r="A5"><v>1</v></c><c r="B5"><f t="dataTable" ref="B5:C6" dt2D="1" '
            'dtr="1" r1="B2" r2="B1"/><v>11</v></c><c r="C5"><v>21</v></c></row>'
            '<row r="6"><c r="A6"><v>3</v></c><c r="B6"><v>31</v></c><c r="C6"><v>61</v></c>'
            '</row><row r="7">' + _f("A7", "SUM(B5:C6)", "124") + "</row>")
    report = audit(_package(tmp_path / "t.xlsx", {"S": rows}))
    assert report.mismatches == [] and report.not_checked == {}
    assert report.cells_checked == 1 + 3  # the table (4 cells compared), D1, A4, A7


def test_a_data_table_whose_chain_calls_rand_is_not_checked(tmp_path):
    rows = ('<row r="1"><c r="A1"><v>1</v></c></row>'
            '<row r="3">' + _f("C3", "A1*RAND()", "0.5") + "</row>"
            '<row r="4"><c r="B4"><v>2</v></c><c r="C4"><f t="dataTable" ref="C4:C4" '
            'dt2D="0" dtr="0" r1="A1"/><v>1.2</v></c></row>')
    report = audit(_package(tmp_path / "t.xlsx", {"S": rows}))
    assert report.not_checked["S!C4"] == ("data table: its formula reads a cell calling "
                                          "RAND: S!C3")


def test_data_tables_of_each_layout_agree_with_libreoffice(tmp_path, libreoffice):
    """LibreOffice computes <f t="dataTable"> (as MULTIPLE.OPERATIONS): a column-input, a
    row-input and a two-dimensional table through a chain of formulas, written with
    cached 0s, recalculated by LibreOffice; its values, cached in the same workbook, must
    be what the audit recomputes."""
    import openpyxl
    from workbook_gen.engines.libreoffice import recalculate

    def book(values: dict[str, float]) -> str:
        v = lambda ref: values.get(ref, 0)  # noqa: E731
        table = lambda ref, **a: (f'<c r="{ref}"><f t="dataTable" ref="{a["area"]}" '  # noqa
                                  f'dt2D="{a.get("d2", 0)}" dtr="{a.get("dtr", 0)}" '
                                  f'r1="{a["r1"]}"{a.get("r2", "")}/><v>{v(ref)}</v></c>')
        plain = lambda ref: f'<c r="{ref}"><v>{v(ref)}</v></c>'  # noqa: E731
        return ('<row r="1"><c r="B1"><v>0.5</v></c><c r="C1"><v>2</v></c>'
                + _f("D1", "B1*C1", "1") + _f("E1", "D1^2+C1", "3") + "</row>"
                # column input B1 (values A4:A6), formulas D3 (=D1+1) and E3 (=E1)
                + '<row r="3">' + _f("D3", "D1+1", "2") + _f("E3", "E1", "3") + "</row>"
                + '<row r="4"><c r="C4"><v>1</v></c>'
                + table("D4", area="D4:E6", r1="B1") + plain("E4") + "</row>"
                + '<row r="5"><c r="C5"><v>2</v></c>' + plain("D5") + plain("E5") + "</row>"
                + '<row r="6"><c r="C6"><v>-3</v></c>' + plain("D6") + plain("E6") + "</row>"
                # row input C1 (values H8:J8), formula G9 (=E1*10)
                + '<row r="8"><c r="H8"><v>1</v></c><c r="I8"><v>4</v></c><c r="J8"><v>9</v>'
                "</c></row>"
                + '<row r="9">' + _f("G9", "E1*10", "30")
                + table("H9", area="H9:J9", dtr=1, r1="C1") + plain("I9") + plain("J9")
                + "</row>"
                # two-dimensional: row input C1 (L12:M12), column input B1 (K13:K14)
                + '<row r="12">' + _f("K12", "E1-D1", "2") + '<c r="L12"><v>3</v></c>'
                '<c r="M12"><v>5</v></c></row>'
                + '<row r="13"><c r="K13"><v>7</v></c>'
                + table("L13", area="L13:M14", d2=1, dtr=1, r1="C1", r2=' r2="B1"')
                + plain("M13") + "</row>"
                + '<row r="14"><c r="K14"><v>0.25</v></c>' + plain("L14") + plain("M14")
                + "</row>")

    source = _package(tmp_path / "tables.xlsx", {"S": book({})})
    sheet = openpyxl.load_workbook(recalculate(source, tmp_path / "lo"), data_only=True).active
    cells = ["D4", "E4", "D5", "E5", "D6", "E6", "H9", "I9", "J9", "L13", "M13", "L14", "M14"]
    theirs = {ref: sheet[ref].value for ref in cells}
    assert all(isinstance(x, (int, float)) for x in theirs.values()), theirs
    assert theirs["D4"] == 1 * 2 + 1  # (LibreOffice really computed them: not the 0s)
    report = audit(_package(tmp_path / "cached.xlsx", {"S": book(theirs)}))
    assert report.not_checked == {} and report.mismatches == []
    # (a table counts once, at its anchor, as the file stores it; D1 E1 D3 E3 G9 K12)
    assert (report.formula_cells, report.cells_checked) == (3 + 6, 3 + 6)


# ------------------------------------------------------------------------ real-time data

def test_rtd_agrees_with_excel_from_the_volatile_dependencies():
    # A2 =RTD(1223,XL11, 1) cached #N/A; the file keeps the call ("1223": "", "1") = #N/A
    report = audit(CORPUS / "openxmlsdk__VolTypes.xlsx")
    assert (report.formula_cells, report.cells_checked, report.mismatches,
            report.not_checked) == (1, 1, [], {})


def _rtd_book(tmp_path: Path, sheet: str) -> Path:
    """A workbook whose RTD server "quotes.feed" last sent ("", "IBM", "Last") = 143.5 and
    ("", "IBM", "Name") = "IBM Corp"."""
    vol = (f'<volTypes xmlns="{MAIN}"><volType type="realTimeData"><main first="quotes.feed">'
           '<tp><v>143.5</v><stp/><stp>IBM</stp><stp>Last</stp><tr r="A1" s="1"/></tp>'
           '<tp t="s"><v>IBM Corp</v><stp/><stp>IBM</stp><stp>Name</stp><tr r="B1" s="1"/>'
           "</tp></main></volType></volTypes>")
    return _package(tmp_path / "rtd.xlsx", {"S": sheet},
                    extra={"xl/volatileDependencies.xml": vol},
                    extra_rels=f'<Relationship Id="rId7" Type="{REL}/volatileDependencies" '
                               'Target="volatileDependencies.xml"/>')


def test_rtd_on_a_small_cache_and_calls_it_does_not_hold(tmp_path):
    sheet = ('<row r="1">' + _f("A1", 'RTD("quotes.feed",,"IBM","Last")*2', "287")
             + _f("B1", 'RTD("Quotes.Feed","","IBM","Name")', "IBM Corp", "str")
             + _f("C1", 'RTD("quotes.feed",,"IBM","Last")+1', "150")  # Excel: 144.5
             + _f("D1", 'RTD("quotes.feed",,"MSFT","Last")', "410")
             + _f("E1", 'RTD("other.feed",,"IBM","Last")', "1") + "</row>")
    report = audit(_rtd_book(tmp_path, sheet))
    assert [(m.cell, m.cached, m.recomputed) for m in report.mismatches] == [
        ("S!C1", 150.0, 144.5)]
    assert report.not_checked == {
        "S!D1": "RTD: the call is not in the file's real-time data cache: 'quotes.feed', '', "
                "'MSFT', 'Last'",
        "S!E1": "RTD: the call is not in the file's real-time data cache: 'other.feed', '', "
                "'IBM', 'Last'"}
    assert report.cells_checked == 3
