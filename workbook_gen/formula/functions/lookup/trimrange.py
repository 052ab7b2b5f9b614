"""TRIMRANGE (Excel 365, Microsoft's "TRIMRANGE function"): a range or array without the
blank rows and columns at its outer edges. ``trim_rows`` and ``trim_cols``: 0 none, 1 the
leading ones, 2 the trailing ones, 3 both (the default). A reference stays a reference (the
trimmed rectangle of the same sheet), an array stays an array.

Blank is an empty cell. What Microsoft Excel cached in formulas__test.xlsx
(LOOKUP!R135:AG136) settles what the page leaves open: an option given as text converts
("3" is 3), a fraction (2.3, "3.3") or an array of options is #VALUE!, and a range blank
throughout is #REF!.

The trim references (``A1.:.E10`` trims both ends, ``A1:.E10`` the trailing blanks,
``A1.:E10`` the leading ones; Excel saves them as ``_xlfn._TRO_ALL``, ``_TRO_TRAILING``,
``_TRO_LEADING`` of the plain range) are TRIMRANGE with the same option for rows and
columns: 3, 2 and 1."""

from __future__ import annotations

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.arrayargs import OMITTED
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range, Ref
from workbook_gen.xlerror import ExcelError


def _option(v):
    """0..3 from an option: omitted is 3, an empty cell 0; a fraction or an array #VALUE!."""
    if v is OMITTED:
        return 3
    if isinstance(v, Range):
        if v.shape != (1, 1):
            return ExcelError.VALUE
        v = v.rows[0][0]
    if v is None:
        return 0
    x = c.to_number(v)
    if isinstance(x, ExcelError):
        return x
    if x != int(x) or not 0 <= x <= 3:
        return ExcelError.VALUE
    return int(x)


def _span(filled: list[bool], how: int) -> tuple[int, int] | None:
    """First and last line kept of lines marked filled, trimming as ``how`` says."""
    if not any(filled):
        return None
    first = filled.index(True) if how & 1 else 0
    last = len(filled) - 1 - filled[::-1].index(True) if how & 2 else len(filled) - 1
    return first, last


def trimmed(rng, trim_rows=3, trim_cols=3):
    """``rng`` (a Range, or one value) trimmed: a Range, or #REF! when it is all blank."""
    if isinstance(rng, ExcelError):
        return rng
    if not isinstance(rng, Range):
        return ExcelError.REF if rng is None else rng
    if len(rng.areas) > 1:
        return ExcelError.VALUE
    rows = rng.rows
    rows_span = _span([any(v is not None for v in r) for r in rows], trim_rows)
    cols_span = _span([any(r[j] is not None for r in rows) for j in range(rng.shape[1])],
                      trim_cols)
    if rows_span is None or cols_span is None:
        return ExcelError.REF
    (r1, r2), (c1, c2) = rows_span, cols_span
    kept = [list(r[c1:c2 + 1]) for r in rows[r1:r2 + 1]]
    if rng.ref is None:
        return Range.array_of(kept)
    ref = rng.ref
    return Range.of(kept, Ref(ref.sheet, ref.row1 + r1, ref.col1 + c1,
                              ref.row1 + r2, ref.col1 + c2))


@register("TRIMRANGE", 1, 3, ("ref", "range", "range"))
def _trimrange(ctx, rng, trim_rows=OMITTED, trim_cols=OMITTED):
    how = [_option(v) for v in (trim_rows, trim_cols)]
    bad = next((h for h in how if isinstance(h, ExcelError)), None)
    if bad is not None:
        return bad
    return trimmed(rng, *how)


register("_TRO_ALL", 1, 1, "ref")(lambda ctx, rng: trimmed(rng, 3, 3))
register("_TRO_TRAILING", 1, 1, "ref")(lambda ctx, rng: trimmed(rng, 2, 2))
register("_TRO_LEADING", 1, 1, "ref")(lambda ctx, rng: trimmed(rng, 1, 1))
