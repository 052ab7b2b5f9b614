"""Lookup and reference: INDEX, MATCH, VLOOKUP, HLOOKUP, LOOKUP, XLOOKUP, XMATCH, CHOOSE,
ROW, COLUMN, ROWS, COLUMNS, OFFSET, INDIRECT, ADDRESS, TRANSPOSE.

Approximate lookups scan sorted data as Excel's binary search does on sorted data: the
last position not past the lookup value (unsorted data is the user's error in Excel too).
"""

from __future__ import annotations

import re

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range, Ref
from workbook_gen.xlerror import ExcelError


def _exact_pattern(lookup):
    if isinstance(lookup, str) and c.has_wildcard(lookup):
        return c.wildcard(lookup)
    return None


def find(lookup, values: list, mode: int, wildcards: bool = True, reverse: bool = False):
    """Index of ``lookup`` in ``values`` or None. ``mode``: 0 exact, 1 largest <= (sorted
    ascending), -1 smallest >= (sorted descending); ``2`` exact with wildcards."""
    if mode == 0 or mode == 2:
        if lookup is None:
            return None
        pattern = _exact_pattern(lookup) if wildcards or mode == 2 else None
        order = range(len(values) - 1, -1, -1) if reverse else range(len(values))
        for i in order:
            v = values[i]
            if v is None or isinstance(v, ExcelError) or c.rank(v) != c.rank(lookup):
                continue
            if (pattern.fullmatch(v) is not None) if pattern else c.compare(v, lookup) == 0:
                return i
        return None
    if lookup is None:
        lookup = 0.0
    want = (0, -1) if mode > 0 else (0, 1)
    found = None
    for i, v in enumerate(values):
        if v is None or isinstance(v, ExcelError) or c.rank(v) != c.rank(lookup):
            continue
        if c.compare(v, lookup) in want:
            found = i
        else:
            break
    return found


def _nearest(lookup, values: list, mode: int, reverse: bool):
    """XLOOKUP/XMATCH modes -1 / 1: exact, else the next smaller / larger (any order)."""
    best = None
    order = range(len(values) - 1, -1, -1) if reverse else range(len(values))
    for i in order:
        v = values[i]
        if v is None or isinstance(v, ExcelError) or c.rank(v) != c.rank(lookup):
            continue
        cmp = c.compare(v, lookup)
        if cmp == 0:
            return i
        if (cmp < 0 and mode < 0) or (cmp > 0 and mode > 0):
            if best is None or c.compare(v, values[best]) == (1 if mode < 0 else -1):
                best = i
    return best


def _vector(area: Range) -> list | None:
    """The values of a one-row or one-column area, else None."""
    rows, cols = area.shape
    if rows == 1:
        return list(area.rows[0])
    if cols == 1:
        return [r[0] for r in area.rows]
    return None


@register("MATCH", "lookup", 2, 3, ("scalar", "range", "scalar"))
def _match(ctx, lookup, area, kind=1.0):
    if isinstance(lookup, ExcelError):
        return lookup
    kind = c.to_number(kind)
    if isinstance(kind, ExcelError):
        return kind
    values = _vector(c.as_area(area))
    if values is None:
        return ExcelError.NA
    if lookup is None and kind == 0:
        return ExcelError.NA
    mode = 0 if kind == 0 else (1 if kind > 0 else -1)
    if mode == 0 and type(lookup) is float and c.as_area(area).numbers() is not None:
        try:  # a number among plain numbers: list.index compares exactly, as find()
            return float(values.index(lookup) + 1)
        except ValueError:
            return ExcelError.NA
    i = find(lookup, values, mode)
    return ExcelError.NA if i is None else float(i + 1)


def _sub(area: Range, r1: int, c1: int, r2: int, c2: int) -> Range:
    """Rows r1..r2, columns c1..c2 (0-based, inclusive) of ``area``, keeping the reference."""
    rows = [row[c1:c2 + 1] for row in area.rows[r1:r2 + 1]]
    if area.ref is None:
        return Range.array_of(rows)
    ref = area.ref
    return Range.of(rows, Ref(ref.sheet, ref.row1 + r1, ref.col1 + c1,
                              ref.row1 + r2, ref.col1 + c2))


@register("INDEX", "lookup", 2, 4, ("ref", "scalar"))
def _index(ctx, area, row, col=None, part=1.0):
    area = c.as_area(area)
    idx = [c.to_number(v) for v in (row, col, part) if v is not None]
    bad = next((x for x in idx if isinstance(x, ExcelError)), None)
    if bad is not None:
        return bad
    nrows, ncols = area.shape
    r = int(idx[0])
    k = int(idx[1]) if col is not None else None
    if k is None:
        if nrows == 1 and ncols > 1:
            r, k = 1, r  # one index into a single row selects a column
        else:
            k = 0 if ncols > 1 else 1
    if r < 0 or k < 0:
        return ExcelError.VALUE
    if r > nrows or k > ncols:
        return ExcelError.REF
    r1, r2 = (0, nrows - 1) if r == 0 else (r - 1, r - 1)
    c1, c2 = (0, ncols - 1) if k == 0 else (k - 1, k - 1)
    return _sub(area, r1, c1, r2, c2)


