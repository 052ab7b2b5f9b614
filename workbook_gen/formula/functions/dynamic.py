"""Dynamic-array functions that shape arrays (Excel 365): CHOOSECOLS, CHOOSEROWS, TOCOL,
TOROW, TAKE, DROP, EXPAND, VSTACK, HSTACK, WRAPROWS, WRAPCOLS, SEQUENCE; and the text
ones that make or read arrays: TEXTBEFORE, TEXTAFTER, ARRAYTOTEXT, VALUETOTEXT.

Arguments that are arrays arrive whole (kind ``range``); an array result is an array
Range that the formula spills. An empty result is #CALC! (Excel has no empty array).
"""

from __future__ import annotations

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

MAX_CELLS = 1_048_576
OMITTED = object()  # an argument not given (an empty cell given is None: 0)


def _grid(v) -> list[list] | ExcelError:
    if isinstance(v, ExcelError):
        return v
    if isinstance(v, Range):
        return [list(r) for r in v.rows] if v.rows and v.rows[0] else ExcelError.CALC
    return [[v]]


def _out(rows: list[list]):
    if not rows or not rows[0]:
        return ExcelError.CALC
    return Range.array_of(rows)


def _int(v, default=None):
    """A whole-number argument (truncated); ``default`` when omitted, 0 for an empty cell."""
    if v is OMITTED:
        return default
    if v is None:
        return 0
    if isinstance(v, str):
        n = c.to_number(v)
        return ExcelError.VALUE if isinstance(n, ExcelError) else int(n)
    n = c.number(v)
    return n if isinstance(n, ExcelError) else int(n)


def _ints(*vs):
    out = []
    for v in vs:
        if isinstance(v, ExcelError):
            return v
        out.append(v)
    return out


def _choose(rows, picks, by_col: bool):
    lines = [list(col) for col in zip(*rows)] if by_col else rows
    n = len(lines)
    chosen = []
    if any(isinstance(p, Range) and min(p.shape) > 1 for p in picks):
        return ExcelError.VALUE  # (a list of numbers is a row or a column)
    flat = [x for p in picks for x in (p.flat() if isinstance(p, Range) else [p])]
    for p in flat:
        k = _int(p)
        if isinstance(k, ExcelError):
            return k
        if k == 0 or abs(k) > n:
            return ExcelError.VALUE
        chosen.append(lines[k - 1] if k > 0 else lines[n + k])
    if by_col:
        return _out([list(r) for r in zip(*chosen)])
    return _out(chosen)


@register("CHOOSECOLS", "lookup", 2, 254, "range")
def _choosecols(ctx, array, *cols):
    rows = _grid(array)
    return rows if isinstance(rows, ExcelError) else _choose(rows, cols, True)


@register("CHOOSEROWS", "lookup", 2, 254, "range")
def _chooserows(ctx, array, *picks):
    rows = _grid(array)
    return rows if isinstance(rows, ExcelError) else _choose(rows, picks, False)


def _flat(array, ignore=OMITTED, scan_by_column=OMITTED):
    rows = _grid(array)
    if isinstance(rows, ExcelError):
        return rows
    mode = _int(ignore, 0)
    by_col = (False if scan_by_column in (OMITTED, None) else c.to_bool(scan_by_column))
    if isinstance(mode, ExcelError) or isinstance(by_col, ExcelError):
        return mode if isinstance(mode, ExcelError) else by_col
    if mode not in (0, 1, 2, 3):
        return ExcelError.VALUE
    items = [x for line in (zip(*rows) if by_col else rows) for x in line]
    return [x for x in items if not ((mode & 1 and x is None)
                                     or (mode & 2 and isinstance(x, ExcelError)))]


@register("TOCOL", "lookup", 1, 3, ("range", "scalar", "scalar"))
def _tocol(ctx, array, ignore=OMITTED, scan_by_column=OMITTED):
    items = _flat(array, ignore, scan_by_column)
    return items if isinstance(items, ExcelError) else _out([[x] for x in items])


@register("TOROW", "lookup", 1, 3, ("range", "scalar", "scalar"))
def _torow(ctx, array, ignore=OMITTED, scan_by_column=OMITTED):
    items = _flat(array, ignore, scan_by_column)
    return items if isinstance(items, ExcelError) else _out([items])


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
    return _out(rows)


def _take_or_drop(array, rows, cols, drop: bool):
    grid = _grid(array)
    n = _ints(_int(rows), _int(cols))
    if isinstance(grid, ExcelError) or isinstance(n, ExcelError):
        return grid if isinstance(grid, ExcelError) else n
    return _take(grid, n[0], n[1], drop)


