"""Cube functions answered from the OLAP cache the file keeps (:mod:`workbook_gen.xlsx.olap`).

Excel asks an OLAP server; the file keeps what the server answered to the sheet's cube
functions. What that cache holds is recomputed from it, never from a cell's own cached
value; what it does not hold raises :class:`Unanswered` (the cell is "not checked" with
the reason):

- CUBEMEMBER(connection, member_expression, [caption]): the member the cache's query for
  ``member_expression`` resolved to (text), or the member a referenced cell holds; its
  value is ``caption`` when given, else the caption of the (last) member, as the cache's
  field items hold it (Microsoft: "returns a member or tuple from the cube ... the
  caption of the last member in the tuple");
- CUBEVALUE(connection, member_expression1, ...): the cache's entry for the tuple of all
  members given (texts, cells holding members, ranges of them);
- CUBEMEMBERPROPERTY(connection, member_expression, property): the member's item in the
  cache's member-property field called ``property`` (its full unique name).

A cube member is a :class:`CubeMember`: text (its caption, what the cell shows) that
carries the members, so that a CUBEVALUE reading the cell knows them.
"""

from __future__ import annotations

from workbook_gen.formula.functions.registry import Unanswered, register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

FUNCTIONS = frozenset({"CUBEMEMBER", "CUBEVALUE", "CUBEMEMBERPROPERTY"})


class CubeMember(str):
    """A cell's cube member (or tuple): its caption as text, its members as ``members``."""

    members: frozenset

    def __new__(cls, caption: str, members: frozenset):
        self = super().__new__(cls, caption)
        self.members = members
        return self

    def __reduce__(self):  # (pickled between the audit's processes)
        return CubeMember, (str(self), self.members)


def _cache(ctx, name: str, connection):
    if isinstance(connection, ExcelError):
        return connection
    cache = ctx.workbook.olap(connection) if isinstance(connection, str) else None
    if cache is None:
        raise Unanswered(f"{name}: no OLAP cache in the file for connection {connection!r}")
    return cache


def _members(name: str, cache, arg) -> frozenset | ExcelError:
    """The members a member-expression argument stands for."""
    values = [v for row in arg.rows for v in row] if isinstance(arg, Range) else [arg]
    out: set = set()
    for v in values:
        if isinstance(v, ExcelError):
            return v
        if isinstance(v, CubeMember):
            out |= v.members
        elif isinstance(v, str) and v in cache.queries:
            out |= cache.queries[v]
        elif isinstance(v, str):
            raise Unanswered(f"{name}: a member expression not in the file's OLAP cache: "
                             f"{v!r}")
        else:
            raise Unanswered(f"{name}: a member expression that is not text: {v!r}")
    return frozenset(out)


def _tuple_text(cache, members) -> str:
    return "(" + ", ".join(sorted(cache.unique_name(m) for m in members)) + ")"


def _member_args(ctx, name: str, connection, member, extra):
    """(cache, members) for a function of a connection, a member and one more argument,
    or the first error among the three, in argument order."""
    cache = _cache(ctx, name, connection)
    if isinstance(cache, ExcelError):
        return cache
    members = _members(name, cache, member)
    if isinstance(members, ExcelError):
        return members
    if isinstance(extra, ExcelError):
        return extra
    return cache, members


@register("CUBEMEMBER", 2, 3, ("scalar", "range", "scalar"))
def _cubemember(ctx, connection, member, caption=None):
    got = _member_args(ctx, "CUBEMEMBER", connection, member, caption)
    if isinstance(got, ExcelError):
        return got
    cache, members = got
    if isinstance(caption, str) and caption:
        return CubeMember(caption, members)
    last = member
    if isinstance(member, Range):
        last = member.rows[-1][-1]
    if isinstance(last, CubeMember):
        return CubeMember(str(last), members)
    own = cache.queries.get(last) if isinstance(last, str) else None
    shown = cache.caption(sorted(own)[-1]) if own is not None and len(own) == 1 else None
    if shown is None:
        raise Unanswered(f"CUBEMEMBER: no caption in the file's OLAP cache: "
                         f"{_tuple_text(cache, members)}")
    return CubeMember(shown, members)


@register("CUBEVALUE", 1, -1, ("scalar", "range"))
def _cubevalue(ctx, connection, *members):
    cache = _cache(ctx, "CUBEVALUE", connection)
    if isinstance(cache, ExcelError):
        return cache
    tuple_: set = set()
    for arg in members:
        found = _members("CUBEVALUE", cache, arg)
        if isinstance(found, ExcelError):
            return found
        tuple_ |= found
    key = frozenset(tuple_)
    if key not in cache.entries:
        raise Unanswered(f"CUBEVALUE: the tuple is not in the file's OLAP cache: "
                         f"{_tuple_text(cache, key)}")
    return cache.entries[key]


@register("CUBEMEMBERPROPERTY", 3, 3, ("scalar", "range", "scalar"))
def _cubememberproperty(ctx, connection, member, prop):
    got = _member_args(ctx, "CUBEMEMBERPROPERTY", connection, member, prop)
    if isinstance(got, ExcelError):
        return got
    cache, members = got
    if len(members) != 1 or next(iter(members))[0] != "f":
        raise Unanswered("CUBEMEMBERPROPERTY: the member is not one item of the file's "
                         f"OLAP cache: {_tuple_text(cache, members)}")
    _, index, item = next(iter(members))
    level = cache.fields[index]
    holders = [f for f in cache.fields
               if f.is_property and (f.hierarchy, f.level) == (level.hierarchy, level.level)]
    named = [k for k, f in enumerate(holders) if f.name.casefold() == str(prop).casefold()]
    props = level.items[item][2]
    if not named or named[0] >= len(props) or props[named[0]] >= len(holders[named[0]].items):
        held = ", ".join(f.name for f in holders) or "none"
        raise Unanswered(f"CUBEMEMBERPROPERTY: no property {str(prop)!r} in the file's OLAP "
                         f"cache (it holds {held}): {cache.unique_name(('f', index, item))}")
    return holders[named[0]].items[props[named[0]]][0]
