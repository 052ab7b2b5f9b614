"""lookup/groupby.py and lookup/pivot.py: GROUPBY and PIVOTBY.

Against Microsoft Excel's cached spills in formulas__test.xlsx (every GROUPBY and PIVOTBY
formula of its LOOKUP and EXTRA sheets: headers, totals and subtotals at the bottom and the
top, sorting by fields and by values, filters, PERCENTOF relative to each total, errors),
and against the rules of Microsoft's pages ("GROUPBY function", "PIVOTBY function":
support.microsoft.com/en-us/excel/functions/groupby-function, .../pivotby-function) on
random tables, the reference being a dictionary of groups built here."""

from __future__ import annotations

import math
import random
from collections import defaultdict

import pytest

from tests.formula.functions import excel_cached as xc
from workbook_gen.formula import DictResolver
from workbook_gen.xlerror import ExcelError

RNG = random.Random(2311)


@pytest.mark.parametrize("sheet,part,first,last", [("LOOKUP", "sheet11", 20, 115),
                                                   ("EXTRA", "sheet18", 1, 110)])
def test_every_groupby_and_pivotby_of_formulas_test_agrees_with_excel(sheet, part, first, last):
    formulas = xc.array_formulas(part, r"GROUPBY|PIVOTBY")
    assert len(formulas) >= 7
    res = xc.resolver((sheet, "LOOKUP") if sheet != "LOOKUP" else ("LOOKUP",), first, last)
    for anchor, ref, formula in formulas:
        xc.assert_spill(formula, ref, sheet, res)


def lit(rows) -> str:
    def one(v):
        return '"' + v + '"' if isinstance(v, str) else repr(float(v))
    return "{" + ";".join(",".join(one(v) for v in r) for r in rows) + "}"


def ev(text: str):
    return xc.recomputed(text, DictResolver({}))


def table(n=30):
    keys = [(RNG.choice("pqrs"), RNG.choice("xyz")) for _ in range(n)]
    vals = [float(RNG.randint(-9, 9)) for _ in range(n)]
    return keys, vals


def test_groupby_sums_each_group_sorted_ascending_with_a_grand_total():
    """Example 1 of the GROUPBY page, =GROUPBY(A2:A76,D2:D76,SUM): one line per distinct
    field value in ascending order, then the grand total."""
    keys, vals = table()
    got = ev(f"GROUPBY({lit([[k[0]] for k in keys])},{lit([[v] for v in vals])},_xleta.SUM)")
    sums = defaultdict(float)
    for k, v in zip(keys, vals):
        sums[k[0]] += v
    assert got == [[k, sums[k]] for k in sorted(sums)] + [["Total", math.fsum(vals)]]


def test_groupby_sorted_by_the_values_descending():
    """Example 2 of the GROUPBY page, =GROUPBY(C2:C76,D2:D76,SUM,,,-2): sort_order -2 is
    the first values column, descending."""
    keys, vals = table()
    got = ev(f"GROUPBY({lit([[k[0]] for k in keys])},{lit([[v] for v in vals])},"
             f"_xleta.SUM,,,-2)")
    sums = defaultdict(float)
    for k, v in zip(keys, vals):
        sums[k[0]] += v
    body = got[:-1]
    assert [r[1] for r in body] == sorted(sums.values(), reverse=True)
    assert {r[0]: r[1] for r in body} == sums


def test_groupby_two_fields_subtotals_above_and_a_filter():
    """total_depth -2: grand total and subtotals by the first field, above what they total;
    filter_array keeps the rows marked TRUE; the grand total reads "Grand Total"."""
    keys, vals = table()
    keep = [RNG.random() < 0.7 for _ in keys]
    flags = "{" + ";".join("TRUE" if k else "FALSE" for k in keep) + "}"
    got = ev(f"GROUPBY({lit(keys)},{lit([[v] for v in vals])},_xleta.SUM,0,-2,,{flags})")
    leaf, sub = defaultdict(float), defaultdict(float)
    for k, v, f in zip(keys, vals, keep):
        if f:
            leaf[k] += v
            sub[k[0]] += v
    want = [["Grand Total", "", sum(sub.values())]]
    for a in sorted(sub):
        want.append([a, "", sub[a]])
        want += [[a, b, leaf[(a, b)]] for (x, b) in sorted(leaf) if x == a]
    assert got == [[r[0], r[1], pytest.approx(r[2])] for r in want]


