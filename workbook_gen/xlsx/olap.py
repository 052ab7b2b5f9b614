"""The OLAP cache a workbook keeps for its cube functions (CUBEMEMBER, CUBEVALUE, ...).

Excel caches what an OLAP server answered to the cube functions of a sheet in a pivot
cache marked ``tupleCache="1"`` (ECMA-376 Part 1, 18.10.1.94; [MS-XLSB] 2.2.5.2.11:
"Relevant information retrieved from the OLAP server as a result of using cube
functions in a sheet is cached in the tuple cache"), tied to its connection
(xl/connections.xml) by ``cacheSource connectionId``:

- ``cacheFields``: each level's members (``<s v="unique name" c="caption">``, with
  ``<x v>`` indexes into the member-property fields that follow ``mappingCount``);
- ``tupleCache/queryCache``: each member expression a formula sent (``query mdx``) and
  the members it resolved to (``tpl fld item``, or ``tpl hier item`` for a hierarchy's
  member that is no field item, such as its All member);
- ``tupleCache/entries``: the value of each tuple asked for (``<n v>``, ``<s v>``,
  ``<e v>``, ``<b v>``; ``<m>`` for an empty cell), keyed by its members.

A member is ``("f", field, item)`` or ``("h", hierarchy, item)``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from xml.etree.ElementTree import Element

from workbook_gen.xlerror import ExcelError

Member = tuple[str, int, int]
ALL_ITEM = 4294967295  # tpl item of a hierarchy's All member (no field item)


@dataclass(slots=True)
class OlapField:
    name: str              # the level's (or member property's) unique name
    hierarchy: int | None
    level: int | None
    is_property: bool      # memberPropertyField: values of a member property of a level
    items: list[tuple[str, str | None, tuple[int, ...]]]  # (value, caption, property items)


@dataclass
class OlapCache:
    """One connection's cube-function cache."""

    connection: str
    fields: list[OlapField] = field(default_factory=list)
    hierarchies: list[dict[str, str]] = field(default_factory=list)  # cacheHierarchy attrs
    queries: dict[str, frozenset[Member]] = field(default_factory=dict)  # mdx -> members
    entries: dict[frozenset[Member], object] = field(default_factory=dict)  # tuple -> value

    def unique_name(self, member: Member) -> str:
        kind, index, item = member
        if kind == "f" and index < len(self.fields) and item < len(self.fields[index].items):
            return self.fields[index].items[item][0]
        if kind == "h" and index < len(self.hierarchies):
            h = self.hierarchies[index]
            if item == ALL_ITEM:
                return h.get("allUniqueName") or f"{h.get('uniqueName', '?')} (All)"
            return f"{h.get('uniqueName', '?')} item {item}"
        return f"{kind}{index}:{item}"

    def caption(self, member: Member) -> str | None:
        """The member's caption as the cache holds it, or None."""
        kind, index, item = member
        if kind == "f" and index < len(self.fields) and item < len(self.fields[index].items):
            return self.fields[index].items[item][1]
        if kind == "h" and item == ALL_ITEM and index < len(self.hierarchies):
            return self.hierarchies[index].get("allCaption")
        return None


def _local(el: Element) -> str:
    return el.tag.rpartition("}")[2]


def _kids(el: Element | None, name: str) -> list[Element]:
    return [] if el is None else [c for c in el if _local(c) == name]


def _kid(el: Element | None, name: str) -> Element | None:
    return next(iter(_kids(el, name)), None)


def _int(text: str | None) -> int | None:
    return int(text) if text is not None and text.isdigit() else None


def _members(tpls: Element) -> frozenset[Member] | None:
    out = []
    for tpl in _kids(tpls, "tpl"):
        item = _int(tpl.get("item"))
        fld, hier = _int(tpl.get("fld")), _int(tpl.get("hier"))
        if item is None or (fld is None and hier is None):
            return None
        out.append(("f", fld, item) if fld is not None else ("h", hier, item))
    return frozenset(out) if out else None


def _value(el: Element):
    kind, v = _local(el), el.get("v")
    if v is None:
        return None
    if kind == "n":
        try:
            return float(v)
        except ValueError:
            return None
    if kind == "s":
        return v
    if kind == "b":
        return v in ("1", "true")
    if kind == "e":
        return ExcelError.from_text(v)
    return None


def read_cache(root: Element, connection: str) -> OlapCache | None:
    """The cube-function cache of a pivot cache definition, or None if it keeps none."""
    tuples = _kid(root, "tupleCache")
    if tuples is None:
        return None
    cache = OlapCache(connection)
    for f in _kids(_kid(root, "cacheFields"), "cacheField"):
        items = []
        for s in _kids(_kid(f, "sharedItems"), "s"):
            props = tuple(x for x in (_int(x.get("v")) for x in _kids(s, "x")) if x is not None)
            items.append((s.get("v", ""), s.get("c"), props))
        cache.fields.append(OlapField(f.get("name", ""), _int(f.get("hierarchy")),
                                      _int(f.get("level")),
                                      f.get("memberPropertyField") in ("1", "true"), items))
    cache.hierarchies = [dict(h.attrib) for h in
                         _kids(_kid(root, "cacheHierarchies"), "cacheHierarchy")]
    for q in _kids(_kid(tuples, "queryCache"), "query"):
        tpls = _kids(q, "tpls")
        members = _members(tpls[0]) if len(tpls) == 1 else None
        if q.get("mdx") is not None and members is not None:
            cache.queries[q.get("mdx", "")] = members
    for entry in list(_kid(tuples, "entries") or ()):
        tpls = _kids(entry, "tpls")
        members = _members(tpls[0]) if len(tpls) == 1 else None
        value = _value(entry)
        if members is not None and value is not None:
            cache.entries[members] = value
    return cache


def read_olap(pkg, root: Element, rels: dict, rid) -> dict[str, OlapCache]:
    """{connection name (case-folded): its cube-function cache} of a workbook, from the
    pivot caches that xl/workbook.xml (``root``) lists and xl/connections.xml."""
    caches = _kids(_kid(root, "pivotCaches"), "pivotCache")
    if not caches:
        return {}
    part = next((p for k, p in rels.values() if k == "connections" and p
                 and not p.startswith("external:")), None)
    if part is None:
        return {}
    names = {c.get("id"): c.get("name", "") for c in _kids(pkg.parse(part), "connection")}
    out: dict[str, OlapCache] = {}
    for el in caches:
        target = rels.get(rid(el), (None, None))[1]
        if target is None or target.startswith("external:"):
            continue
        definition = pkg.parse(target)
        if definition.get("tupleCache") not in ("1", "true"):
            continue
        source = _kid(definition, "cacheSource")
        name = names.get(source.get("connectionId") if source is not None else None)
        if name is None:
            continue
        cache = read_cache(definition, name)
        if cache is not None:
            out[name.casefold()] = cache
    return out


__all__ = ["ALL_ITEM", "Member", "OlapCache", "OlapField", "read_cache", "read_olap"]
