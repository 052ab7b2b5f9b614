"""References themselves: ROW, COLUMN, ROWS, COLUMNS, AREAS, OFFSET and INDIRECT (volatile, and
evaluated), ADDRESS, TRANSPOSE, FORMULATEXT, HYPERLINK (SHEET and SHEETS, Excel's
information functions, are in :mod:`..information.sheets`). A reference argument is a Range
with ``.ref``."""

from __future__ import annotations

import re

from workbook_gen.cellref import column_letters
from workbook_gen.errors import WorkbookGenError
from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range, Ref
from workbook_gen.xlerror import ExcelError


# -- the reference itself ------------------------------------------------------------------

def _position(ctx, v, axis: int):
    if v is None:
        if ctx.cell is None:
            return ExcelError.VALUE
        return float(ctx.cell[1 + axis])
    if isinstance(v, ExcelError) and ctx.dialect == "excel":  # e.g. an empty intersection's
        return v                            # #NULL! (formulas__test.xlsx LOOKUP!AG13)
    if not isinstance(v, Range) or v.ref is None:
        return ExcelError.VALUE
    ref = v.ref
    lo, hi = (ref.row1, ref.row2) if axis == 0 else (ref.col1, ref.col2)
    if lo == hi:
        return float(lo)
    values = [[float(i)] for i in range(lo, hi + 1)]
    return Range.array_of(values if axis == 0 else [sum(values, [])])


register("ROW", 0, 1, "ref", position=True)(
    lambda ctx, v=None: _position(ctx, v, 0))
register("COLUMN", 0, 1, "ref", position=True)(
    lambda ctx, v=None: _position(ctx, v, 1))


def _extent(ctx, v, axis):
    if isinstance(v, ExcelError):
        return v
    if isinstance(v, Range) and len(v.areas) > 1:  # a union: #REF! in Excel (formulas__test
        return ExcelError.REF if ctx.dialect == "excel" else ExcelError.VALUE  # LOOKUP!S15)
    return float(v.shape[axis]) if isinstance(v, Range) else 1.0


def union_area(union: Range, part) -> Range | ExcelError:
    """Area ``part`` (1-based) of a union, with its values and reference; #REF! beyond."""
    if isinstance(part, ExcelError):
        return part
    n = int(part)
    if not 1 <= n <= len(union.areas):
        return ExcelError.REF
    start = sum(a.shape[0] * a.shape[1] for a in union.areas[:n - 1])
    ref = union.areas[n - 1]
    height, width = ref.shape
    values = [v for row in union.rows[start:start + height * width] for v in row]
    return Range.of([values[i * width:(i + 1) * width] for i in range(height)], ref)


@register("AREAS", 1, 1, "ref")
def _areas(ctx, v):
    """How many areas a reference has: a union's, else 1; #VALUE! for no reference."""
    if isinstance(v, ExcelError):
        return v
    if not isinstance(v, Range) or (v.ref is None and not v.areas):
        return ExcelError.VALUE
    return float(len(v.areas) or 1)


register("ROWS", 1, 1, "ref")(lambda ctx, v: _extent(ctx, v, 0))
register("COLUMNS", 1, 1, "ref")(lambda ctx, v: _extent(ctx, v, 1))


@register("OFFSET", 3, 5, ("ref", "scalar"), volatile=True, omitted=True)
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


@register("INDIRECT", 1, 2, volatile=True)
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




_OMITTED = object()


@register("ADDRESS", 2, 5)
def _address(ctx, row, col, absolute=1.0, a1=True, sheet=_OMITTED):
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
        text = ("$" if col_abs else "") + column_letters(k) + ("$" if row_abs else "") + str(r)
    else:
        text = (f"R{r}" if row_abs else f"R[{r}]") + (f"C{k}" if col_abs else f"C[{k}]")
    if sheet is not _OMITTED:
        s = "" if sheet is None else c.to_text(sheet)
        if isinstance(s, ExcelError):
            return s
        if not s and ctx.dialect == "excel":  # Excel writes the empty sheet name's "!"
            return f"!{text}"                 # (formulas__test.xlsx LOOKUP!S3)
        if s:
            quoted = s if re.fullmatch(r"(\[[^\]]+\])?[A-Za-z_][A-Za-z0-9_.]*", s) else (
                "'" + s.replace("'", "''") + "'")
            text = f"{quoted}!{text}"
    return text


@register("TRANSPOSE", 1, 1, "range")
def _transpose(ctx, v):
    area = c.as_area(v)
    return Range.array_of(zip(*area.rows)) if area.rows else area


# -- FORMULATEXT ---------------------------------------------------------------------------

_HIDDEN_PREFIXES = ("_xlfn._xlws.", "_xlfn.", "_xlws.", "_xlpm.", "_xleta.")
MAX_FORMULA = 8192  # characters of a formula (Excel's limit; FORMULATEXT: #N/A beyond)


def display_text(stored: str) -> str:
    """A formula as Excel shows it: the file's text without the prefixes of functions
    newer than Excel 2007 (``_xlfn.``) and of LAMBDA parameters (``_xlpm.``); strings
    and everything else as stored."""
    from workbook_gen.formula.tokenizer import FUNC, NAME, tokenize
    out = []
    for token in tokenize(stored):
        text = token.text
        if token.kind in (FUNC, NAME):
            for prefix in _HIDDEN_PREFIXES:
                if text[:len(prefix)].lower() == prefix:
                    text = text[len(prefix):]
                    break
        out.append(text)
    return "".join(out)


@register("FORMULATEXT", 1, 1, "ref")
def _formulatext(ctx, v):
    """The formula of the (top-left) cell referred to, as text; #N/A for a cell without
    a formula; a CSE array formula's in braces."""
    if isinstance(v, ExcelError):
        return v
    if not isinstance(v, Range) or v.ref is None:
        return ExcelError.VALUE
    ref = v.ref
    found = ctx.workbook.formula_text(ref.sheet, ref.row1, ref.col1)
    if found is None:
        return ExcelError.NA
    stored, array = found
    try:
        text = "=" + display_text(stored.lstrip("="))
    except WorkbookGenError:  # (a text the tokenizer refuses: as stored)
        text = "=" + stored.lstrip("=")
    if array:
        text = "{" + text + "}"
    return text if len(text) <= MAX_FORMULA else ExcelError.NA


# -- HYPERLINK -----------------------------------------------------------------------------

_NOT_GIVEN = object()


@register("HYPERLINK", 1, 2)
def _hyperlink(ctx, link, friendly=_NOT_GIVEN):
    """The text the cell shows: the friendly name, else the link; an empty cell shows 0
    (Excel, ironcalc link_test.xlsx: HYPERLINK("https://"&E21,E21) with E21 empty)."""
    shown = link if friendly is _NOT_GIVEN else friendly
    return 0.0 if shown is None else shown
