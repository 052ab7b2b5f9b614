"""PERCENTOF (Excel 365): the share a subset makes of a whole, ``SUM(data_subset) /
SUM(data_all)`` (Microsoft's "PERCENTOF function": "logically equivalent to
=SUM(data_subset)/SUM(data_all)"), with SUM's coercion: a range keeps only its numbers
(text, booleans and empty cells skipped), a direct argument converts.

An error value in either argument is #NUM!, not the error itself: Microsoft Excel cached
#NUM! for every such call in formulas__test.xlsx (MATH & TRIG!W49:AF49, errors in the subset,
in the whole, or both). A whole summing to 0 is #DIV/0!. GROUPBY and PIVOTBY call it with
the group's values and all values (:mod:`..lookup.groupby`)."""

from __future__ import annotations

from math import fsum

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError


@register("PERCENTOF", 2, 2, "range", range_numbers=True)
def _percentof(ctx, data_subset, data_all):
    part, whole = c.numbers([data_subset], ctx), c.numbers([data_all], ctx)
    if isinstance(part, ExcelError) or isinstance(whole, ExcelError):
        return ExcelError.NUM
    total = fsum(whole)
    if total == 0:
        return ExcelError.DIV0
    return c.result(fsum(part) / total)
