"""Dynamic-array functions that shape arrays (Excel 365): CHOOSECOLS, CHOOSEROWS, TOCOL,
TOROW, TAKE, DROP, EXPAND, VSTACK, HSTACK, WRAPROWS, WRAPCOLS (SEQUENCE is in
:mod:`..math.series`; the text ones that make or read arrays in :mod:`..text.arrays`).

Arguments that are arrays arrive whole (kind ``range``); an array result is an array
Range that the formula spills. An empty result is #CALC! (Excel has no empty array).
"""

from __future__ import annotations

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.arrayargs import (
    MAX_CELLS, OMITTED, array_result, as_grid, whole_arg, whole_args,
)
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

def _choose(rows, picks, by_col: bool):
    lines = [list(col) for col in zip(*rows)] if by_col else rows
    n = len(lines)
    chosen = []
    if any(isinstance(p, Range) and min(p.shape) > 1 for p in picks):
        return ExcelError.VALUE  # (a list of numbers is a row or a column)
    flat = [x for p in picks for x in (p.flat() if isinstance(p, Range) else [p])]
    for p in flat:
        k = whole_arg(p)
        if isinstance(k, ExcelError):
            return k
        if k == 0 or abs(k) > n:
            return ExcelError.VALUE
        chosen.append(lines[k - 1] if k > 0 else lines[n + k])
    if by_col:
        return array_result([list(r) for r in zip(*chosen)])
    return array_result(chosen)


@register("CHOOSECOLS", 2, 254, "range")
def _choosecols(ctx, array, *cols):
    rows = as_grid(array)
    return rows if isinstance(rows, ExcelError) else _choose(rows, cols, True)


@register("CHOOSEROWS", 2, 254, "range")
def _chooserows(ctx, array, *picks):
    rows = as_grid(array)
    return rows if isinstance(rows, ExcelError) else _choose(rows, picks, False)


def _flat(array, ignore=OMITTED, scan_by_column=OMITTED):
    rows = as_grid(array)
    if isinstance(rows, ExcelError):
        return rows
    mode = whole_arg(ignore, 0)
    by_col = (False if scan_by_column in (OMITTED, None) else c.to_bool(scan_by_column))
    if isinstance(mode, ExcelError) or isinstance(by_col, ExcelError):
        return mode if isinstance(mode, ExcelError) else by_col
    if mode not in (0, 1, 2, 3):
        return ExcelError.VALUE
    items = [x for line in (zip(*rows) if by_col else rows) for x in line]
    return [x for x in items if not ((mode & 1 and x is None)
                                     or (mode & 2 and isinstance(x, ExcelError)))]


@register("TOCOL", 1, 3, ("range", "scalar", "scalar"))
def _tocol(ctx, array, ignore=OMITTED, scan_by_column=OMITTED):
    items = _flat(array, ignore, scan_by_column)
    return items if isinstance(items, ExcelError) else array_result([[x] for x in items])


@register("TOROW", 1, 3, ("range", "scalar", "scalar"))
def _torow(ctx, array, ignore=OMITTED, scan_by_column=OMITTED):
    items = _flat(array, ignore, scan_by_column)
    return items if isinstance(items, ExcelError) else array_result([items])


def _take(rows, n, m, drop: bool):
    def cut(seq, k):
        if k is None:
            return seq
        if drop:
            return seq[k:] if k >= 0 else seq[:len(seq) + k] if -k < len(seq) else []
        return seq[:k] if k >= 0 else seq[max(0, len(seq) + k):]
    rows = cut(rows, n)
    rows = [cut(r, m) for r in rows]
    if not rows or not rows[0]:  # (Excel's value for nothing taken or everything dropped)
        return ExcelError.VALUE
    return array_result(rows)


def _take_or_drop(array, rows, cols, drop: bool):
    grid = as_grid(array)
    n = whole_args(whole_arg(rows), whole_arg(cols))
    if isinstance(grid, ExcelError) or isinstance(n, ExcelError):
        return grid if isinstance(grid, ExcelError) else n
    return _take(grid, n[0], n[1], drop)


@register("TAKE", 2, 3, ("range", "scalar", "scalar"))
def _take_fn(ctx, array, rows, cols=OMITTED):
    return _take_or_drop(array, rows, cols, False)


@register("DROP", 2, 3, ("range", "scalar", "scalar"))
def _drop_fn(ctx, array, rows, cols=OMITTED):
    return _take_or_drop(array, rows, cols, True)


@register("EXPAND", 2, 4, ("range", "scalar", "scalar", "scalar"))
def _expand(ctx, array, rows, cols=OMITTED, pad=OMITTED):
    grid = as_grid(array)
    if isinstance(grid, ExcelError):
        return grid
    n = whole_args(whole_arg(rows, len(grid)), whole_arg(cols, len(grid[0])))
    if isinstance(n, ExcelError):
        return n
    r, k = n
    if r < len(grid) or k < len(grid[0]):
        return ExcelError.VALUE
    if r * k > MAX_CELLS:
        return ExcelError.NUM
    pad = ExcelError.NA if pad is OMITTED else 0.0 if pad is None else pad
    out = [list(line) + [pad] * (k - len(line)) for line in grid]
    out += [[pad] * k for _ in range(r - len(grid))]
    return array_result(out)


def _stack(arrays, vertical: bool):
    grids = [as_grid(a) for a in arrays]
    grids = [[[g]] if isinstance(g, ExcelError) else g for g in grids]
    if vertical:
        width = max(len(g[0]) for g in grids)
        return array_result([list(r) + [ExcelError.NA] * (width - len(r))
                             for g in grids for r in g])
    height = max(len(g) for g in grids)
    out = [[] for _ in range(height)]
    for g in grids:
        for i in range(height):
            out[i] += g[i] if i < len(g) else [ExcelError.NA] * len(g[0])
    return array_result(out)


@register("VSTACK", 1, 254, "range")
def _vstack(ctx, *arrays):
    return _stack(arrays, True)


@register("HSTACK", 1, 254, "range")
def _hstack(ctx, *arrays):
    return _stack(arrays, False)


def _wrap(vector, count, pad, by_rows: bool):
    grid = as_grid(vector)
    if isinstance(grid, ExcelError):
        return grid
    if len(grid) > 1 and len(grid[0]) > 1:
        return ExcelError.VALUE
    k = whole_arg(count)
    if isinstance(k, ExcelError):
        return k
    if k is None or k < 1:
        return ExcelError.NUM
    items = [x for r in grid for x in r]
    pad = ExcelError.NA if pad is OMITTED else 0.0 if pad is None else pad
    lines = [items[i:i + k] for i in range(0, len(items), k)]
    lines[-1] = lines[-1] + [pad] * (k - len(lines[-1]))
    return array_result(lines if by_rows else [list(r) for r in zip(*lines)])


@register("WRAPROWS", 2, 3, ("range", "scalar", "scalar"))
def _wraprows(ctx, vector, count, pad=OMITTED):
    return _wrap(vector, count, pad, True)


@register("WRAPCOLS", 2, 3, ("range", "scalar", "scalar"))
def _wrapcols(ctx, vector, count, pad=OMITTED):
    return _wrap(vector, count, pad, False)
