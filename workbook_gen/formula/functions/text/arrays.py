"""The text functions of Excel 365 that make or read arrays: TEXTBEFORE, TEXTAFTER,
TEXTSPLIT, VALUETOTEXT, ARRAYTOTEXT. Arguments that are arrays arrive whole (kind
``range``); an array result is an array Range that the formula spills."""

from __future__ import annotations

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.arrayargs import OMITTED, array_result, as_grid, whole_arg
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError


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
    k = whole_arg(instance, 1)
    mode = whole_arg(match_mode, 0)
    end = whole_arg(match_end, 0)
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


@register("TEXTBEFORE", 2, 6, ("scalar", "range", "scalar"))
def _textbefore(ctx, text, delimiter, instance=OMITTED, match_mode=OMITTED,
                match_end=OMITTED, if_not_found=OMITTED):
    return _before_after(text, delimiter, instance, match_mode, match_end, if_not_found, False)


@register("TEXTAFTER", 2, 6, ("scalar", "range", "scalar"))
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


@register("VALUETOTEXT", 1, 2)
def _valuetotext(ctx, value, fmt=OMITTED):
    f = whole_arg(fmt, 0)
    if isinstance(f, ExcelError):
        return f
    if f not in (0, 1):
        return ExcelError.VALUE
    return _value_text(value, f == 1)


@register("ARRAYTOTEXT", 1, 2, ("range", "scalar"))
def _arraytotext(ctx, array, fmt=OMITTED):
    f = whole_arg(fmt, 0)
    if isinstance(f, ExcelError):
        return f
    if f not in (0, 1):
        return ExcelError.VALUE
    grid = as_grid(array)
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


@register("TEXTSPLIT", 2, 6, ("scalar", "range", "range", "scalar", "scalar",
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
    mode = whole_arg(match_mode, 0)
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
    return array_result([r + [fill] * (width - len(r)) for r in grid])
