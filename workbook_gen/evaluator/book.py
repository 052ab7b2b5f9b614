"""What the evaluator needs of a workbook beyond its cells: the sheet order (3-D
references), sheet-scoped defined names and the tables that structured references name.

:func:`resolve_structured` turns ``Table1[Amount]``, ``Table1[[#This Row],[x]]``,
``[@x]``, ``Table1[#All]`` ... into plain references, as seen from one cell; a
``#This Row`` reference becomes row-relative, so a filled column keeps one tree.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from workbook_gen.evaluator.relnames import calling_cell_struct
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
    # of those, the rows a filter hid (an autoFilter's or a table's): SUBTOTAL 1-11 skip them
    filtered_rows: dict[str, frozenset[int]] = field(default_factory=dict)
    # every sheet of the workbook (worksheets, chart, macro and dialog sheets) in its order:
    # SHEET and SHEETS count them all (empty: the worksheets of ``sheets``)
    all_sheets: list[str] = field(default_factory=list)
    # the character set of CHAR and CODE (Microsoft's CHAR page: Windows' ANSI set, cp1252;
    # the Macintosh character set in Excel for Mac)
    charset: str = "cp1252"
    # the workbook's date system (workbookPr date1904): serial 0 is 1904-01-01 (serials.py)
    date1904: bool = False
    _names: tuple | None = field(default=None, repr=False, compare=False)

    def is_table(self, name: str) -> bool:
        """Does a table have this name (any case)?"""
        if self._names is None or len(self._names[0]) != len(self.tables):
            self._names = (tuple(self.tables), frozenset(t.name.casefold() for t in self.tables))
        return name.casefold() in self._names[1]
    # the cube functions' cache of each connection (xlsx.olap), by case-folded name
    olap: dict = field(default_factory=dict)
    topics: dict = field(default_factory=dict)  # the RTD calls' last values (xlsx.topics)
    # the links to other workbooks with their cached cells (xlsx.model.ExternalLink)
    external: list = field(default_factory=list)

    def table(self, name: str, sheet: str, row: int, col: int) -> Table | None:
        """The table called ``name``, or ("" ) the one holding cell (sheet, row, col)."""
        if name:
            folded = name.casefold()
            return next((t for t in self.tables if t.name.casefold() == folded), None)
        return next((t for t in self.tables if t.sheet == sheet and t.row1 <= row <= t.row2
                     and t.col1 <= col <= t.col2), None)


_SPECIALS = {"#all", "#data", "#headers", "#totals", "#this row"}


def _name_end(text: str, at: int) -> int:
    """Offset of the ``]`` closing the column name that starts at ``at`` (``'`` escapes the
    next character: ``'[ '] '# ''`` and ``'@``), or -1."""
    while at < len(text):
        ch = text[at]
        if ch == "'":
            at += 2
            continue
        if ch == "]":
            return at
        if ch == "[":
            return -1
        at += 1
    return -1


def _unescape(text: str) -> str:
    """A column name as its header reads: escapes removed, spaces kept (a header may begin
    or end with spaces: ``[the two ]`` names the column "the two ")."""
    return re.sub(r"'(.)", r"\1", text)


def _item(text: str, specials: set[str], columns: list[str]) -> None:
    key = text.strip().lower()
    if key in _SPECIALS:
        specials.add(key)
    else:
        columns.append(_unescape(text))


def _parse_spec(spec: str) -> tuple[set[str], list[str]] | None:
    """(specials, column names; two names for a column range) of a bracketed spec.

    Microsoft's grammar ("Using structured references with Excel tables"): a bare column
    name ``Table1[Sales Amount]``, a special item ``[#All]``, ``[@Col]`` / ``[@[Col]]`` /
    ``[@]`` for this row, or a list of bracketed items ``[[#Totals],[a]:[b]]`` separated by
    commas (spaces between items are ignored, spaces inside an item's brackets are part of
    the name). ``'`` escapes ``[ ] # ' @`` in a name."""
    inner = spec[1:-1]
    specials: set[str] = set()
    columns: list[str] = []
    if inner.startswith("@"):
        specials.add("#this row")
        inner = inner[1:]
        if not inner.strip():
            return specials, columns
        if not inner.lstrip().startswith("["):
            columns.append(_unescape(inner))
            return specials, columns
    if not inner.lstrip().startswith("["):  # one bare name or special item
        if inner.strip():
            _item(inner, specials, columns)
        return specials, columns
    at, n, ranged = 0, len(inner), False
    while True:
        while at < n and inner[at] == " ":
            at += 1
        if at >= n or inner[at] != "[":
            return None
        end = _name_end(inner, at + 1)
        if end < 0:
            return None
        before = len(columns)
        _item(inner[at + 1:end], specials, columns)
        if ranged and len(columns) == before:  # "[a]:[#Data]" is no column range
            return None
        at = end + 1
        while at < n and inner[at] == " ":
            at += 1
        if at >= n:
            return specials, columns
        ranged = inner[at] == ":"
        if inner[at] not in ",:":
            return None
        at += 1


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


def _table_name(node: ast.Node, info: BookInfo) -> bool:
    """A bare table name (``=SUM(Sales)``: its data rows, as ``Sales[]``); tables and
    defined names share one namespace in Excel."""
    return (isinstance(node, ast.Name) and node.sheet is None and bool(info.tables)
            and info.is_table(node.name))


def _structured(node: ast.Node, info: BookInfo) -> bool:
    return isinstance(node, ast.StructRef) or _table_name(node, info)


def resolve(node: ast.Node, info: BookInfo | None, sheet: str, row: int, col: int) -> ast.Node:
    """``node`` with its structured references made plain (as seen from one cell)."""
    if info is None or not any(_structured(n, info) for n in ast.walk(node)):
        return node
    return _map(node, lambda n: structured_ref(n, info, sheet, row, col), info)


def resolve_fixed(node: ast.Node, info: BookInfo | None) -> ast.Node:
    """A defined name's tree with the structured references that read the same cells from
    any cell made plain; those resolved from the calling cell (no table named, this row)
    are kept for it (:mod:`relnames` writes the name into that cell's formula)."""
    if info is None or not any(_structured(n, info) for n in ast.walk(node)):
        return node
    return _map(node, lambda n: n if calling_cell_struct(n)
                else structured_ref(n, info, "", 0, 0), info)


def _map(node, fn, info: BookInfo):
    if isinstance(node, ast.StructRef):
        return fn(node)
    if _table_name(node, info):
        return fn(ast.StructRef(node.name, "[]"))
    if isinstance(node, ast.Func):
        return ast.Func(node.name, tuple(_map(a, fn, info) for a in node.args), node.prefix)
    if isinstance(node, ast.Unary):
        return ast.Unary(node.op, _map(node.operand, fn, info))
    if isinstance(node, ast.Percent):
        return ast.Percent(_map(node.operand, fn, info))
    if isinstance(node, ast.Binary):
        return ast.Binary(node.op, _map(node.left, fn, info), _map(node.right, fn, info))
    if isinstance(node, ast.RefOp):
        return ast.RefOp(node.op, _map(node.left, fn, info), _map(node.right, fn, info))
    if isinstance(node, ast.Paren):
        return ast.Paren(_map(node.inner, fn, info))
    return node


# What a reference to a sheet the workbook does not have evaluates to: Excel, loading a
# file whose formula names a sheet it lacks, holds #REF! (as after deleting the sheet);
# LibreOffice 7.4 reads the text as an unknown name: #NAME? (measured, ROWS included)
MISSING_SHEET = {"excel": ExcelError.REF, "libreoffice": ExcelError.NAME}


def without_missing_sheets(node: ast.Node, sheets, dialect: str) -> ast.Node:
    """``node`` with every reference to a sheet not in ``sheets`` (lower-case names; empty:
    not known, nothing replaced) made the dialect's error; another workbook's (``[1]``)
    stays."""
    if not sheets:
        return node

    def missing(ref) -> bool:
        return (ref.sheet is not None and "]" not in ref.sheet
                and ref.sheet.lower() not in sheets)
    if not any(isinstance(n, (ast.CellRef, ast.RangeRef)) and missing(n) for n in ast.walk(node)):
        return node
    error = ast.ErrorLit(MISSING_SHEET.get(dialect, ExcelError.REF))
    return ast.map_refs(node, lambda ref: error if missing(ref) else ref)
