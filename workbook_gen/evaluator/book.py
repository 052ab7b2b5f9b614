"""What the evaluator needs of a workbook beyond its cells: the sheet order (3-D
references), sheet-scoped defined names and the tables that structured references name.

:func:`resolve_structured` turns ``Table1[Amount]``, ``Table1[[#This Row],[x]]``,
``[@x]``, ``Table1[#All]`` ... into plain references, as seen from one cell; a
``#This Row`` reference becomes row-relative, so a filled column keeps one tree.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from workbook_gen.formula import ast
from workbook_gen.xlerror import ExcelError


@dataclass(frozen=True)
class Table:
    name: str
    sheet: str
    row1: int
    col1: int
    row2: int
    col2: int
    columns: tuple[str, ...]
    header_rows: int = 1
    totals_rows: int = 0


@dataclass
class BookInfo:
    sheets: list[str] = field(default_factory=list)  # in workbook order
    local_names: dict[str, dict[str, str]] = field(default_factory=dict)  # sheet -> names
    tables: list[Table] = field(default_factory=list)
    # sheets the workbook lists whose cells cannot be read (no part): what reads them is
    # not checked
    unreadable: list[str] = field(default_factory=list)
    # rows hidden (by hand or by a filter) per sheet: SUBTOTAL 101-111 and AGGREGATE skip them
    hidden_rows: dict[str, frozenset[int]] = field(default_factory=dict)
    # the character set of CHAR and CODE (Microsoft's CHAR page: Windows' ANSI set, cp1252;
    # the Macintosh character set in Excel for Mac)
    charset: str = "cp1252"
    # the cube functions' cache of each connection (xlsx.olap), by case-folded name
    olap: dict = field(default_factory=dict)
    # the links to other workbooks with their cached cells (xlsx.model.ExternalLink)
    external: list = field(default_factory=list)

    def table(self, name: str, sheet: str, row: int, col: int) -> Table | None:
        """The table called ``name``, or ("" ) the one holding cell (sheet, row, col)."""
        if name:
            folded = name.casefold()
            return next((t for t in self.tables if t.name.casefold() == folded), None)
        return next((t for t in self.tables if t.sheet == sheet and t.row1 <= row <= t.row2
                     and t.col1 <= col <= t.col2), None)


_ITEM = re.compile(r"\[((?:[^\[\]']|'.)*)\]")
_SPECIALS = {"#all", "#data", "#headers", "#totals", "#this row"}


def _unescape(text: str) -> str:
    return re.sub(r"'(.)", r"\1", text).strip()


def _parse_spec(spec: str) -> tuple[set[str], list[str]] | None:
    """(specials, column names; two names for a column range) of a bracketed spec."""
    inner = spec[1:-1]
    specials: set[str] = set()
    columns: list[str] = []
    if inner.startswith("@"):
        specials.add("#this row")
        inner = inner[1:]
        if not inner:
            return specials, columns
        if not inner.startswith("["):
            return specials, [_unescape(inner)]
    if "[" not in inner:
        text = _unescape(inner)
        if text.lower() in _SPECIALS:
            specials.add(text.lower())
        elif text:
            columns.append(text)
        return specials, columns
    for part in re.split(r"\s*,\s*(?=\[)", inner.strip()):
        items = _ITEM.findall(part)
        if not items:
            return None
        for item in items:
            text = _unescape(item)
            if text.lower() in _SPECIALS:
                specials.add(text.lower())
            else:
                columns.append(text)
    return specials, columns


def structured_ref(node: ast.StructRef, info: BookInfo, sheet: str, row: int, col: int):
    """The plain reference ``node`` stands for in cell (sheet, row, col), or #REF!."""
    table = info.table(node.table, sheet, row, col)
    parsed = _parse_spec(node.spec)
    if table is None or parsed is None:
        return ast.ErrorLit(ExcelError.REF)
    specials, columns = parsed
    lookup = {c.casefold(): i for i, c in enumerate(table.columns)}
    if columns:
        idx = [lookup.get(c.casefold()) for c in columns]
        if any(i is None for i in idx):
            return ast.ErrorLit(ExcelError.REF)
        c1, c2 = table.col1 + min(idx), table.col1 + max(idx)
    else:
        c1, c2 = table.col1, table.col2
    data1 = table.row1 + table.header_rows
    data2 = table.row2 - table.totals_rows
    this_sheet = None if table.sheet == sheet else table.sheet
    if "#this row" in specials:
        if not data1 <= row <= data2:
            return ast.ErrorLit(ExcelError.VALUE)
        first = ast.CellRef(None, c1, row, True, False)
        last = ast.CellRef(None, c2, row, True, False)
    else:
        rows = []
        if "#all" in specials:
            rows = [table.row1, table.row2]
        if "#headers" in specials and table.header_rows:
            rows += [table.row1, table.row1 + table.header_rows - 1]
        if "#totals" in specials and table.totals_rows:
            rows += [data2 + 1, table.row2]
        if "#data" in specials or not specials:
            rows += [data1, data2]
        if not rows or min(rows) > max(rows):
            return ast.ErrorLit(ExcelError.REF)
        first = ast.CellRef(None, c1, min(rows), True, True)
        last = ast.CellRef(None, c2, max(rows), True, True)
    if first == last:
        return ast.CellRef(this_sheet, first.col, first.row, True, first.row_abs)
    return ast.RangeRef(this_sheet, first, last)


def resolve(node: ast.Node, info: BookInfo | None, sheet: str, row: int, col: int) -> ast.Node:
    """``node`` with its structured references made plain (as seen from one cell)."""
    if info is None or not any(isinstance(n, ast.StructRef) for n in ast.walk(node)):
        return node
    return _map(node, lambda n: structured_ref(n, info, sheet, row, col))


def _map(node, fn):
    if isinstance(node, ast.StructRef):
        return fn(node)
    if isinstance(node, ast.Func):
        return ast.Func(node.name, tuple(_map(a, fn) for a in node.args), node.prefix)
    if isinstance(node, ast.Unary):
        return ast.Unary(node.op, _map(node.operand, fn))
    if isinstance(node, ast.Percent):
        return ast.Percent(_map(node.operand, fn))
    if isinstance(node, ast.Binary):
        return ast.Binary(node.op, _map(node.left, fn), _map(node.right, fn))
    if isinstance(node, ast.RefOp):
        return ast.RefOp(node.op, _map(node.left, fn), _map(node.right, fn))
    if isinstance(node, ast.Paren):
        return ast.Paren(_map(node.inner, fn))
    return node
