"""Lookup: INDEX, MATCH, VLOOKUP, HLOOKUP, LOOKUP, CHOOSE (XLOOKUP and XMATCH are in
:mod:`.xlookup`; the functions of references themselves, ROW .. INDIRECT, in
:mod:`.reference`).

Approximate lookups bisect, as Excel does: on sorted data the last position not past the
lookup value; on unsorted data where the bisection lands (descending data for MATCH's -1
is scanned down to the first value below the lookup value or past a run equal to it, as
Excel's results on pycel's lookup.xlsx show).
"""

from __future__ import annotations

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.dialect import exact_lookup
from workbook_gen.formula.functions.lookup.reference import union_area
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
    if mode > 0:
        return _bisect(lookup, values)
    # descending data (MATCH's -1): a scan from the top that stops below the lookup value
    # or after a run of values equal to it (the last of the run, as LibreOffice, and as
    # Excel's bisection for ascending data), as Excel's results on pycel's lookup.xlsx show
    # over ascending 0..4 (lookup -1: 5; 0.5, 2, 3, 4.5: #N/A; 0 or an empty cell: 1)
    found, equal = None, False
    for i, v in enumerate(values):
        if not _comparable(v, lookup):
            continue
        cmp = c.compare(v, lookup)
        if cmp < 0 or (equal and cmp > 0):
            break
        found, equal = i, cmp == 0
    return found


_INDEXES: dict[int, tuple] = {}  # id(rows) -> (rows, {key: first row}); rows are cached


def _key(v):
    """What exact lookup compares: type rank and value (text without case); None for
    blanks and errors, which never match."""
    if v is None or isinstance(v, ExcelError):
        return None
    rank = c.rank(v)
    return (rank, v.lower() if rank == 1 else bool(v) if rank == 2 else float(v))


def _exact_index(rows) -> dict:
    """{key: first row} of the first column of a table, built once per table (a table read
    from the workbook is one cached object): VLOOKUP(x, T, n, FALSE) x 10,000 stays linear."""
    hit = _INDEXES.get(id(rows))
    if hit is not None and hit[0] is rows:
        return hit[1]
    index: dict = {}
    for i, row in enumerate(rows):
        k = _key(row[0]) if row else None
        if k is not None and k not in index:
            index[k] = i
    if len(_INDEXES) > 256:
        _INDEXES.clear()
    _INDEXES[id(rows)] = (rows, index)
    return index


def _comparable(v, lookup) -> bool:
    return v is not None and not isinstance(v, ExcelError) and c.rank(v) == c.rank(lookup)


def _bisect(lookup, values: list, typed: bool = False):
    """Excel's approximate search, a bisection: on ascending data the last position not
    past ``lookup``; on unsorted data the position its bisection lands on, as Excel's
    (sheetjs' and POI's test files). An equal value ends the search at the last of its run.
    Empty cells are stepped over, and values of another type too unless ``typed`` (then
    Excel's order numbers < text < booleans decides, as XLOOKUP's binary search)."""
    def usable(v):
        if typed:
            return v is not None and not isinstance(v, ExcelError)
        return _comparable(v, lookup)
    lo, hi, found = 0, len(values) - 1, None
    while lo <= hi:
        mid = (lo + hi) // 2
        probe = mid
        v = values[mid]
        # a value of another type at mid: the one found stepping back is only a candidate,
        # even if equal (formulas test.xlsx LOOKUP!X60: LOOKUP("b",{"b",4.1,"a",1.1}) is
        # "a"; Y71: MATCH(TRUE,{TRUE,4.1,FALSE,1.1}) is 3)
        other = not typed and v is not None and not isinstance(v, ExcelError) and not usable(v)
        while probe >= lo and not usable(values[probe]):
            probe -= 1
        if probe < lo:
            lo = mid + 1
            continue
        cmp = c.compare(values[probe], lookup)
        if cmp == 0 and other:
            cmp = -1
        if cmp == 0:
            while probe + 1 < len(values) and usable(values[probe + 1]) and (
                    c.compare(values[probe + 1], lookup) == 0):
                probe += 1
            return probe
        if cmp < 0:
            found, lo = probe, mid + 1
        else:
            hi = probe - 1
    return found


def _vector(area: Range) -> list | None:
    """The values of a one-row or one-column area, else None."""
    rows, cols = area.shape
    if rows == 1:
        return list(area.rows[0])
    if cols == 1:
        return [r[0] for r in area.rows]
    return None


@register("MATCH", 2, 3, ("scalar", "range", "scalar"))
def _match(ctx, lookup, area, kind=1.0):
    if (e := c.first_error((lookup, area))) is not None:  # an array's #REF! too
        return e
    kind = c.to_number(kind)
    if isinstance(kind, ExcelError):
        return kind
    values = _vector(c.as_area(area))
    if values is None:
        return ExcelError.NA
    if lookup is None and kind == 0:
        return ExcelError.NA
    mode = 0 if kind == 0 else (1 if kind > 0 else -1)
    lookup, values = exact_lookup(ctx, lookup, values) if mode == 0 else (lookup, values)
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


@register("INDEX", 2, 4, ("ref", "scalar"))
def _index(ctx, area, row, col=None, part=1.0):
    area = c.as_area(area)
    r, k = c.to_number(row), (c.to_number(col) if col is not None else None)
    # an error as area_num is INDEX's error (Mac Excel's LOOKUP!AB54)
    bad = next((x for x in (r, k, part) if isinstance(x, ExcelError)), None)
    if bad is not None:
        return bad
    if area.areas and ctx is not None and ctx.dialect == "excel":
        area = union_area(area, c.to_number(part))  # area_num picks one area of a union
        if isinstance(area, ExcelError):        # (Mac Excel 16, LOOKUP!AQ52:AU53)
            return area
    nrows, ncols = area.shape
    r = int(r)
    k = int(k) if k is not None else None
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
    lookup, rows = (lookup, rows) if approx else exact_lookup(ctx, lookup, rows, first=True)
    if not approx and not by_rows and _exact_pattern(lookup) is None and lookup is not None:
        i = _exact_index(rows).get(_key(lookup))  # the first equal key: find()'s answer
    else:
        i = find(lookup, [r[0] for r in rows], 1 if approx else 0)
    return ExcelError.NA if i is None else rows[i][n - 1]


@register("VLOOKUP", 3, 4, ("scalar", "range", "scalar"))
def _vlookup(ctx, lookup, table, col, approx=None):
    return _table_lookup(ctx, lookup, table, col, approx, False)


@register("HLOOKUP", 3, 4, ("scalar", "range", "scalar"))
def _hlookup(ctx, lookup, table, row, approx=None):
    return _table_lookup(ctx, lookup, table, row, approx, True)


@register("LOOKUP", 2, 3, ("scalar", "range"))
def _lookup(ctx, lookup, where, result=None):
    if (e := c.first_error((lookup, where, result))) is not None:
        return e
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


@register("CHOOSE", 2, -1, "lazy")
def _choose(ctx, index, *options):
    i = c.to_number(ctx.scalar(index()))
    if isinstance(i, ExcelError):
        return i
    i = int(i)
    return options[i - 1]() if 1 <= i <= len(options) else ExcelError.VALUE
