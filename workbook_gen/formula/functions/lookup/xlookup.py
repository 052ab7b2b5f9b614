"""Lookup: XLOOKUP and XMATCH (Excel 365's lookups: match modes exact, next smaller,
next larger and wildcard, search first-to-last, last-to-first and binary both ways), with
the helpers they share; MATCH, INDEX and the older lookups are in :mod:`.core`."""

from __future__ import annotations

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.lookup.core import _bisect, _sub, _vector, find
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError


def _xcompare(v, lookup) -> int:
    """XLOOKUP/XMATCH's order over every type: numbers < text < FALSE < TRUE, text
    without case (casefolded: "ß" is "ss"); an empty lookup value is past everything
    (formulas__test.xlsx LOOKUP!W171:Y197, EXTRA!L75)."""
    if lookup is None:
        return -1
    ra, rb = c.rank(v), c.rank(lookup)
    if ra != rb:
        return -1 if ra < rb else 1
    if ra == 1:
        a, b = v.casefold(), lookup.casefold()
        return (a > b) - (a < b)
    return c.compare(v, lookup)


def _nearest(lookup, values: list, mode: int, reverse: bool):
    """XLOOKUP/XMATCH modes 0, -1, 1: exact, else the next smaller / larger (any order,
    across types in :func:`_xcompare`'s order)."""
    best = None
    order = range(len(values) - 1, -1, -1) if reverse else range(len(values))
    for i in order:
        v = values[i]
        if v is None or isinstance(v, ExcelError):
            continue
        cmp = _xcompare(v, lookup)
        if cmp == 0:
            return i
        if (cmp < 0 and mode < 0) or (cmp > 0 and mode > 0):
            if best is None or _xcompare(v, values[best]) == (1 if mode < 0 else -1):
                best = i
    return best


def _bisect_down(lookup, values: list, mode: int):
    """XLOOKUP/XMATCH's binary search over descending data (search mode -2): an equal
    value, else (``mode`` -1) the last probe below the lookup value or (1) the last probe
    above it; on data not in that order, where the bisection lands (formulas__test.xlsx
    EXTRA!K80, L87, L92)."""
    lo, hi, below, above = 0, len(values) - 1, None, None
    while lo <= hi:
        mid = (lo + hi) // 2
        probe = mid
        while probe >= lo and (values[probe] is None or isinstance(values[probe], ExcelError)):
            probe -= 1
        if probe < lo:
            lo = mid + 1
            continue
        cmp = _xcompare(values[probe], lookup)
        if cmp == 0:
            return probe
        if cmp > 0:
            above, lo = probe, mid + 1
        else:
            below, hi = probe, probe - 1
    return None if mode == 0 else below if mode < 0 else above


def _xfind(lookup, values, match_mode: int, search_mode: int):
    if search_mode == 2 and lookup is None:  # past everything: the last value or nothing
        last = next((i for i in range(len(values) - 1, -1, -1) if values[i] is not None
                     and not isinstance(values[i], ExcelError)), None)
        return last if match_mode < 0 else None
    if search_mode == 2 and match_mode != 2:  # binary search over ascending data
        i = _bisect(lookup, values, typed=True)
        if i is not None and c.compare(values[i], lookup) == 0:
            return i
        if match_mode == 0:
            return None
        if match_mode < 0:
            return i
        j = 0 if i is None else i + 1
        return j if j < len(values) else None
    if search_mode == -2:
        return _bisect_down(lookup, values, match_mode)
    reverse = search_mode == -1
    if match_mode == 0:
        return None if lookup is None else _nearest(lookup, values, 0, reverse)
    if match_mode == 2:
        return find(lookup, values, 2, reverse=reverse)
    if match_mode == 3:  # Excel 365's regular expression match (REGEXTEST's rule: a match
        return _regex_find(lookup, values, reverse)  # anywhere in the value's text)
    return _nearest(lookup, values, match_mode, reverse)


def _regex_find(lookup, values: list, reverse: bool):
    import re
    pattern = c.to_text(lookup)
    if isinstance(pattern, ExcelError):
        return pattern
    try:
        rx = re.compile(pattern)
    except (re.error, OverflowError):
        return ExcelError.VALUE
    order = range(len(values) - 1, -1, -1) if reverse else range(len(values))
    for i in order:
        v = values[i]
        if v is not None and not isinstance(v, ExcelError) and rx.search(c.to_text(v)):
            return i
    return None


def _modes(match_mode, search_mode):
    m, s = c.to_number(match_mode), c.to_number(search_mode)
    for x in (m, s):
        if isinstance(x, ExcelError):
            return x
    m, s = int(m // 1), int(s // 1)  # down: -1.1 is -2 (Mac Excel 16, formulas__test LOOKUP!AH162)
    if m not in (-1, 0, 1, 2, 3) or s not in (-2, -1, 1, 2) or (m >= 2 and s in (-2, 2)):
        return ExcelError.VALUE  # (wildcards or a regex with a binary search: #VALUE!)
    return m, s


@register("XMATCH", 2, 4, ("scalar", "range", "scalar"))
def _xmatch(ctx, lookup, where, match_mode=0.0, search_mode=1.0):
    if (e := c.first_error((lookup, where))) is not None:
        return e
    modes = _modes(match_mode, search_mode)
    if isinstance(modes, ExcelError):
        return modes
    values = _vector(c.as_area(where))
    if values is None:
        return ExcelError.VALUE
    i = _xfind(lookup, values, *modes)
    if isinstance(i, ExcelError):
        return i
    return ExcelError.NA if i is None else float(i + 1)


@register("XLOOKUP", 3, 6, ("scalar", "range", "range", "lazy", "scalar", "scalar"))
def _xlookup(ctx, lookup, where, result, if_not_found=None, match_mode=None,
             search_mode=None):
    lookup = ctx.scalar(lookup())
    if isinstance(lookup, ExcelError):
        return lookup
    modes = _modes(ctx.scalar(match_mode()) if match_mode else 0.0,
                   ctx.scalar(search_mode()) if search_mode else 1.0)
    if isinstance(modes, ExcelError):
        return modes
    area, out = where(), result()
    if (e := c.first_error((area, out))) is not None:  # a #REF! for an array
        return e
    area, out = c.as_area(area), c.as_area(out)
    values = _vector(area)
    if values is None:
        return ExcelError.VALUE
    i = _xfind(lookup, values, *modes)
    if isinstance(i, ExcelError):
        return i
    if i is None:
        return if_not_found() if if_not_found is not None else ExcelError.NA
    nrows, ncols = out.shape
    if area.shape[1] == 1:  # a column: the matching row of the result
        return ExcelError.VALUE if i >= nrows else _sub(out, i, 0, i, ncols - 1)
    return ExcelError.VALUE if i >= ncols else _sub(out, 0, i, nrows - 1, i)
