"""SHEET and SHEETS: the place of a sheet among the workbook's sheets, and how many there are
(Excel's Information functions). They read the workbook through the resolver
(``sheet_number``, ``sheet_count``); #N/A where it cannot tell."""

from __future__ import annotations

from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError


def _not_3d(args) -> bool:
    """The calls evaluated: not of a 3-D reference (Sheet1:Sheet3!A1)."""
    from workbook_gen.formula import ast
    return not any(isinstance(a, ast.Sheets3D) for a in args)


def _sheets_accepts(args) -> bool:
    from workbook_gen.formula import ast
    return all(isinstance(a, (ast.CellRef, ast.RangeRef, ast.Name, ast.StructRef))
               for a in args)


@register("SHEET", 0, 1, "ref", accepts=_not_3d)
def _sheet(ctx, v=None):
    """The place of a sheet among all the workbook's sheets (chart sheets included):
    of the calling cell's sheet, of a reference's, or of the sheet a text names (any
    case); #N/A for a text naming no sheet and for a number (ironcalc tables.xlsx)."""
    number = ctx.workbook.sheet_number
    if ctx.workbook.sheet_count() is None:  # the workbook's sheets are not known
        return ExcelError.NA
    if v is None:
        found = number(ctx.cell[0] if ctx.cell else None)
    elif isinstance(v, ExcelError):
        return v
    elif isinstance(v, Range) and v.ref is not None:
        found = number(v.ref.sheet or (ctx.cell[0] if ctx.cell else None))
    elif isinstance(v, str):
        found = number(v)
    else:
        return ExcelError.NA
    return ExcelError.NA if found is None else float(found)


@register("SHEETS", 0, 1, "ref", accepts=_sheets_accepts)
def _sheets(ctx, v=None):
    """The number of sheets in the workbook (no argument) or in a reference (1)."""
    if v is None:
        count = ctx.workbook.sheet_count()
        return ExcelError.NA if count is None else float(count)
    if isinstance(v, ExcelError):
        return v
    return 1.0 if isinstance(v, Range) and v.ref is not None else ExcelError.VALUE