def test_groupby_average_with_headers_shown():
    """field_headers 3: the first row holds the names, shown above the result."""
    got = ev('GROUPBY({"k";"a";"b";"a"},{"v";1;2;4},_xleta.AVERAGE,3,0)')
    assert got == [["k", "v"], ["a", 2.5], ["b", 2.0]]


def test_groupby_lambda_and_errors():
    got = ev('GROUPBY({"a";"b";"a"},{1;2;4},LAMBDA(x,MAX(x)-MIN(x)),0,0)')
    assert got == [["a", 3.0], ["b", 0.0]]
    assert ev('GROUPBY({"a";"b"},{1;2;3},_xleta.SUM)') == [[ExcelError.VALUE]]  # lengths
    assert ev('GROUPBY({"a";"b"},{1;2},_xleta.SUM,0,0,3)') == [[ExcelError.VALUE]]  # sort 3
    assert ev('GROUPBY({"a";"b"},{1;2},1)') == [[ExcelError.VALUE]]  # not a function


def test_pivotby_sums_the_crossing_of_rows_and_columns():
    """PIVOTBY page: rows grouped by row_fields, columns by col_fields; a crossing without
    values is empty; totals below and to the right."""
    keys, vals = table()
    got = ev(f"PIVOTBY({lit([[k[0]] for k in keys])},{lit([[k[1]] for k in keys])},"
             f"{lit([[v] for v in vals])},_xleta.SUM)")
    cell = defaultdict(float)
    for k, v in zip(keys, vals):
        cell[k] += v
    rows, cols = sorted({k[0] for k in keys}), sorted({k[1] for k in keys})
    assert got[0] == [""] + cols + ["Total"]
    for line, r in zip(got[1:], rows):
        assert line[0] == r
        for value, col in zip(line[1:-1], cols):
            assert value == (pytest.approx(cell[(r, col)]) if (r, col) in cell else "")
        assert line[-1] == pytest.approx(sum(v for (a, _), v in cell.items() if a == r))
    assert got[-1][-1] == pytest.approx(math.fsum(vals))


@pytest.mark.parametrize("rel", range(5))
def test_pivotby_percentof_relative_to(rel):
    """relative_to: 0 column totals, 1 row totals, 2 the grand total, 3 the parent column
    total, 4 the parent row total (one field per axis: the parents are the totals)."""
    keys, vals = table(40)
    vals = [abs(v) + 1 for v in vals]
    got = ev(f"PIVOTBY({lit([[k[0]] for k in keys])},{lit([[k[1]] for k in keys])},"
             f"{lit([[v] for v in vals])},_xleta.PERCENTOF,0,1,,1,,,{rel})")
    cell, row, col = defaultdict(float), defaultdict(float), defaultdict(float)
    for k, v in zip(keys, vals):
        cell[k] += v
        row[k[0]] += v
        col[k[1]] += v
    grand = math.fsum(vals)
    rows, cols = sorted(row), sorted(col)
    for line, r in zip(got[1:-1], rows):
        for value, c in zip(line[1:-1], cols):
            if (r, c) in cell:
                whole = (col[c], row[r], grand, row[r], col[c])[rel]
                assert value == pytest.approx(cell[(r, c)] / whole)


def test_what_is_not_computed_is_said_so():
    """field_headers 2 (generated names the pages do not give) is Unanswered: the cell is
    "not checked"; a vector of functions is refused before evaluation."""
    from workbook_gen.formula import parse as parse_formula
    from workbook_gen.formula.functions.registry import REGISTRY, Unanswered
    with pytest.raises(Unanswered):
        ev('GROUPBY({"a";"b"},{1;2},_xleta.SUM,2)')
    node = parse_formula("GROUPBY(A1:A3,B1:B3,HSTACK(_xleta.SUM,_xleta.MAX))")
    assert not REGISTRY["GROUPBY"].accepts(node.args)
    node = parse_formula("PIVOTBY(A1:A3,C1:C3,B1:B3,LAMBDA(x,SUM(x)))")
    assert REGISTRY["PIVOTBY"].accepts(node.args)
