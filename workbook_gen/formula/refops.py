"""Values of the reference nodes beyond a plain cell or range: array constants, 3-D
references, the reference operators (``:``, space, ``,``) and unresolved structured
references, for the scalar evaluator.

A reference is ``(sheet, row1, col1, row2, col2)``; the values of a 3-D reference or a
union are their areas' values in one column (what SUM, COUNT, MAX ... need); a
structured reference the evaluator meets was not resolved against the workbook's tables
and is #REF!.
"""

from __future__ import annotations

from workbook_gen.formula import ast
from workbook_gen.formula import values as xv
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

Rect = tuple  # (sheet | None, row1, col1, row2, col2)


def array_value(node: ast.Array) -> Range:
    rows = [[_literal(v) for v in row] for row in node.rows]
    maker = getattr(Range, "array_of", Range.of)
    return maker(rows)


def _literal(node):
    if isinstance(node, ast.ErrorLit):
        return node.error
    return node.value


def rect_of(node) -> Rect | None:
    """The rectangle of a plain reference node, or None."""
    if isinstance(node, ast.CellRef):
        return (node.sheet, node.row, node.col, node.row, node.col)
    if isinstance(node, ast.RangeRef):
        r1, r2 = sorted((node.first.row, node.last.row))
        c1, c2 = sorted((node.first.col, node.last.col))
        return (node.sheet, r1, c1, r2, c2)
    return None


def _rect(ev, node) -> Rect | None | ExcelError:
    """The rectangle a reference-valued node stands for (evaluating INDEX, OFFSET ...)."""
    while isinstance(node, ast.Paren):
        node = node.inner
    rect = rect_of(node)
    if rect is not None:
        return rect
    if isinstance(node, ast.RefOp) and node.op in (":", " "):
        return _combine(ev, node)
    value = ev.arg(node)
    if isinstance(value, ExcelError):
        return value
    ref = getattr(value, "ref", None)
    return tuple(ref) if ref is not None else None


def _combine(ev, node: ast.RefOp) -> Rect | ExcelError:
    a, b = _rect(ev, node.left), _rect(ev, node.right)
    for side in (a, b):
        if isinstance(side, ExcelError):
            return side
        if side is None:
            return ExcelError.VALUE
    if (a[0] or "").casefold() != (b[0] or "").casefold() and a[0] and b[0]:
        return ExcelError.VALUE
    sheet = a[0] or b[0]
    if node.op == ":":
        return (sheet, min(a[1], b[1]), min(a[2], b[2]), max(a[3], b[3]), max(a[4], b[4]))
    r1, c1, r2, c2 = max(a[1], b[1]), max(a[2], b[2]), min(a[3], b[3]), min(a[4], b[4])
    if r1 > r2 or c1 > c2:
        return ExcelError.NULL
    return (sheet, r1, c1, r2, c2)


def read(ev, rect: Rect) -> Range:
    sheet, r1, c1, r2, c2 = rect
    value = ev.resolver.range(sheet, r1, c1, r2, c2)
    value = value if isinstance(value, Range) else Range.of(value)
    ref_type = getattr(xv, "Ref", None)  # references keep their position where supported
    if ref_type is not None and hasattr(value, "with_ref"):
        value = value.with_ref(ref_type(*rect))
    return value


def ref_op(ev, node: ast.RefOp):
    """``A1:INDEX(..)``, ``A1:B3 B2:C2`` (intersection) or ``(A1,B2:B3)`` (union)."""
    if node.op in ",~":  # '~' is how LibreOffice saves the union
        values, areas = [], []
        for part in (node.left, node.right):
            v = ev.arg(part)
            if isinstance(v, ExcelError):
                return v
            values.extend(v.flat() if isinstance(v, Range) else [v])
            if areas is not None:  # (None once a part is no reference)
                found = _areas_of(v)
                areas = areas + list(found) if found else None
        return Range(tuple((v,) for v in values), areas=tuple(areas or ()))
    if node.op == " " and (_is_union(node.left) or _is_union(node.right)):
        if getattr(ev, "dialect", "excel") == "libreoffice":
            return ExcelError.VALUE  # (measured: LibreOffice 7.4 intersects no union)
        return _union_intersection(ev, node)
    rect = _combine(ev, node)
    return rect if isinstance(rect, ExcelError) else read(ev, rect)


def _is_union(node) -> bool:
    while isinstance(node, ast.Paren):
        node = node.inner
    return isinstance(node, ast.RefOp) and node.op in ",~"


def _areas_of(v) -> tuple:
    """The areas of a reference value: a union's, or its one; () for no reference."""
    if not isinstance(v, Range):
        return ()
    return v.areas or ((v.ref,) if v.ref is not None else ())


def _union_intersection(ev, node: ast.RefOp):
    """``(A1:B2,C1:C4) B1:C9``: each area of one side with each of the other's; one area
    left is a plain reference, several are a union again, none is #NULL!."""
    sides = []
    for part in (node.left, node.right):
        v = ev.arg(part)
        if isinstance(v, ExcelError):
            return v
        areas = _areas_of(v)
        if not areas:
            return ExcelError.VALUE
        sides.append(areas)
    found = []
    for a in sides[0]:
        for b in sides[1]:
            if a.sheet and b.sheet and a.sheet.casefold() != b.sheet.casefold():
                return ExcelError.VALUE
            r1, c1 = max(a.row1, b.row1), max(a.col1, b.col1)
            r2, c2 = min(a.row2, b.row2), min(a.col2, b.col2)
            if r1 <= r2 and c1 <= c2:
                found.append((a.sheet or b.sheet, r1, c1, r2, c2))
    if not found:
        return ExcelError.NULL
    if len(found) == 1:
        return read(ev, found[0])
    parts = [read(ev, rect) for rect in found]
    return Range(tuple((v,) for part in parts for v in part.flat()),
                 areas=tuple(part.ref or xv.Ref(*rect) for part, rect in zip(parts, found)))


def sheets_3d(ev, node: ast.Sheets3D):
    """The values of ``ref`` on every sheet from ``sheet`` to ``sheet2``, in one column."""
    sheets = ev.ctx.workbook.sheets_between(node.sheet, node.sheet2)
    if not sheets:
        return ExcelError.REF
    _, r1, c1, r2, c2 = rect_of(node.ref)
    values = []
    for sheet in sheets:
        values.extend(read(ev, (sheet, r1, c1, r2, c2)).flat())
    return Range.of([[v] for v in values])


def evaluate(ev, node):
    """The value of one of this module's nodes."""
    if isinstance(node, ast.Array):
        return array_value(node)
    if isinstance(node, ast.RefOp):
        return ref_op(ev, node)
    if isinstance(node, ast.Sheets3D):
        return sheets_3d(ev, node)
    return ExcelError.REF  # an unresolved structured reference
