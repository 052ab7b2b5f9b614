"""xlsx/olap.py: the cube functions' cache (a pivot cache with tupleCache="1", ECMA-376
Part 1, 18.10.1.94), read from hand-made XML parts written from the standard's schema,
and from the corpus's Open XML SDK file that Excel saved (checked against the same
part walked independently here with ElementTree)."""

from __future__ import annotations

import zipfile
from xml.etree.ElementTree import fromstring

from corpus_audits import CORPUS
from workbook_gen.xlerror import ExcelError
from workbook_gen.xlsx import read_workbook
from workbook_gen.xlsx.olap import ALL_ITEM, read_cache, read_olap

MAIN = "http://schemas.openxmlformats.org/spreadsheetml/2006/main"
DEFINITION = f"""<pivotCacheDefinition xmlns="{MAIN}" tupleCache="1">
 <cacheSource type="external" connectionId="7"/>
 <cacheFields count="2">
  <cacheField name="[Measures].[MeasuresLevel]" hierarchy="0">
   <sharedItems><s v="[Measures].[Sales]" c="Sales"/></sharedItems></cacheField>
  <cacheField name="[Product].[Cat].[Cat]" hierarchy="1" level="1" mappingCount="1">
   <sharedItems><s v="[Product].[Cat].&amp;[1]" c="Bikes"><x v="0"/></s>
    <s v="[Product].[Cat].&amp;[2]"/></sharedItems></cacheField>
  <cacheField name="[Product].[Cat].[Colour]" memberPropertyField="1">
   <sharedItems><s v="Red"/></sharedItems></cacheField>
 </cacheFields>
 <cacheHierarchies>
  <cacheHierarchy uniqueName="[Measures]"/>
  <cacheHierarchy uniqueName="[Product].[Cat]" allUniqueName="[Product].[Cat].[All]"
                  allCaption="All Products"/>
 </cacheHierarchies>
 <tupleCache>
  <entries>
   <n v="1234.5"><tpls c="2"><tpl fld="0" item="0"/><tpl fld="1" item="0"/></tpls></n>
   <s v="none"><tpls c="1"><tpl fld="1" item="1"/></tpls></s>
   <e v="#N/A"><tpls c="2"><tpl fld="0" item="0"/><tpl hier="1" item="4294967295"/></tpls></e>
   <b v="1"><tpls c="1"><tpl hier="1" item="4294967295"/></tpls></b>
   <m><tpls c="1"><tpl fld="0" item="0"/></tpls></m>
   <n v="oops"><tpls c="1"><tpl fld="1" item="0"/></tpls></n>
   <n v="3"><tpls c="1"><tpl item="0"/></tpls></n>
  </entries>
  <queryCache>
   <query mdx="[Product].[Cat].&amp;[1]"><tpls c="1"><tpl fld="1" item="0"/></tpls></query>
   <query mdx="[Product].[Cat].[All]"><tpls c="1"><tpl hier="1" item="4294967295"/></tpls></query>
   <query mdx="two tpls"><tpls><tpl fld="1" item="0"/></tpls><tpls><tpl fld="1" item="1"/></tpls></query>
   <query><tpls><tpl fld="1" item="1"/></tpls></query>
  </queryCache>
 </tupleCache>
</pivotCacheDefinition>"""

SALES, BIKES, OTHER, ALL = ("f", 0, 0), ("f", 1, 0), ("f", 1, 1), ("h", 1, ALL_ITEM)


def test_fields_hierarchies_queries_and_entries():
    cache = read_cache(fromstring(DEFINITION), "Cube")
    assert cache.connection == "Cube"
    assert [(f.name, f.hierarchy, f.level, f.is_property) for f in cache.fields] == [
        ("[Measures].[MeasuresLevel]", 0, None, False), ("[Product].[Cat].[Cat]", 1, 1, False),
        ("[Product].[Cat].[Colour]", None, None, True)]
    assert cache.fields[1].items == [("[Product].[Cat].&[1]", "Bikes", (0,)),
                                     ("[Product].[Cat].&[2]", None, ())]
    # a query with two tuple sets, or without its mdx, is not kept
    assert cache.queries == {"[Product].[Cat].&[1]": frozenset({BIKES}),
                             "[Product].[Cat].[All]": frozenset({ALL})}
    # <m> (an empty cell), an unreadable number and a tpl naming neither fld nor hier: none
    assert cache.entries == {frozenset({SALES, BIKES}): 1234.5, frozenset({OTHER}): "none",
                             frozenset({SALES, ALL}): ExcelError.NA, frozenset({ALL}): True}