def _table_lookup(ctx, lookup, table, index, approx, by_rows: bool):
    if isinstance(lookup, ExcelError):
        return lookup
    n = c.to_number(index)
    if isinstance(n, ExcelError):
        return n
    approx = c.to_bool(approx if approx is not None else True)
    if isinstance(approx, ExcelError):
        return approx
    area = c.as_area(table)
    rows = area.rows if not by_rows else tuple(zip(*area.rows))
    n = int(n)
    if n < 1:
        return ExcelError.VALUE
    if not rows or n > len(rows[0]):
        return ExcelError.REF
    i = find(lookup, [r[0] for r in rows], 1 if approx else 0)
    return ExcelError.NA if i is None else rows[i][n - 1]


@register("VLOOKUP", "lookup", 3, 4, ("scalar", "range", "scalar"))
def _vlookup(ctx, lookup, table, col, approx=None):
    return _table_lookup(ctx, lookup, table, col, approx, False)


@register("HLOOKUP", "lookup", 3, 4, ("scalar", "range", "scalar"))
def _hlookup(ctx, lookup, table, row, approx=None):
    return _table_lookup(ctx, lookup, table, row, approx, True)


@register("LOOKUP", "lookup", 2, 3, ("scalar", "range"))
def _lookup(ctx, lookup, where, result=None):
    if isinstance(lookup, ExcelError):
        return lookup
    area = c.as_area(where)
    nrows, ncols = area.shape
    if result is None:
        if ncols > nrows:
            keys, out = list(area.rows[0]), list(area.rows[-1])
        else:
            keys, out = [r[0] for r in area.rows], [r[-1] for r in area.rows]
    else:
        keys, out = _vector(area), _vector(c.as_area(result))
        if keys is None:  # a 2-D lookup area: its first column, or first row if wider
            keys = [r[0] for r in area.rows] if nrows >= ncols else list(area.rows[0])
        if out is None:
            return ExcelError.NA
    i = find(lookup, keys, 1)
    if i is None:
        return ExcelError.NA
    return out[i] if i < len(out) else ExcelError.NA


def _xfind(lookup, values, match_mode: int, search_mode: int):
    reverse = search_mode in (-1, -2)
    if match_mode == 0:
        return find(lookup, values, 0, wildcards=False, reverse=reverse)
    if match_mode == 2:
        return find(lookup, values, 2, reverse=reverse)
    return _nearest(lookup, values, match_mode, reverse)


def _modes(match_mode, search_mode):
    m, s = c.to_number(match_mode), c.to_number(search_mode)
    for x in (m, s):
        if isinstance(x, ExcelError):
            return x
    m, s = int(m), int(s)
    if m not in (-1, 0, 1, 2) or s not in (-2, -1, 1, 2):
        return ExcelError.VALUE
    return m, s


@register("XMATCH", "lookup", 2, 4, ("scalar", "range", "scalar"))
def _xmatch(ctx, lookup, where, match_mode=0.0, search_mode=1.0):
    if isinstance(lookup, ExcelError):
        return lookup
    modes = _modes(match_mode, search_mode)
    if isinstance(modes, ExcelError):
        return modes
    values = _vector(c.as_area(where))
    if values is None:
        return ExcelError.VALUE
    i = _xfind(lookup, values, *modes)
    return ExcelError.NA if i is None else float(i + 1)


@register("XLOOKUP", "lookup", 3, 6, ("scalar", "range", "range", "lazy"))
def _xlookup(ctx, lookup, where, result, if_not_found=None, match_mode=None,
             search_mode=None):
    lookup = ctx.scalar(lookup())
    if isinstance(lookup, ExcelError):
        return lookup
    modes = _modes(ctx.scalar(match_mode()) if match_mode else 0.0,
                   ctx.scalar(search_mode()) if search_mode else 1.0)
    if isinstance(modes, ExcelError):
        return modes
    area, out = c.as_area(where()), c.as_area(result())
    values = _vector(area)
    if values is None:
        return ExcelError.VALUE
    i = _xfind(lookup, values, *modes)
    if i is None:
        return if_not_found() if if_not_found is not None else ExcelError.NA
    nrows, ncols = out.shape
    if area.shape[1] == 1:  # a column: the matching row of the result
        return ExcelError.VALUE if i >= nrows else _sub(out, i, 0, i, ncols - 1)
    return ExcelError.VALUE if i >= ncols else _sub(out, 0, i, nrows - 1, i)


@register("CHOOSE", "lookup", 2, -1, "lazy")
def _choose(ctx, index, *options):
    i = c.to_number(ctx.scalar(index()))
    if isinstance(i, ExcelError):
        return i
    i = int(i)
    return options[i - 1]() if 1 <= i <= len(options) else ExcelError.VALUE


# -- the reference itself ------------------------------------------------------------------

