"""RANDARRAY (Excel 365): an array of random draws, a new one at every recalculation.

``RANDARRAY([rows], [columns], [min], [max], [whole_number])``, Microsoft's page: 1 row,
1 column, 0 and 1 when omitted; whole numbers with ``whole_number`` TRUE, decimals
otherwise; #VALUE! where min is greater than max. The audit checks a cell that is just
the call against this contract (:func:`workbook_gen.evaluator.volatile.check_array`);
computed here, the draws are only what the function may return.
"""

from __future__ import annotations

import math
import random

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

MAX_CELLS = 1_048_576


def contract(rows=None, cols=None, lo=None, hi=None, whole=None):
    """``(rows, columns, min, max, whole)`` of a call's (evaluated) arguments, or the
    ExcelError it returns."""
    values = []
    for v, default in ((rows, 1.0), (cols, 1.0), (lo, 0.0), (hi, 1.0)):
        x = c.number(v) if v is not None else default
        if isinstance(x, ExcelError):
            return x
        values.append(x)
    flag = c.to_bool(c.scalar_of(whole)) if whole is not None else False
    if isinstance(flag, ExcelError):
        return flag
    n_rows, n_cols, lo_, hi_ = int(values[0]), int(values[1]), values[2], values[3]
    if n_rows < 1 or n_cols < 1 or lo_ > hi_:
        return ExcelError.VALUE
    if n_rows * n_cols > MAX_CELLS:
        return ExcelError.NUM
    if flag:
        lo_, hi_ = float(math.ceil(lo_)), float(math.floor(hi_))
        if lo_ > hi_:
            return ExcelError.VALUE
    return n_rows, n_cols, lo_, hi_, bool(flag)


@register("RANDARRAY", 0, 5, volatile=True, omitted=True)
def _randarray(ctx, rows=None, cols=None, lo=None, hi=None, whole=None):
    found = contract(rows, cols, lo, hi, whole)
    if isinstance(found, ExcelError):
        return found
    n_rows, n_cols, lo, hi, whole = found

    def draw():
        return float(random.randint(int(lo), int(hi))) if whole else random.uniform(lo, hi)
    return Range.array_of([[draw() for _ in range(n_cols)] for _ in range(n_rows)])
