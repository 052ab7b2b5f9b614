"""SUMIF and SUMIFS: the sum of the cells where every criterion holds (criteria in
:mod:`..criteria`)."""

from __future__ import annotations

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.criteria import ifs, picked
from workbook_gen.formula.functions.math.core import fsum
from workbook_gen.formula.functions.registry import ARRAY_LIFTED, register
from workbook_gen.xlerror import ExcelError


@register("SUMIF", 2, 3, "range")
def _sumif(ctx, rng, crit, target=None):
    xs = picked(ctx, rng if target is None else target, [(rng, crit)])
    return xs if isinstance(xs, ExcelError) else c.result(fsum(xs))


register("SUMIFS", 3, -1, "range")(ifs(fsum, 0.0))

# an array of criteria in an array formula gives one result per criterion (as COUNTIF's,
# statistical/core.py)
ARRAY_LIFTED.update({"SUMIF": (1).__eq__, "SUMIFS": lambda i: i >= 2 and i % 2 == 0})