def _position(ctx, v, axis: int):
    if v is None:
        if ctx.cell is None:
            return ExcelError.VALUE
        return float(ctx.cell[1 + axis])
    if not isinstance(v, Range) or v.ref is None:
        return ExcelError.VALUE
    ref = v.ref
    lo, hi = (ref.row1, ref.row2) if axis == 0 else (ref.col1, ref.col2)
    if lo == hi:
        return float(lo)
    values = [[float(i)] for i in range(lo, hi + 1)]
    return Range.array_of(values if axis == 0 else [sum(values, [])])


register("ROW", "lookup", 0, 1, "ref", position=True)(
    lambda ctx, v=None: _position(ctx, v, 0))
register("COLUMN", "lookup", 0, 1, "ref", position=True)(
    lambda ctx, v=None: _position(ctx, v, 1))


def _extent(v, axis):
    if isinstance(v, ExcelError):
        return v
    return float(v.shape[axis]) if isinstance(v, Range) else 1.0


register("ROWS", "lookup", 1, 1, "ref")(lambda ctx, v: _extent(v, 0))
register("COLUMNS", "lookup", 1, 1, "ref")(lambda ctx, v: _extent(v, 1))


@register("OFFSET", "lookup", 3, 5, ("ref", "scalar"), volatile=True)
def _offset(ctx, base, rows, cols, height=None, width=None):
    if isinstance(base, ExcelError):
        return base
    if not isinstance(base, Range) or base.ref is None:
        return ExcelError.VALUE
    ref = base.ref
    nums = [c.to_number(v) for v in (rows, cols)]
    h = c.to_number(height) if height is not None else float(ref.shape[0])
    w = c.to_number(width) if width is not None else float(ref.shape[1])
    bad = next((x for x in (*nums, h, w) if isinstance(x, ExcelError)), None)
    if bad is not None:
        return bad
    dr, dc, h, w = int(nums[0]), int(nums[1]), int(h), int(w)
    if h == 0 or w == 0:
        return ExcelError.REF
    r1, c1 = ref.row1 + dr, ref.col1 + dc
    r2, c2 = r1 + h - 1, c1 + w - 1
    r1, r2 = sorted((r1, r2))
    c1, c2 = sorted((c1, c2))
    return ctx.read(Ref(ref.sheet, r1, c1, r2, c2))


_R1C1 = re.compile(r"(?:'((?:[^']|'')+)'!|([^!'\[\]]+)!)?R(\d+)C(\d+)(?::R(\d+)C(\d+))?",
                   re.IGNORECASE)


def _r1c1_ref(text: str) -> Ref | None:
    m = _R1C1.fullmatch(text.strip())
    if m is None:
        return None
    sheet = m.group(1).replace("''", "'") if m.group(1) else m.group(2)
    r1, c1 = int(m.group(3)), int(m.group(4))
    r2, c2 = (int(m.group(5)), int(m.group(6))) if m.group(5) else (r1, c1)
    return Ref(sheet, min(r1, r2), min(c1, c2), max(r1, r2), max(c1, c2))


@register("INDIRECT", "lookup", 1, 2, volatile=True)
def _indirect(ctx, text, a1=True):
    t = c.to_text(text)
    if isinstance(t, ExcelError):
        return t
    style = c.to_bool(a1)
    if isinstance(style, ExcelError):
        return style
    if not style:
        target = _r1c1_ref(t)
    else:
        target = ctx.parse_ref(t) if ctx.parse_ref is not None else None
    if target is None:
        return ExcelError.REF
    return target if isinstance(target, (Range, ExcelError)) else ctx.read(target)


def _column_letters(col: int) -> str:
    out = ""
    while col:
        col, rem = divmod(col - 1, 26)
        out = chr(65 + rem) + out
    return out


@register("ADDRESS", "lookup", 2, 5)
def _address(ctx, row, col, absolute=1.0, a1=True, sheet=None):
    r, k, a = c.to_number(row), c.to_number(col), c.to_number(absolute)
    bad = next((x for x in (r, k, a) if isinstance(x, ExcelError)), None)
    if bad is not None:
        return bad
    style = c.to_bool(a1)
    if isinstance(style, ExcelError):
        return style
    r, k, a = int(r), int(k), int(a)
    if not (1 <= r <= 1_048_576 and 1 <= k <= 16_384) or a not in (1, 2, 3, 4):
        return ExcelError.VALUE
    row_abs, col_abs = a in (1, 2), a in (1, 3)
    if style:
        text = ("$" if col_abs else "") + _column_letters(k) + ("$" if row_abs else "") + str(r)
    else:
        text = (f"R{r}" if row_abs else f"R[{r}]") + (f"C{k}" if col_abs else f"C[{k}]")
    if sheet is not None:
        s = c.to_text(sheet)
        if isinstance(s, ExcelError):
            return s
        if s:
            quoted = s if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_.]*", s) else (
                "'" + s.replace("'", "''") + "'")
            text = f"{quoted}!{text}"
    return text


@register("TRANSPOSE", "lookup", 1, 1, "range")
def _transpose(ctx, v):
    area = c.as_area(v)
    return Range.array_of(zip(*area.rows)) if area.rows else area
