"""GROUPBY and PIVOTBY (Excel 365; Microsoft's "GROUPBY function" and "PIVOTBY function"
pages): a summary of data by a formula, grouped along one axis (GROUPBY) or two (PIVOTBY),
each group's values aggregated by ``function``: a function named where a LAMBDA is expected
(``SUM``, saved as ``_xleta.SUM``) or a LAMBDA. The result spills.

Arguments (the lines of an axis, their order and totals: :mod:`.pivot`):

* ``field_headers``: 0 the data has no headers, 1 it has and they are not shown, 3 it has
  and they are shown. Missing: the data has headers when the first value is text and the
  second a number. 2 (no headers, generated ones shown) is not computed: the pages do not
  give the generated names (such a call is "not checked").
* ``filter_array``: which data rows count (as tall as the fields; only its first column is
  read, as Excel did for LOOKUP!N93 of formulas__test.xlsx).
* ``relative_to`` (PIVOTBY): what PERCENTOF, or a LAMBDA of two parameters, receives as its
  second argument: 0 the column's values (the default), 1 the row's, 2 all, 3 the row's
  within the parent column group, 4 the column's within the parent row group. GROUPBY gives
  all the values.

Where the pages leave it open, what Microsoft Excel cached in formulas__test.xlsx decides:
a missing ``total_depth`` is the grand total alone and missing ``field_headers`` never shows
the headers (LOOKUP!Y25, three row fields); a group with no values is "" (LOOKUP!N93); a
total depth the fields cannot hold is #VALUE! (EXTRA!AX3); shown headers of PIVOTBY put the
column fields' names, joined by ", ", above the column labels and the row fields' and the
values' names below them (EXTRA!BD95). A vector of functions is not computed.
"""

from __future__ import annotations

from workbook_gen.formula import ast
from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.arrayargs import OMITTED, array_result, as_grid
from workbook_gen.formula.functions.callables import Closure, Function
from workbook_gen.formula.functions.lookup import pivot
from workbook_gen.formula.functions.registry import Unanswered, register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError


class _Bad(Exception):
    def __init__(self, error: ExcelError):
        self.error = error


def _check(v):
    if isinstance(v, ExcelError):
        raise _Bad(v)
    return v


def _option(v, allowed, default):
    """A whole-number option: ``default`` when missing, #VALUE! outside ``allowed``."""
    if v is OMITTED or v is None:
        return default
    if isinstance(v, Range):
        _check(ExcelError.VALUE if v.shape != (1, 1) else None)
        v = v.rows[0][0]
        if v is None:
            return default
    x = _check(c.to_number(_check(v)))
    n = int(x)
    if n not in allowed:
        raise _Bad(ExcelError.VALUE)
    return n


def _sort_keys(v, fields: int, width: int) -> list[tuple[int, bool]]:
    """``(index, descending)`` of each sort key (index 0-based over fields, then values)."""
    if v is OMITTED or v is None:
        return []
    items = list(v.flat()) if isinstance(v, Range) else [v]
    if isinstance(v, Range) and min(v.shape) > 1:
        raise _Bad(ExcelError.VALUE)
    keys = []
    for item in items:
        n = int(_check(c.to_number(_check(item))))
        if n == 0 or abs(n) > width or (len(items) > 1 and abs(n) > fields):
            raise _Bad(ExcelError.VALUE)
        keys.append((abs(n) - 1, n < 0))
    return keys


def _callable(fn):
    if isinstance(fn, Range) and fn.shape == (1, 1):
        fn = fn.rows[0][0]
    _check(fn)
    if not isinstance(fn, (Closure, Function)):
        raise _Bad(ExcelError.VALUE)
    return fn


def _two(fn) -> bool:
    """Whether the function is given the whole as well (PERCENTOF; a LAMBDA of two)."""
    if isinstance(fn, Closure):
        return len(fn.params) == 2
    return fn.name == "PERCENTOF"


def _one(v):
    if isinstance(v, Range):
        return v.rows[0][0] if v.shape == (1, 1) else ExcelError.CALC
    if isinstance(v, (Closure, Function)):
        return ExcelError.CALC
    return "" if v is None else v


