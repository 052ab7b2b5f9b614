"""formula/functions/lookup/pivot.py: the lines of one axis of GROUPBY/PIVOTBY, on small
hand-derived data, by Microsoft's GROUPBY and PIVOTBY pages (support.microsoft.com:
total_depth 0 no totals, 1 grand totals, 2 grand and subtotals, negative at the top;
sort_order a column number, negative for descending; field_relationship 0 hierarchy, 1
table), Excel's sort order ("Sort data in a range or table": numbers, text, FALSE, TRUE,
errors, blanks; text without case) and UNIQUE's equality (text without case), and what
Excel cached in formulas__test.xlsx for the labels ("Total", "Grand Total" with
subtotals) and for a value key (it orders the innermost groups only)."""

from __future__ import annotations

import pytest

from workbook_gen.formula.functions.lookup.pivot import Line, lines, table_lines, tree
from workbook_gen.xlerror import ExcelError

KEYS = [("East", "Pen"), ("West", "Pen"), ("east", "Ink"), ("West", "Ink"), ("East", "Pen")]
VALUES = [1.0, 2.0, 3.0, 4.0, 5.0]
ALL = list(range(len(KEYS)))


def total(members, j=0):
    return sum(VALUES[i] for i in members)


def labels(ls):
    return [ln.labels for ln in ls]


def test_groups_text_without_case_keeping_the_first_label():
    root = tree(KEYS, ALL, 2, [], total)
    assert [n.label for n in root.children] == ["East", "West"]
    east = root.children[0]
    assert east.members == [0, 2, 4]
    assert [(n.label, n.members) for n in east.children] == [("Ink", [2]), ("Pen", [0, 4])]
    assert root.members == ALL


@pytest.mark.parametrize("depth, expected", [
    (0, [["East", "Ink"], ["East", "Pen"], ["West", "Ink"], ["West", "Pen"]]),
    (1, [["East", "Ink"], ["East", "Pen"], ["West", "Ink"], ["West", "Pen"], ["Total", ""]]),
    (2, [["East", "Ink"], ["East", "Pen"], ["East", ""], ["West", "Ink"], ["West", "Pen"],
         ["West", ""], ["Grand Total", ""]]),
    (-1, [["Total", ""], ["East", "Ink"], ["East", "Pen"], ["West", "Ink"], ["West", "Pen"]]),
    (-2, [["Grand Total", ""], ["East", ""], ["East", "Ink"], ["East", "Pen"], ["West", ""],
          ["West", "Ink"], ["West", "Pen"]]),
])
def test_total_depth(depth, expected):
    assert labels(lines(tree(KEYS, ALL, 2, [], total), 2, depth)) == expected


def test_lines_carry_their_members_depth_and_parent():
    got = lines(tree(KEYS, ALL, 2, [], total), 2, 2)
    by = {tuple(ln.labels): ln for ln in got}
    everything = frozenset(ALL)
    assert by[("East", "Pen")] == Line(["East", "Pen"], frozenset({0, 4}), 2,
                                       frozenset({0, 2, 4}))
    assert by[("East", "")] == Line(["East", ""], frozenset({0, 2, 4}), 1, everything)
    assert by[("Grand Total", "")] == Line(["Grand Total", ""], everything, 0, everything)
    # each group's members, summed, are the totals' (the totals hold what they total)
    assert sum(total(ln.members) for ln in got if ln.depth == 2) == total(ALL) == 15.0


def test_one_field_has_no_subtotals():
    keys = [(k[0],) for k in KEYS]
    assert labels(lines(tree(keys, ALL, 1, [], total), 1, 2)) == [["East"], ["West"],
                                                                   ["Total"]]


def test_sort_keys():
    # a field's key, descending: -1
    got = lines(tree(KEYS, ALL, 2, [(0, True)], total), 2, 0)
    assert labels(got) == [["West", "Ink"], ["West", "Pen"], ["East", "Ink"], ["East", "Pen"]]
    got = lines(tree(KEYS, ALL, 2, [(1, True)], total), 2, 0)
    assert labels(got) == [["East", "Pen"], ["East", "Ink"], ["West", "Pen"], ["West", "Ink"]]
    # a value key (column 3 = the first value column) orders the innermost groups by their
    # aggregate, within their parent; the outer ones stay by label
    got = lines(tree(KEYS, ALL, 2, [(2, True)], total), 2, 0)
    assert labels(got) == [["East", "Pen"], ["East", "Ink"], ["West", "Ink"], ["West", "Pen"]]
    got = lines(tree(KEYS, ALL, 2, [(2, False)], total), 2, 0)
    assert labels(got) == [["East", "Ink"], ["East", "Pen"], ["West", "Pen"], ["West", "Ink"]]


def test_excels_sort_order_of_labels():
    values = [2.0, "b", True, False, "A", ExcelError.NA, None, -1.0, ExcelError.DIV0]
    keys = [(v,) for v in values]
    got = [ln.labels[0] for ln in lines(tree(keys, list(range(len(keys))), 1, [], None), 1, 0)]
    assert got == [-1.0, 2.0, "A", "b", False, True, ExcelError.DIV0, ExcelError.NA, None]


def test_table_relationship():
    # the distinct keys as UNIQUE gives them: each as its first row has it ("east", "Ink")
    got = table_lines(KEYS, ALL, 2, [], total, 1)
    assert labels(got) == [["east", "Ink"], ["East", "Pen"], ["West", "Ink"], ["West", "Pen"],
                           ["Total", ""]]
    assert got[1].members == frozenset({0, 4}) and got[-1].depth == 0
    assert labels(table_lines(KEYS, ALL, 2, [], total, -1))[0] == ["Total", ""]
    assert len(table_lines(KEYS, ALL, 2, [], total, 0)) == 4
    # sorted as a table's rows: the second field descending, then the first ascending
    got = table_lines(KEYS, ALL, 2, [(1, True), (0, False)], total, 0)
    assert labels(got) == [["East", "Pen"], ["West", "Pen"], ["east", "Ink"], ["West", "Ink"]]
    # by the aggregate over the whole table (not within a parent)
    got = table_lines(KEYS, ALL, 2, [(2, True)], total, 0)
    assert labels(got) == [["East", "Pen"], ["West", "Ink"], ["east", "Ink"], ["West", "Pen"]]


def test_a_subset_of_the_rows():
    got = lines(tree(KEYS, [1, 3], 2, [], total), 2, 1)
    assert labels(got) == [["West", "Ink"], ["West", "Pen"], ["Total", ""]]
    assert got[-1].members == frozenset({1, 3})