@register("TAKE", "lookup", 2, 3, ("range", "scalar", "scalar"))
def _take_fn(ctx, array, rows, cols=OMITTED):
    return _take_or_drop(array, rows, cols, False)


@register("DROP", "lookup", 2, 3, ("range", "scalar", "scalar"))
def _drop_fn(ctx, array, rows, cols=OMITTED):
    return _take_or_drop(array, rows, cols, True)


@register("EXPAND", "lookup", 2, 4, ("range", "scalar", "scalar", "scalar"))
def _expand(ctx, array, rows, cols=OMITTED, pad=OMITTED):
    grid = _grid(array)
    if isinstance(grid, ExcelError):
        return grid
    n = _ints(_int(rows, len(grid)), _int(cols, len(grid[0])))
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
    return _out(out)


def _stack(arrays, vertical: bool):
    grids = [_grid(a) for a in arrays]
    grids = [[[g]] if isinstance(g, ExcelError) else g for g in grids]
    if vertical:
        width = max(len(g[0]) for g in grids)
        return _out([list(r) + [ExcelError.NA] * (width - len(r)) for g in grids for r in g])
    height = max(len(g) for g in grids)
    out = [[] for _ in range(height)]
    for g in grids:
        for i in range(height):
            out[i] += g[i] if i < len(g) else [ExcelError.NA] * len(g[0])
    return _out(out)


@register("VSTACK", "lookup", 1, 254, "range")
def _vstack(ctx, *arrays):
    return _stack(arrays, True)


@register("HSTACK", "lookup", 1, 254, "range")
def _hstack(ctx, *arrays):
    return _stack(arrays, False)


def _wrap(vector, count, pad, by_rows: bool):
    grid = _grid(vector)
    if isinstance(grid, ExcelError):
        return grid
    if len(grid) > 1 and len(grid[0]) > 1:
        return ExcelError.VALUE
    k = _int(count)
    if isinstance(k, ExcelError):
        return k
    if k is None or k < 1:
        return ExcelError.NUM
    items = [x for r in grid for x in r]
    pad = ExcelError.NA if pad is OMITTED else 0.0 if pad is None else pad
    lines = [items[i:i + k] for i in range(0, len(items), k)]
    lines[-1] = lines[-1] + [pad] * (k - len(lines[-1]))
    return _out(lines if by_rows else [list(r) for r in zip(*lines)])


@register("WRAPROWS", "lookup", 2, 3, ("range", "scalar", "scalar"))
def _wraprows(ctx, vector, count, pad=OMITTED):
    return _wrap(vector, count, pad, True)


@register("WRAPCOLS", "lookup", 2, 3, ("range", "scalar", "scalar"))
def _wrapcols(ctx, vector, count, pad=OMITTED):
    return _wrap(vector, count, pad, False)


@register("SEQUENCE", "math", 1, 4)
def _sequence(ctx, rows, cols=OMITTED, start=OMITTED, step=OMITTED):
    n = _ints(_int(rows, 1), _int(cols, 1))
    if isinstance(n, ExcelError):
        return n
    first = 1.0 if start is OMITTED else c.number(start)
    by = 1.0 if step is OMITTED else c.number(step)
    for v in (first, by):
        if isinstance(v, ExcelError):
            return v
    r, k = n
    if r < 1 or k < 1:
        return ExcelError.CALC if r == 0 or k == 0 else ExcelError.VALUE
    if r * k > MAX_CELLS:
        return ExcelError.NUM
    return _out([[first + by * (i * k + j) for j in range(k)] for i in range(r)])


# -- text ---------------------------------------------------------------------------------

def _find_all(text: str, delims: list[str], fold: bool):
    """(start, end) of every delimiter occurrence, left to right, not overlapping."""
    hay = text.casefold() if fold else text
    keys = [d.casefold() if fold else d for d in delims]
    out, i = [], 0
    while i <= len(hay):
        best = None
        for d in keys:
            j = hay.find(d, i)
            if j >= 0 and (best is None or j < best[0] or (j == best[0] and len(d) > best[1])):
                best = (j, len(d))
        if best is None:
            break
        out.append((best[0], best[0] + best[1]))
        i = best[0] + max(best[1], 1)
    return out


def _delims(v):
    if isinstance(v, Range):
        items = [x for r in v.rows for x in r]
    else:
        items = [v]
    out = []
    for x in items:
        t = c.to_text(x)
        if isinstance(t, ExcelError):
            return t
        out.append(t)
    return out