class Data:
    """The arguments' rows: keys of each axis, values, names, the rows the filter keeps."""

    def __init__(self, fields: list, values, filter_array, headers):
        grids = [_check(as_grid(f)) for f in fields]
        vals = _check(as_grid(values))
        n = len(vals)
        if any(len(g) != n for g in grids):
            raise _Bad(ExcelError.VALUE)
        mode = _option(headers, (0, 1, 2, 3), None)
        if mode == 2:
            raise Unanswered("GROUPBY/PIVOTBY field_headers 2: the generated names are "
                             "not documented")
        if mode is None:
            first = [r[0] for r in vals[:2]]
            has = (len(first) == 2 and isinstance(first[0], str)
                   and isinstance(first[1], (int, float)) and not isinstance(first[1], bool))
        else:
            has = mode in (1, 3)
        self.show = mode == 3
        start = 1 if has else 0
        self.names = [list(g[0]) if has else [""] * len(g[0]) for g in grids]
        self.value_names = list(vals[0]) if has else [""] * len(vals[0])
        self.keys = [[tuple(r) for r in g[start:]] for g in grids]
        self.values = vals[start:]
        self.members = self._kept(filter_array, n, start)
        if not self.members:
            raise _Bad(ExcelError.CALC)

    def _kept(self, filter_array, n: int, start: int) -> list[int]:
        if filter_array is OMITTED or filter_array is None:
            return list(range(n - start))
        flags = _check(as_grid(filter_array))
        if len(flags) != n:
            raise _Bad(ExcelError.VALUE)
        kept = []
        for i, row in enumerate(flags[start:]):
            f = row[0]
            _check(f)
            if isinstance(f, str):
                raise _Bad(ExcelError.VALUE)
            if f:
                kept.append(i)
        return kept

    def aggregate(self, fn, j: int, subset, whole=None):
        if not subset:
            return ""
        column = Range.array_of([[self.values[i][j]] for i in sorted(subset)])
        if not _two(fn):
            return _one(fn(column))
        everything = Range.array_of([[self.values[i][j]] for i in sorted(whole or ())]
                                    or [[0.0]])
        return _one(fn(column, everything))


def _axis(data: Data, fn, axis: int, depth_arg, sort_arg, table: bool = False):
    keys = data.keys[axis]
    fields, width = len(keys[0]) if keys else len(data.names[axis]), len(data.values[0])
    depth = _option(depth_arg, range(-fields, fields + 1), 1)
    if table and abs(depth) >= 2:
        raise _Bad(ExcelError.VALUE)
    sort = _sort_keys(sort_arg, fields, fields + width)

    def aggregate(members, j):
        return data.aggregate(fn, j, members, data.members)
    if table:
        return pivot.table_lines(keys, data.members, fields, sort, aggregate, depth)
    root = pivot.tree(keys, data.members, fields, sort, aggregate)
    return pivot.lines(root, fields, depth)


def _single_function(args) -> bool:
    """GROUPBY/PIVOTBY compute one function, not a vector of them (HSTACK(SUM, AVERAGE))."""
    fn = args[2] if len(args) > 2 else None
    return not isinstance(fn, (ast.Array, ast.Func)) or (
        isinstance(fn, ast.Func) and fn.name == "LAMBDA")


@register("GROUPBY", 3, 8, "range", omitted=True, accepts=_single_function)
def _groupby(ctx, row_fields, values, function, field_headers=OMITTED, total_depth=OMITTED,
             sort_order=OMITTED, filter_array=OMITTED, field_relationship=OMITTED):
    try:
        fn = _callable(function)
        data = Data([row_fields], values, filter_array, field_headers)
        table = _option(field_relationship, (0, 1), 0) == 1
        rows = _axis(data, fn, 0, total_depth, sort_order, table)
    except _Bad as bad:
        return bad.error
    width = len(data.values[0])
    out = [data.names[0] + data.value_names] if data.show else []
    for line in rows:
        out.append(line.labels + [data.aggregate(fn, j, line.members, data.members)
                                  for j in range(width)])
    return array_result(out)


def _pivot_accepts(args) -> bool:
    return _single_function(args[1:])


def _whole(rel: int, row: pivot.Line, col: pivot.Line, everything):
    return (col.members, row.members, everything, row.members & col.outer,
            col.members & row.outer)[rel]


@register("PIVOTBY", 4, 11, "range", omitted=True, accepts=_pivot_accepts)
def _pivotby(ctx, row_fields, col_fields, values, function, field_headers=OMITTED,
             row_total_depth=OMITTED, row_sort_order=OMITTED, col_total_depth=OMITTED,
             col_sort_order=OMITTED, filter_array=OMITTED, relative_to=OMITTED):
    try:
        fn = _callable(function)
        data = Data([row_fields, col_fields], values, filter_array, field_headers)
        rows = _axis(data, fn, 0, row_total_depth, row_sort_order)
        cols = _axis(data, fn, 1, col_total_depth, col_sort_order)
        rel = _option(relative_to, range(5), 0)
    except _Bad as bad:
        return bad.error
    width, lead = len(data.values[0]), len(data.names[0])
    everything = frozenset(data.members)
    out = []
    if data.show:
        out.append([""] * lead + [", ".join(str(c.to_text(x)) for x in data.names[1])]
                   + [""] * (len(cols) * width - 1))
    for level in range(len(data.names[1])):
        out.append([""] * lead + [col.labels[level] for col in cols for _ in range(width)])
    if data.show:
        out.append(data.names[0] + data.value_names * len(cols))
    for row in rows:
        line = list(row.labels)
        for col in cols:
            subset = row.members & col.members
            whole = _whole(rel, row, col, everything)
            line.extend(data.aggregate(fn, j, subset, whole) for j in range(width))
        out.append(line)
    return array_result(out)
