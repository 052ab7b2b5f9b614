"""Arguments and results of the dynamic-array functions (Excel 365), shared by the lookup,
text and math families: an argument not given (:data:`OMITTED`), an array argument as rows,
a whole-number argument, an array result (an empty one is #CALC!: Excel has no empty
array)."""

from __future__ import annotations

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

MAX_CELLS = 1_048_576
OMITTED = object()  # an argument not given (an empty cell given is None: 0)


def as_grid(v) -> list[list] | ExcelError:
    if isinstance(v, ExcelError):
        return v
    if isinstance(v, Range):
        return [list(r) for r in v.rows] if v.rows and v.rows[0] else ExcelError.CALC
    return [[v]]


def array_result(rows: list[list]):
    if not rows or not rows[0]:
        return ExcelError.CALC
    return Range.array_of(rows)


def whole_arg(v, default=None):
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


def whole_args(*vs):
    out = []
    for v in vs:
        if isinstance(v, ExcelError):
            return v
        out.append(v)
    return out