def test_names_and_captions_of_members():
    cache = read_cache(fromstring(DEFINITION), "Cube")
    assert cache.unique_name(BIKES) == "[Product].[Cat].&[1]"
    assert cache.caption(BIKES) == "Bikes" and cache.caption(OTHER) is None
    assert cache.unique_name(ALL) == "[Product].[Cat].[All]"
    assert cache.caption(ALL) == "All Products"
    assert cache.unique_name(("h", 0, ALL_ITEM)) == "[Measures] (All)"
    assert cache.unique_name(("h", 1, 5)) == "[Product].[Cat] item 5"
    assert cache.unique_name(("f", 9, 0)) == "f9:0" and cache.caption(("f", 9, 0)) is None


def test_a_pivot_cache_without_a_tuple_cache_is_none():
    assert read_cache(fromstring(f'<pivotCacheDefinition xmlns="{MAIN}"/>'), "c") is None


class _Package:
    def __init__(self, parts):
        self.parts = parts

    def parse(self, part):
        return fromstring(self.parts[part])


def test_read_olap_follows_the_workbook_and_its_connections():
    ns_r = "http://schemas.openxmlformats.org/officeDocument/2006/relationships"
    root = fromstring(f'<workbook xmlns="{MAIN}" xmlns:r="{ns_r}"><pivotCaches>'
                      '<pivotCache cacheId="1" r:id="rId5"/><pivotCache cacheId="2" r:id="rId6"/>'
                      '<pivotCache cacheId="3" r:id="rId9"/></pivotCaches></workbook>')
    plain = f'<pivotCacheDefinition xmlns="{MAIN}"><cacheSource connectionId="7"/></pivotCacheDefinition>'
    pkg = _Package({"xl/connections.xml": f'<connections xmlns="{MAIN}"><connection id="7" '
                                          'name="Adventure Works"/></connections>',
                    "xl/pc1.xml": DEFINITION, "xl/pc2.xml": plain})
    rels = {"rId1": ("connections", "xl/connections.xml"), "rId5": ("pivotCacheDefinition", "xl/pc1.xml"),
            "rId6": ("pivotCacheDefinition", "xl/pc2.xml")}
    rid = lambda el: el.get(f"{{{ns_r}}}id")
    out = read_olap(pkg, root, rels, rid)
    assert list(out) == ["adventure works"]  # case-folded; the plain pivot cache has none
    assert out["adventure works"].connection == "Adventure Works"
    # without xl/connections.xml there is no cube cache to name
    assert read_olap(pkg, root, {k: v for k, v in rels.items() if k != "rId1"}, rid) == {}


def test_the_corpus_file_excel_saved():
    path = CORPUS / "openxmlsdk__Connection.xlsx"
    with zipfile.ZipFile(path) as z:
        part = fromstring(z.read("xl/pivotCache/pivotCacheDefinition1.xml"))
        name = fromstring(z.read("xl/connections.xml"))[0].get("name")
    tag = lambda el: el.tag.rpartition("}")[2]
    queries = {q.get("mdx"): q for q in part.iter() if tag(q) == "query"}
    fields = [f for f in part.iter() if tag(f) == "cacheField"]
    cache = read_workbook(path).olap[name.casefold()]
    assert len(cache.fields) == len(fields) and len(cache.queries) == len(queries)
    for mdx, q in list(queries.items())[:50] + list(queries.items())[-5:]:
        tpls = [t for t in q.iter() if tag(t) == "tpl"]
        want = frozenset(("f", int(t.get("fld")), int(t.get("item"))) if t.get("fld") is not None
                         else ("h", int(t.get("hier")), int(t.get("item"))) for t in tpls)
        assert cache.queries[mdx] == want, mdx
    # the All member's query: its hierarchy, no field item
    assert cache.queries["[Product].[Product Categories].[All Products]"] == frozenset(
        {("h", 101, ALL_ITEM)})
    fld3 = [s.get("v") for s in fields[3].iter() if tag(s) == "s"]
    assert cache.unique_name(("f", 3, 349)) == fld3[349]
