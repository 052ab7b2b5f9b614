"""Dynamic-array functions that select from an array (Excel 365): FILTER, UNIQUE, SORT,
SORTBY.

Arrays arrive whole; the result is an array Range (spilled by the formula). Nothing left
(FILTER without ``if_empty``, UNIQUE with every value repeated) is #VALUE!: the value the
Excel that saved formulas__test.xlsx gives (newer builds document #CALC!).
"""

from __future__ import annotations

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.arrayargs import OMITTED, array_result, as_grid, whole_arg
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError


@register("FILTER", 2, 3, "range")
def _filter(ctx, array, include, if_empty=OMITTED):
    rows = as_grid(array)
    keep = as_grid(include)
    for v in (rows, keep):
        if isinstance(v, ExcelError):
            return v
    n, m = len(rows), len(rows[0])
    if len(keep[0]) == 1 and len(keep) == n:        # one flag per row
        flags, by_row = [r[0] for r in keep], True
    elif len(keep) == 1 and len(keep[0]) == m:      # one flag per column
        flags, by_row = keep[0], False
    else:
        return ExcelError.VALUE
    chosen = []
    for f in flags:
        if isinstance(f, ExcelError):
            return f
        if isinstance(f, str):
            return ExcelError.VALUE
        chosen.append(bool(f))
    if by_row:
        out = [r for r, k in zip(rows, chosen) if k]
    else:
        out = [[x for x, k in zip(r, chosen) if k] for r in rows]
    if not out or not out[0]:
        if if_empty is OMITTED:
            return ExcelError.VALUE
        return if_empty
    return array_result(out)


def _key(v):
    """Equality of UNIQUE: text without case, numbers and booleans as they are."""
    if isinstance(v, str):
        return ("s", v.casefold())
    if isinstance(v, ExcelError):
        return ("e", v.value)
    if v is None:
        return ("n", None)
    return (type(v).__name__, v)


@register("UNIQUE", 1, 3, ("range", "scalar", "scalar"))
def _unique(ctx, array, by_col=OMITTED, exactly_once=OMITTED):
    rows = as_grid(array)
    if isinstance(rows, ExcelError):
        return rows
    flags = []
    for v in (by_col, exactly_once):
        f = False if v in (OMITTED, None) else c.to_bool(v)
        if isinstance(f, ExcelError):
            return f
        flags.append(f)
    lines = [list(col) for col in zip(*rows)] if flags[0] else rows
    counts: dict[tuple, int] = {}
    first: dict[tuple, list] = {}
    for line in lines:
        k = tuple(_key(x) for x in line)
        counts[k] = counts.get(k, 0) + 1
        first.setdefault(k, line)
    out = [first[k] for k in first if not flags[1] or counts[k] == 1]
    if not out:
        return ExcelError.VALUE
    return array_result([list(r) for r in zip(*out)] if flags[0] else out)


def _rank(v):
    """Excel's sort order: numbers, text (without case), FALSE before TRUE, errors, empty."""
    if isinstance(v, bool):
        return (2, v)
    if isinstance(v, (int, float)):
        return (0, v)
    if isinstance(v, str):
        return (1, v.casefold())
    if isinstance(v, ExcelError):
        return (3, v.code)  # #NULL!, #DIV/0!, #VALUE!, #REF!, #NAME?, #NUM!, #N/A
    return (4, 0)


def _single(v):
    """An option given as a reference or array: one value, else #VALUE!."""
    if isinstance(v, Range):
        return v.rows[0][0] if v.shape == (1, 1) else ExcelError.VALUE
    return v


@register("SORT", 1, 4, "range", omitted=True)
def _sort(ctx, array, index=OMITTED, order=OMITTED, by_col=OMITTED):
    """An omitted option (SORT(A1:A9,,-1)) takes its default; an empty cell is 0."""
    rows = as_grid(array)
    if isinstance(rows, ExcelError):
        return rows
    index, order, by_col = (OMITTED if v is None else _single(v) for v in (index, order, by_col))
    k = whole_arg(index, 1)
    o = whole_arg(order, 1)
    flag = False if by_col in (OMITTED, None) else c.to_bool(by_col)
    for v in (k, o, flag):
        if isinstance(v, ExcelError):
            return v
    lines = [list(col) for col in zip(*rows)] if flag else rows
    if k < 1 or k > len(lines[0]) or o not in (1, -1):
        return ExcelError.VALUE
    ordered = sorted(lines, key=lambda line: _rank(line[k - 1]), reverse=o == -1)
    return array_result([list(r) for r in zip(*ordered)] if flag else ordered)


@register("SORTBY", 2, 254, "range", omitted=True)
def _sortby(ctx, array, *by):
    rows = as_grid(array)
    if isinstance(rows, ExcelError):
        return rows
    keys, orders = [], []
    for i in range(0, len(by), 2):
        key = as_grid(by[i])
        order = whole_arg(_single(by[i + 1]) if i + 1 < len(by) and by[i + 1] is not None
                     else OMITTED, 1)
        for v in (key, order):
            if isinstance(v, ExcelError):
                return v
        if order not in (1, -1):
            return ExcelError.VALUE
        keys.append(key)
        orders.append(order)
    # every by_array is one column as tall as the array (sort rows) or one row as wide
    # (sort columns), all the same way
    if all(len(k[0]) == 1 and len(k) == len(rows) for k in keys):
        by_col, values = False, [[r[0] for r in k] for k in keys]
    elif all(len(k) == 1 and len(k[0]) == len(rows[0]) for k in keys):
        by_col, values = True, [k[0] for k in keys]
    else:
        return ExcelError.VALUE
    lines = [list(col) for col in zip(*rows)] if by_col else rows
    order = list(range(len(lines)))
    for vals, o in reversed(list(zip(values, orders))):  # stable: last key first
        order.sort(key=lambda i, vals=vals: _rank(vals[i]), reverse=o == -1)
    ordered = [lines[i] for i in order]
    return array_result([list(r) for r in zip(*ordered)] if by_col else ordered)