def _before_after(text, delimiter, instance, match_mode, match_end, if_not_found, after):
    t = c.to_text(text)
    if isinstance(t, ExcelError):
        return t
    delims = _delims(delimiter)
    if isinstance(delims, ExcelError):
        return delims
    k = _int(instance, 1)
    mode = _int(match_mode, 0)
    end = _int(match_end, 0)
    for v in (k, mode, end):
        if isinstance(v, ExcelError):
            return v
    if k == 0 or abs(k) > len(t) + (1 if end else 0) or mode not in (0, 1) or end not in (0, 1):
        return ExcelError.VALUE
    if any(d == "" for d in delims):
        return t if (k > 0) == after else ""
    hits = _find_all(t, delims, mode == 1)
    if end:  # the end of the text counts as a delimiter
        hits = ([(0, 0)] if k < 0 else []) + hits + ([(len(t), len(t))] if k > 0 else [])
    if abs(k) > len(hits):
        return ExcelError.NA if if_not_found is OMITTED else (
            0.0 if if_not_found is None else if_not_found)
    start, stop = hits[k - 1] if k > 0 else hits[k]
    return t[stop:] if after else t[:start]


@register("TEXTBEFORE", "text", 2, 6, ("scalar", "range", "scalar"))
def _textbefore(ctx, text, delimiter, instance=OMITTED, match_mode=OMITTED,
                match_end=OMITTED, if_not_found=OMITTED):
    return _before_after(text, delimiter, instance, match_mode, match_end, if_not_found, False)


@register("TEXTAFTER", "text", 2, 6, ("scalar", "range", "scalar"))
def _textafter(ctx, text, delimiter, instance=OMITTED, match_mode=OMITTED,
               match_end=OMITTED, if_not_found=OMITTED):
    return _before_after(text, delimiter, instance, match_mode, match_end, if_not_found, True)


def _value_text(v, strict: bool):
    if isinstance(v, ExcelError):
        return v.value
    if v is None:
        return ""
    if isinstance(v, str):
        return '"' + v.replace('"', '""') + '"' if strict else v
    t = c.to_text(v)
    return t.value if isinstance(t, ExcelError) else t


@register("VALUETOTEXT", "text", 1, 2)
def _valuetotext(ctx, value, fmt=OMITTED):
    f = _int(fmt, 0)
    if isinstance(f, ExcelError):
        return f
    if f not in (0, 1):
        return ExcelError.VALUE
    return _value_text(value, f == 1)


@register("ARRAYTOTEXT", "text", 1, 2, ("range", "scalar"))
def _arraytotext(ctx, array, fmt=OMITTED):
    f = _int(fmt, 0)
    if isinstance(f, ExcelError):
        return f
    if f not in (0, 1):
        return ExcelError.VALUE
    grid = _grid(array)
    if isinstance(grid, ExcelError):
        grid = [[grid]]
    if f == 0:
        return ", ".join(_value_text(x, False) for r in grid for x in r)
    if grid == [[None]]:  # (Excel: one empty cell has no strict form; in an array it is "")
        return ExcelError.VALUE
    return "{" + ";".join(",".join(_value_text(x, True) for x in r) for r in grid) + "}"


def _split(text: str, delims: list[str], fold: bool) -> list[str]:
    parts, last = [], 0
    for start, stop in _find_all(text, [d for d in delims if d], fold):
        parts.append(text[last:start])
        last = stop
    return parts + [text[last:]]


@register("TEXTSPLIT", "text", 2, 6, ("scalar", "range", "range", "scalar", "scalar",
                                      "scalar"))
def _textsplit(ctx, text, col_delimiter, row_delimiter=OMITTED, ignore_empty=OMITTED,
               match_mode=OMITTED, pad=OMITTED):
    t = c.to_text(text)
    if isinstance(t, ExcelError):
        return t
    cols = _delims(col_delimiter) if col_delimiter is not None else []
    rows = (_delims(row_delimiter) if row_delimiter not in (OMITTED, None) else [])
    for v in (cols, rows):
        if isinstance(v, ExcelError):
            return v
    skip = False if ignore_empty in (OMITTED, None) else c.to_bool(ignore_empty)
    mode = _int(match_mode, 0)
    for v in (skip, mode):
        if isinstance(v, ExcelError):
            return v
    if mode not in (0, 1) or not any(cols + rows):
        return ExcelError.VALUE
    lines = _split(t, rows, mode == 1) if any(rows) else [t]
    grid = [_split(line, cols, mode == 1) if any(cols) else [line] for line in lines]
    if skip:
        grid = [[x for x in r if x != ""] for r in grid]
        grid = [r for r in grid if r]
    if not grid:
        return ExcelError.CALC
    width = max(len(r) for r in grid)
    fill = ExcelError.NA if pad is OMITTED else 0.0 if pad is None else pad
    return _out([r + [fill] * (width - len(r)) for r in grid])
