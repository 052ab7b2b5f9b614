"""Information functions: IS* tests, NA, N, TYPE, ERROR.TYPE (T is in :mod:`..text.core`)."""

from __future__ import annotations

import numpy as np

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.callables import Closure, Function
from workbook_gen.formula.functions.registry import ARRAY_LIFTED, register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError


def _value(ctx, v):
    """IS* functions look at one value: a multi-cell reference is intersected."""
    return ctx.scalar(v) if isinstance(v, Range) else v


def _is(name, test, vector=None, libreoffice=None):
    """``libreoffice``: the test in LibreOffice's dialect, where it differs."""
    def fn(ctx, v):
        lo = libreoffice is not None and ctx is not None and ctx.dialect == "libreoffice"
        return (libreoffice if lo else test)(_value(ctx, v))
    register(name, 1, 1, "range", vector=vector)(fn)
    # in an array formula, one test per cell (formulas__test INFORMATION!AG7:AW18)
    ARRAY_LIFTED[name] = (0).__eq__


def _iserror_vector(xs, n):
    (_, e), = xs
    return (e != 0).astype(float), np.zeros(n, np.uint8), True


_is("ISERROR", lambda v: isinstance(v, ExcelError), _iserror_vector)
_is("ISERR", lambda v: isinstance(v, ExcelError) and v is not ExcelError.NA)
_is("ISNA", lambda v: v is ExcelError.NA)
# LibreOffice has no boolean type: a TRUE cell is a number (measured)
_is("ISNUMBER", c.is_number, libreoffice=lambda v: c.is_number(v) or isinstance(v, bool))
_is("ISTEXT", lambda v: isinstance(v, str))
_is("ISNONTEXT", lambda v: not isinstance(v, str))
_is("ISLOGICAL", lambda v: isinstance(v, bool))
_is("ISBLANK", lambda v: v is None)


@register("ISREF", 1, 1, "ref")
def _isref(ctx, v):
    return isinstance(v, Range) and v.ref is not None


@register("ISFORMULA", 1, 1, "ref")
def _isformula(ctx, v):
    """Does the cell hold a formula (for a range, each cell: an array)? A resolver that
    knows no formulas, a table of values, has none."""
    if isinstance(v, ExcelError):
        return v
    if not isinstance(v, Range) or v.ref is None:
        return ExcelError.VALUE
    ask = ctx.workbook.has_formula
    ref = v.ref
    if ref.shape == (1, 1):
        return bool(ask(ref.sheet, ref.row1, ref.col1))
    return Range.array_of([[bool(ask(ref.sheet, r, k)) for k in range(ref.col1, ref.col2 + 1)]
                           for r in range(ref.row1, ref.row2 + 1)])  # (each cell's)


def _parity(ctx, v, odd):
    if isinstance(v, bool) or (isinstance(v, (str, type(None)))
                               and ctx.dialect == "libreoffice"):
        return ExcelError.VALUE  # LibreOffice: any text and an empty cell too (measured)
    x = c.integer(v)
    if isinstance(x, ExcelError):
        return x
    return (x % 2 == 1) == odd


register("ISEVEN", 1, 1)(lambda ctx, v: _parity(ctx, v, False))
register("ISODD", 1, 1)(lambda ctx, v: _parity(ctx, v, True))
register("NA", 0, 0)(lambda ctx: ExcelError.NA)


@register("N", 1, 1, "range")
def _n(ctx, v):
    """A reference gives its first cell, as T (formulas__test INFORMATION!AH19:AW19:
    {=N(C19:Q19)} is N(C19) in every cell); LibreOffice intersects, as for T."""
    if isinstance(v, Range) and ctx.dialect == "libreoffice":
        v = ctx.scalar(v)
    elif isinstance(v, Range):
        v = v.rows[0][0] if v.rows and v.rows[0] else None
    if isinstance(v, ExcelError):
        return v
    if isinstance(v, bool):
        return float(v)
    return float(v) if c.is_number(v) else 0.0


@register("TYPE", 1, 1, "range")
def _type(ctx, v):
    if isinstance(v, Range) and v.shape != (1, 1):
        return 64.0
    v = c.scalar_of(v)
    if isinstance(v, ExcelError):
        return 16.0
    if isinstance(v, (Closure, Function)):  # a LAMBDA, or a function as a value: 128
        return 128.0                        # (Mac Excel 16: TYPE(_xleta.SUM), INFORMATION!S24)
    if isinstance(v, bool):
        return 1.0 if ctx.dialect == "libreoffice" else 4.0
    return 2.0 if isinstance(v, str) else 1.0


_ERROR_TYPES = {ExcelError.NULL: 1.0, ExcelError.DIV0: 2.0, ExcelError.VALUE: 3.0,
                ExcelError.REF: 4.0, ExcelError.NAME: 5.0, ExcelError.NUM: 6.0,
                ExcelError.NA: 7.0, ExcelError.GETTING_DATA: 8.0}


@register("ERROR.TYPE", 1, 1)
def _error_type(ctx, v):
    return _ERROR_TYPES.get(v, ExcelError.NA) if isinstance(v, ExcelError) else ExcelError.NA


# CELL: only the kinds of information the values hold; the others (format, width, color,
# filename...) and the omitted reference (Excel's last changed cell) are not computed:
# such calls count as unsupported, their cells "not checked".
_CELL_INFO = ("contents", "row", "col", "type")


def _cell_accepts(args) -> bool:
    from workbook_gen.formula import ast
    return (len(args) == 2 and isinstance(args[0], ast.String)
            and args[0].value.strip().lower() in _CELL_INFO
            and isinstance(args[1], (ast.CellRef, ast.RangeRef)))


@register("CELL", 1, 2, ("scalar", "ref"), accepts=_cell_accepts)
def _cell(ctx, info, ref=None):
    kind = c.to_text(info)
    if isinstance(kind, ExcelError):
        return kind
    kind = kind.strip().lower()
    if not isinstance(ref, Range) or ref.ref is None or kind not in _CELL_INFO:
        return ExcelError.VALUE
    if kind == "row":
        return float(ref.ref.row1)
    if kind == "col":
        return float(ref.ref.col1)
    first = ref.rows[0][0] if ref.rows and ref.rows[0] else None
    if kind == "contents":
        return 0.0 if first is None else first
    return "b" if first is None else "l" if isinstance(first, str) else "v"
