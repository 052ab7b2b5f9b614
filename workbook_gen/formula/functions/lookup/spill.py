"""The dynamic-array operators Excel stores as functions: the spill reference ``A1#``
(``_xlfn.ANCHORARRAY(A1)``) and implicit intersection ``@x`` (``_xlfn.SINGLE(x)``).

* ``ANCHORARRAY(anchor)``: the range the array formula anchored at ``anchor`` fills,
  as the file records it (the ``ref`` of its ``<f t="array">``, a dynamic array's spill
  range); #REF! where the cell anchors no array. A formula Excel entered the old way
  (Ctrl+Shift+Enter) is taken as well: Excel's cached values do
  (ironcalc__dynamic_arrays.xlsx, M1 ``=CONCAT(K1#)`` over the legacy array K1:K3).
* ``SINGLE(x)``: one value, as Excel's formulas did before dynamic arrays: a reference
  intersected with the calling cell's row or column, an array's top-left value.

The anchor's area comes from the evaluation context's resolver (``spill_area(sheet,
row, col)``); the Resolver default knows no arrays.
"""

from __future__ import annotations

from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range, Ref
from workbook_gen.xlerror import ExcelError


@register("ANCHORARRAY", 1, 1, "ref")
def _anchorarray(ctx, anchor):
    if isinstance(anchor, ExcelError):
        return anchor
    if not isinstance(anchor, Range) or anchor.ref is None:
        return ExcelError.VALUE
    ref = anchor.ref
    end = ctx.workbook.spill_area(ref.sheet, ref.row1, ref.col1)
    if end is None:
        return ExcelError.REF
    return ctx.read(Ref(ref.sheet, ref.row1, ref.col1, *end))


@register("SINGLE", 1, 1, "range")
def _single(ctx, v):
    return ctx.scalar(v)
