"""Turn an AST back into formula text.

``render(node)`` returns the formula WITHOUT the leading ``=`` (``render_formula``
adds it). For every formula without whitespace in Excel's canonical case (function
names, booleans, error literals and column letters upper-case, sheet names quoted
only where needed) ``render(parse(text)) == text.lstrip("=")``: parentheses are
kept as Paren nodes and numbers keep the text they were written with.
"""

from __future__ import annotations

import re

from workbook_gen.cellref import column_letters  # noqa: F401  (part of this module's face)
from workbook_gen.formula import ast
from workbook_gen.formula.ast import INFIX_POWER as _INFIX_POWER
from workbook_gen.formula.ast import PERCENT_POWER as _PERCENT_POWER
from workbook_gen.formula.ast import PREFIX_POWER as _PREFIX_POWER

# [A-Za-z_\u00a1-\uffff][\w.\u00a1-\uffff]*, spelled negated (see the tokenizer's _FIRST):
# a word character beyond U+FFFF is quoted, as any name may be
_PLAIN_SHEET = re.compile(r"[^\x00-@\[-^`{-\xa0\U00010000-\U0010ffff]"
                          r"[^\x00-\-/:-@\[-^`{-\xa0\U00010000-\U0010ffff]*")
_R1C1_LIKE = re.compile(r"(?:R[0-9]*)?(?:C[0-9]*)?", re.IGNORECASE)


def quote_sheet(sheet: str) -> str:
    """The sheet name as it appears before ``!`` (quoted where Excel quotes it)."""
    from workbook_gen.formula.tokenizer import is_cell_ref

    if _PLAIN_SHEET.fullmatch(sheet) and not is_cell_ref(sheet) and not _R1C1_LIKE.fullmatch(sheet):
        return sheet
    return "'" + sheet.replace("'", "''") + "'"


def cell_text(ref: ast.CellRef) -> str:
    """``$A$1`` style text of a reference, without its sheet."""
    return (("$" if ref.col_abs else "") + column_letters(ref.col)
            + ("$" if ref.row_abs else "") + str(ref.row))


def number_text(value: float) -> str:
    """Canonical text of a number built without source text (``2.0`` -> ``2``)."""
    if value == int(value) and abs(value) < 1e15:
        return str(int(value))
    return repr(value).upper()


def _a1(ref) -> str:
    if isinstance(ref, ast.CellRef):
        return cell_text(ref)
    if ref.whole == "col":
        return "".join(("$" if c.col_abs else "") + column_letters(c.col)
                       for c in (ref.first,)) + ":" + \
            ("$" if ref.last.col_abs else "") + column_letters(ref.last.col)
    if ref.whole == "row":
        return (("$" if ref.first.row_abs else "") + str(ref.first.row) + ":"
                + ("$" if ref.last.row_abs else "") + str(ref.last.row))
    return cell_text(ref.first) + ":" + cell_text(ref.last)


def _power(node: ast.Node) -> int:
    if isinstance(node, ast.Binary):
        return _INFIX_POWER[node.op]
    if isinstance(node, ast.Percent):
        return _PERCENT_POWER
    if isinstance(node, ast.Unary):
        return _PREFIX_POWER
    if isinstance(node, ast.RefOp):
        return 80 if node.op in ",~" else 85 if node.op == " " else 90
    return 100


def render(node: ast.Node) -> str:
    """Formula text of ``node`` without the leading ``=``."""
    return render_with(node, _a1)


def render_formula(node: ast.Node) -> str:
    """Formula text with the leading ``=``, as stored in a cell."""
    return "=" + render(node)


def render_with(node: ast.Node, ref_text) -> str:
    """Render with ``ref_text(ref)`` giving the text of each reference after its sheet."""
    def wrap(n, min_power: int) -> str:
        # Trees built in code may lack Paren nodes: add the ones precedence needs.
        return "(" + go(n) + ")" if _power(n) < min_power else go(n)

    def binary(n: ast.Binary) -> str:
        # Iterate over the left spine: long left-deep chains must not recurse.
        spine = []
        while isinstance(n, ast.Binary):
            spine.append(n)
            n = n.left
        text = wrap(n, _INFIX_POWER[spine[-1].op])
        for k in reversed(range(len(spine))):
            power = _INFIX_POWER[spine[k].op]
            if k + 1 < len(spine) and _INFIX_POWER[spine[k + 1].op] < power:
                text = "(" + text + ")"
            text += spine[k].op + wrap(spine[k].right, power + 1)
        return text

    def go(n) -> str:
        if isinstance(n, ast.Number):
            return n.text or number_text(n.value)
        if isinstance(n, ast.String):
            return '"' + n.value.replace('"', '""') + '"'
        if isinstance(n, ast.Bool):
            return "TRUE" if n.value else "FALSE"
        if isinstance(n, ast.ErrorLit):
            return n.error.value
        if isinstance(n, ast.Missing):
            return ""
        if isinstance(n, (ast.CellRef, ast.RangeRef)):
            prefix = quote_sheet(n.sheet) + "!" if n.sheet is not None else ""
            return prefix + ref_text(n)
        if isinstance(n, ast.Name):
            return (quote_sheet(n.sheet) + "!" if n.sheet is not None else "") + n.name
        if isinstance(n, ast.Func):
            return n.prefix + n.name + "(" + ",".join(go(a) for a in n.args) + ")"
        if isinstance(n, ast.Unary):
            return n.op + wrap(n.operand, _PREFIX_POWER)
        if isinstance(n, ast.Percent):
            return wrap(n.operand, _PERCENT_POWER) + "%"
        if isinstance(n, ast.Binary):
            return binary(n)
        if isinstance(n, ast.Paren):
            return "(" + go(n.inner) + ")"
        if isinstance(n, ast.RefOp):
            power = _power(n)
            return wrap(n.left, power) + n.op + wrap(n.right, power + 1)
        if isinstance(n, ast.Sheets3D):
            a, b = quote_sheet(n.sheet), quote_sheet(n.sheet2)
            both = (f"{a}:{b}" if not (a + b).startswith("'") and "'" not in a + b
                    else quote_sheet(f"{n.sheet}:{n.sheet2}"))
            return both + "!" + ref_text(n.ref)
        if isinstance(n, ast.Array):
            return "{" + ";".join(",".join(go(v) for v in row) for row in n.rows) + "}"
        if isinstance(n, ast.StructRef):
            return n.table + n.spec
        raise TypeError(f"not a formula node: {n!r}")
    return go(node)


def to_relative(node: ast.Node, base_row: int, base_col: int) -> str:
    """A hashable key: the formula in R1C1 notation as seen from (base_row, base_col).

    ``=B2*2`` in C2 and ``=B3*2`` in C3 both give ``RC[-1]*2``; absolute references
    keep their coordinates (``$A$1`` gives ``R1C1``).
    """
    def ref_text(ref):
        if isinstance(ref, ast.CellRef):
            return ast.r1c1(ref, base_row, base_col)
        return ast.r1c1(ref.first, base_row, base_col) + ":" + ast.r1c1(ref.last, base_row, base_col)
    return render_with(node, ref_text)
