"""SUBTOTAL and AGGREGATE: a function of the list (1-11, or 1-19 for AGGREGATE) over
references, leaving out what the sheet's layout says to leave out.

Excel's documented rules:

* nested subtotals: a cell of a reference that itself holds a SUBTOTAL or AGGREGATE
  formula is left out (always for SUBTOTAL; for AGGREGATE with options 0-3), so that a
  grand total over a column of subtotals does not count twice;
* hidden rows: left out by SUBTOTAL 101-111 and by AGGREGATE with options 1, 3, 5, 7
  (hidden columns never are); rows a filter hid are left out by every SUBTOTAL ("ignores
  any rows that are not included in the result of a filter, no matter which
  function_num value you use"); AGGREGATE leaves them out only with the options that
  leave out hidden rows (option 4 "ignore nothing"; LibreOffice likewise);
* errors: AGGREGATE with options 2, 3, 6, 7 leaves error values out; otherwise the
  function meets them as usual (the first error is the result);
* AGGREGATE's variances (7 STDEV.S, 8 STDEV.P, 10 VAR.S, 11 VAR.P) are Excel's one-pass
  sums of x and x^2 in cell order, not the two-pass form of the VAR functions themselves:
  (S2 - S^2/n)/(n-1) and (n S2 - S^2)/n^2, measured on the Excel-saved ClosedXML file
  functions-excel-2010.xlsx (Sheet2 rows 17-25: every one of the 24 variance cells equals
  these to the bit; the two-pass form differs in the last bits where 12.545... enters);
* AGGREGATE 14-19 (LARGE, SMALL, PERCENTILE.INC, QUARTILE.INC, PERCENTILE.EXC,
  QUARTILE.EXC) take one array or reference and the k argument.

What the layout is comes from the evaluation context's resolver (``hidden_rows(sheet)``,
``filtered_rows(sheet)``, the hidden rows below a filtering autoFilter's header:
:mod:`workbook_gen.xlsx.filters`, and ``subtotal_cells(sheet)``); the Resolver defaults
(a bare value table) hide nothing.
"""

from __future__ import annotations

import math

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.registry import REGISTRY, register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

_SUBTOTAL = {1: "AVERAGE", 2: "COUNT", 3: "COUNTA", 4: "MAX", 5: "MIN", 6: "PRODUCT",
             7: "STDEV", 8: "STDEVP", 9: "SUM", 10: "VAR", 11: "VARP"}
_AGGREGATE = {**_SUBTOTAL, 12: "MEDIAN", 13: "MODE.SNGL", 14: "LARGE", 15: "SMALL",
              16: "PERCENTILE.INC", 17: "QUARTILE.INC", 18: "PERCENTILE.EXC",
              19: "QUARTILE.EXC"}
# read the sheet's layout (hidden rows, which cells hold subtotals): evaluated cell by cell
READS_LAYOUT = frozenset({"SUBTOTAL", "AGGREGATE",
                          "CHAR", "CODE"})  # (the workbook's character set: text.py)


def _left_out(ctx, arg, hidden: bool, nested: bool, errors: bool, filtered: bool = False):
    """``arg`` with the cells to leave out made empty: rows hidden (``hidden``; else with
    ``filtered`` the rows a filter hid), cells holding SUBTOTAL/AGGREGATE (``nested``) of a
    reference, error values (``errors``)."""
    if not isinstance(arg, Range):
        return None if errors and isinstance(arg, ExcelError) else arg
    ref, book = arg.ref, ctx.workbook
    drop: set[tuple[int, int]] = set()
    if ref is not None:
        n_rows, n_cols = arg.shape
        if hidden or filtered:
            rows_of = book.hidden_rows if hidden else book.filtered_rows
            rows = [r - ref.row1 for r in rows_of(ref.sheet)
                    if ref.row1 <= r <= ref.row2 and r - ref.row1 < n_rows]
            drop.update((i, j) for i in rows for j in range(n_cols))
        if nested:
            drop.update((r - ref.row1, k - ref.col1)
                        for r, k in book.subtotal_cells(ref.sheet)
                        if ref.row1 <= r < ref.row1 + n_rows
                        and ref.col1 <= k < ref.col1 + n_cols)
    if not drop and (not errors or ExcelError not in set(map(type, arg.flat()))):
        return arg
    rows = [[None if (i, j) in drop or (errors and isinstance(v, ExcelError)) else v
             for j, v in enumerate(row)] for i, row in enumerate(arg.rows)]
    return Range.of(rows, ref) if ref is not None else Range.array_of(rows)


def _one_pass(ctx, args, sample: bool, root: bool):
    xs = c.numbers(args, ctx)
    if isinstance(xs, ExcelError):
        return xs
    n = len(xs)
    if n - sample <= 0:
        return ExcelError.DIV0
    s = s2 = 0.0
    for x in xs:  # plain double sums, in cell order
        s += x
        s2 += x * x
    var = (s2 - s * s / n) / (n - 1) if sample else (n * s2 - s * s) / (n * n)
    var = max(var, 0.0)
    return c.result(math.sqrt(var) if root else var)


_ONE_PASS = {7: (True, True), 8: (False, True), 10: (True, False), 11: (False, False)}


def _number(v):
    x = c.to_number(v)
    return x if isinstance(x, ExcelError) else int(x)


@register("SUBTOTAL", 2, -1, ("scalar", "range"))
def _subtotal(ctx, which, *refs):
    k = _number(which)
    if isinstance(k, ExcelError):
        return k
    name = _SUBTOTAL.get(k % 100) if k in _SUBTOTAL or k - 100 in _SUBTOTAL else None
    if name is None:
        return ExcelError.VALUE
    refs = tuple(_left_out(ctx, r, k > 100, True, False, True) for r in refs)
    return REGISTRY[name].fn(ctx, *refs)


@register("AGGREGATE", 3, -1, ("scalar", "scalar", "range"))
def _aggregate(ctx, which, options, *args):
    k, opt = _number(which), _number(0.0 if options is None else options)
    for v in (k, opt):
        if isinstance(v, ExcelError):
            return v
    name = _AGGREGATE.get(k)
    if name is None or not 0 <= opt <= 7:
        return ExcelError.VALUE
    hidden, errors, nested = opt in (1, 3, 5, 7), opt in (2, 3, 6, 7), opt <= 3
    if k >= 14:  # the array form: one array or reference, then k
        if len(args) != 2:
            return ExcelError.VALUE
        data = _left_out(ctx, args[0], hidden, nested, errors)
        return REGISTRY[name].fn(ctx, data, c.scalar_of(args[1]))
    if ctx.dialect == "excel" and any(isinstance(a, Range) and a.ref is None for a in args):
        return ExcelError.VALUE  # Excel's reference form takes references only (LibreOffice
        # also takes an array: AGGREGATE(9,6,A1:A3/(B1:B3="ok")) is 12 there, measured 7.4)
    args = tuple(_left_out(ctx, a, hidden, nested, errors) for a in args)
    if k in _ONE_PASS:
        return _one_pass(ctx, args, *_ONE_PASS[k])
    return REGISTRY[name].fn(ctx, *args)
