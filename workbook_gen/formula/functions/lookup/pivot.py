"""The lines of one axis of GROUPBY and PIVOTBY (:mod:`.groupby`): the data rows grouped by
the axis's fields, ordered, with subtotals and the grand total where asked.

An axis has ``L`` fields (the columns of ``row_fields`` or ``col_fields``). Each data row
has its key, one label per field; labels are equal as UNIQUE's are (text without case) and
ordered as SORT orders them (numbers, text, FALSE, TRUE, errors, empty).

Ordering (Microsoft's GROUPBY and PIVOTBY pages, "sort_order"): a key is a number, the
fields' columns first and then the values' columns, negative for descending. With the
hierarchy relationship (the default) the groups of each level are ordered within their
parent: by the key naming that field if there is one, by a key naming a value column at
the innermost level (the aggregate of the group), else ascending by label. What Microsoft
Excel cached in formulas__test.xlsx (LOOKUP!AP101:AW105: a value key orders the innermost
column groups, the outer ones stay by label) settles where a value key applies. With the
table relationship (GROUPBY's ``field_relationship`` 1) the groups are the distinct keys,
ordered by the keys as a table's rows are.

Totals (``total_depth``): 0 none, 1 the grand total, 2 also subtotals by the first field, n
subtotals down to the first n-1 fields; negative puts them above what they total. The grand
total reads "Total", or "Grand Total" when there are subtotals; a subtotal line shows its
group's labels and "" for the deeper fields."""

from __future__ import annotations

from dataclasses import dataclass

from workbook_gen.formula.functions.lookup.arrayops import _key, _rank


@dataclass
class Line:
    """One row (or column) of the result's body: its labels, the data rows it covers,
    ``depth`` (how many fields it groups by: L for a group, less for a total) and the data
    rows of its parent group (the grand total's own: it has no parent), shown or not."""

    labels: list
    members: frozenset
    depth: int
    outer: frozenset


@dataclass
class Node:
    label: object
    members: list
    children: list


def _group(keys: list[tuple], members: list[int], level: int) -> list[Node]:
    groups: dict = {}
    for i in members:
        k = _key(keys[i][level])
        if k not in groups:
            groups[k] = Node(keys[i][level], [], [])
        groups[k].members.append(i)
    return list(groups.values())


def _ordered(nodes: list[Node], level: int, depth: int, sort: list[tuple[int, bool]],
             aggregate) -> list[Node]:
    """``nodes`` of one level in order: keys are ``(index, descending)``, index 0-based over
    the fields then the value columns; ``aggregate(members, j)`` a group's value j."""
    out = sorted(nodes, key=lambda n: _rank(n.label))
    steps = []
    for index, desc in sort:
        if index == level:
            steps.append((lambda n: _rank(n.label), desc))
        elif index >= depth and level == depth - 1:
            j = index - depth
            steps.append((lambda n, j=j: _rank(aggregate(n.members, j)), desc))
    for key, desc in reversed(steps):
        out.sort(key=key, reverse=desc)
    return out


def tree(keys: list[tuple], members: list[int], depth: int, sort, aggregate) -> Node:
    root = Node(None, list(members), [])

    def grow(node: Node, level: int):
        if level == depth:
            return
        node.children = _ordered(_group(keys, node.members, level), level, depth, sort,
                                 aggregate)
        for child in node.children:
            grow(child, level + 1)
    grow(root, 0)
    return root


def lines(root: Node, depth: int, total_depth: int) -> list[Line]:
    """The lines of a hierarchy: groups, subtotals (levels 1 .. |total_depth|-1) and the
    grand total, each total below (or, negative, above) what it totals."""
    top, reach = total_depth < 0, abs(total_depth)
    subtotals = reach >= 2 and depth >= 2
    out: list[Line] = []

    def walk(node: Node, prefix: list, level: int, outer: frozenset):
        here, mine = None, frozenset(node.members)
        if level == depth:
            out.append(Line(prefix, mine, depth, outer))
            return
        total_here = (level == 0 and reach >= 1) or (0 < level < reach)
        if total_here:
            label = ("Grand Total" if subtotals else "Total") if level == 0 else None
            labels = ([label] if level == 0 else list(prefix)) + [""] * (depth - max(level, 1))
            here = Line(labels, mine, level, outer)
            if top:
                out.append(here)
        for child in node.children:
            walk(child, prefix + [child.label], level + 1, mine)
        if here is not None and not top:
            out.append(here)
    walk(root, [], 0, frozenset(root.members))
    return out


def table_lines(keys: list[tuple], members: list[int], depth: int, sort, aggregate,
                total_depth: int) -> list[Line]:
    """The table relationship: the distinct keys ordered as rows, then the grand total."""
    groups: dict = {}
    for i in members:
        k = tuple(_key(x) for x in keys[i])
        groups.setdefault(k, (keys[i], []))[1].append(i)
    rows = sorted(groups.values(), key=lambda g: [_rank(x) for x in g[0]])
    steps = []
    for index, desc in sort:
        if index < depth:
            steps.append((lambda g, i=index: _rank(g[0][i]), desc))
        else:
            steps.append((lambda g, j=index - depth: _rank(aggregate(g[1], j)), desc))
    for key, desc in reversed(steps):
        rows.sort(key=key, reverse=desc)
    everything = frozenset(members)
    grand = Line(["Total"] + [""] * (depth - 1), everything, 0, everything)
    body = [Line(list(k), frozenset(m), depth, everything) for k, m in rows]
    if total_depth == 0:
        return body
    return [grand] + body if total_depth < 0 else body + [grand]
