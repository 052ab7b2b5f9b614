"""Cell values held column by column, so that a block of rows is an array slice.

A column keeps ``val`` (float64), ``err`` (uint8 error code) and ``irr`` (True where
the cell holds anything but a number or an error: text, a boolean or nothing; those
values live in a dict). ``scale`` holds each formula cell's operand scale. The
:class:`SheetResolver` gives the scalar evaluator the same data, and resolves
defined names (a name's text is itself a formula, e.g. ``Parameters!$B$2``).
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from itertools import compress, repeat

import numpy as np

from workbook_gen.errors import FormulaSyntaxError
from workbook_gen.evaluator.external import ExternalBooks
from workbook_gen.evaluator.keys import column_groups, pick
from workbook_gen.formula import ast
from workbook_gen.formula.parser import parse_name
from workbook_gen.formula.resolver import Resolver
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

_GROW = 1024
_SUBTOTAL_CALL = re.compile(r"(?<![\w.])(?:_xlfn\.)?(?:SUBTOTAL|AGGREGATE)\s*\(", re.I)


@dataclass(slots=True)
class NumBlock:
    """A block of numbers (or booleans when ``boolean``) with error codes: rows of a
    column as the vectorised evaluator computes them (not ``expr.tree.Num``, a literal)."""

    val: np.ndarray
    err: np.ndarray
    boolean: bool = False


@dataclass(slots=True)
class ObjBlock:
    """A block of arbitrary values (text, booleans, empties, numbers, errors)."""

    items: list


class _Column:
    __slots__ = ("val", "err", "irr", "objs", "scale")

    def __init__(self, size: int):
        self.val = np.full(size, np.nan)
        self.err = np.zeros(size, np.uint8)
        self.irr = np.ones(size, bool)
        self.scale = np.zeros(size)
        self.objs: dict[int, object] = {}

    def reserve(self, size: int) -> None:
        old = len(self.val)
        if size <= old:
            return
        size = max(size, old + _GROW)
        self.val = np.concatenate([self.val, np.full(size - old, np.nan)])
        self.err = np.concatenate([self.err, np.zeros(size - old, np.uint8)])
        self.irr = np.concatenate([self.irr, np.ones(size - old, bool)])
        self.scale = np.concatenate([self.scale, np.zeros(size - old)])


BIG_ROWS, BIG_COLS = 65_536, 1_024  # ranges taller / wider are cut to the used range


class Store:
    """Every cell value of a workbook; rows index arrays directly (row 0 unused).

    ``order`` is the workbook's sheet order (3-D references); ``extent[sheet]`` the
    largest row and column holding a value or a formula: a range taller than BIG_ROWS or
    wider than BIG_COLS (``A:A``, ``1:1``, ``C1:XFD1048576``) is read up to there only,
    what lies beyond being empty."""

    def __init__(self, sheets, order=()):
        self.canonical = {s.lower(): s for s in sheets}
        self.order = [s for s in order if s.lower() in self.canonical] or sorted(sheets)
        self.cols: dict[tuple[str, int], _Column] = {}
        self.rect_cache: dict[tuple, Range] = {}
        self.scale_cache: dict[tuple, float] = {}
        self.extent: dict[str, list[int]] = {}
        self.hidden: dict[str, frozenset[int]] = {}  # sheet -> its hidden rows
        self.filtered: dict[str, frozenset[int]] = {}  # sheet -> the rows a filter hid
        self.charset = "cp1252"  # CHAR and CODE's character set (BookInfo.charset)
        self.all_sheets: list[str] = list(self.order)  # every sheet in order (SHEET, SHEETS)
        self.olap: dict = {}  # the cube functions' caches (BookInfo.olap)
        self.topics: dict = {}  # the RTD calls' last values (BookInfo.topics)
        self.external = ExternalBooks()  # what the file caches of other workbooks
        self.stored = False  # formulas as a file stores them (availability.unavailable)
        self.formula_texts: Mapping[tuple[str, int, int], str] = {}  # for subtotal_cells
        self.array_formulas: Mapping[tuple[str, int, int], tuple] = {}  # (text, (r2, c2))
        self._subtotals: dict[str, list[tuple[int, int]]] | None = None
        self.unparsed: Mapping[tuple[str, int, int], str] = {}  # formulas not handed over
        self.unreadable: set[str] = set()  # sheets listed without their part (lower case)
        self._array_cells: set[tuple[str, int, int]] | None = None

    def subtotal_cells(self, sheet: str) -> list[tuple[int, int]]:
        """(row, col) of the cells of ``sheet`` whose formula calls SUBTOTAL or AGGREGATE
        (found on first use: most workbooks never ask)."""
        if self._subtotals is None:
            self._subtotals = {}
            for (name, row, col), text in self.formula_texts.items():
                if _SUBTOTAL_CALL.search(text):
                    self._subtotals.setdefault(name, []).append((row, col))
            for (name, row, col), (text, (r2, c2)) in self.array_formulas.items():
                if _SUBTOTAL_CALL.search(text):  # every cell of the array holds it
                    self._subtotals.setdefault(name, []).extend(
                        (r, k) for r in range(row, r2 + 1) for k in range(col, c2 + 1))
        return self._subtotals.get(sheet, [])

    def formula_text(self, sheet: str, row: int, col: int) -> tuple[str, bool] | None:
        """The formula of a cell as stored (without '=') and whether it is an array
        formula's, or None (FORMULATEXT)."""
        key = (sheet, row, col)
        if key in self.formula_texts:
            return self.formula_texts[key], False
        if self.has_formula(sheet, row, col):
            for (name, r1, c1), (text, (r2, c2)) in self.array_formulas.items():
                if name == sheet and r1 <= row <= r2 and c1 <= col <= c2:
                    return text, True
        return None

    def has_formula(self, sheet: str, row: int, col: int) -> bool:
        """Does the cell hold a formula (its own, an array formula's, one that does not
        parse)? (ISFORMULA.)"""
        key = (sheet, row, col)
        if key in self.formula_texts or key in self.unparsed:
            return True
        if self._array_cells is None:
            self._array_cells = {(name, r, k) for (name, r1, c1), (_, (r2, c2))
                                 in self.array_formulas.items()
                                 for r in range(r1, r2 + 1) for k in range(c1, c2 + 1)}
        return key in self._array_cells

    def sheet(self, name: str) -> str:
        return self.canonical.get(name.lower(), name)

    def note(self, sheet: str, row: int, col: int) -> None:
        e = self.extent.setdefault(sheet, [0, 0])
        if row > e[0]:
            e[0] = row
        if col > e[1]:
            e[1] = col

    def clip(self, sheet: str, r1: int, c1: int, r2: int, c2: int) -> tuple[int, int, int, int]:
        """A huge rectangle cut to the sheet's used rows and columns (never empty)."""
        if r2 - r1 >= BIG_ROWS or c2 - c1 >= BIG_COLS:
            rows, cols = self.extent.get(sheet, (0, 0))
            if r2 - r1 >= BIG_ROWS:
                r2 = max(r1, min(r2, rows))
            if c2 - c1 >= BIG_COLS:
                c2 = max(c1, min(c2, cols))
        return r1, c1, r2, c2

    def sheets_between(self, first: str, last: str) -> list[str] | None:
        """The sheets of a 3-D reference ``first:last``, in workbook order."""
        names = [s.lower() for s in self.order]
        try:
            a, b = names.index(first.lower()), names.index(last.lower())
        except ValueError:
            return None
        a, b = min(a, b), max(a, b)
        return self.order[a:b + 1]

    def _column(self, sheet: str, col: int, rows: int) -> _Column:
        column = self.cols.get((sheet, col))
        if column is None:
            column = self.cols[(sheet, col)] = _Column(rows + 1)
        column.reserve(rows + 1)
        return column

    def put(self, sheet: str, row: int, col: int, value, scale: float = 0.0) -> None:
        self.note(sheet, row, col)
        c = self._column(sheet, col, row)
        c.scale[row] = scale
        if isinstance(value, ExcelError):
            c.val[row], c.err[row], c.irr[row] = np.nan, value.code, False
            c.objs.pop(row, None)
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            c.val[row], c.err[row], c.irr[row] = float(value), 0, False
            c.objs.pop(row, None)
        else:
            c.val[row], c.err[row], c.irr[row] = np.nan, 0, True
            c.objs[row] = value

    def put_constants(self, constants) -> None:
        """Every constant cell {(sheet, row, col): value}, a column at a time."""
        keys, all_values = list(constants), list(constants.values())
        groups, all_rows = column_groups(keys)
        for sheet, col, idx in groups:  # (a column's keys in the order of ``constants``)
            rows = all_rows[idx]
            values = pick(all_values, idx)
            row_list = rows.tolist()
            self.note(sheet, int(rows.max()), col)
            c = self._column(sheet, col, int(rows.max()))
            everyone = set(map(type, values)) == {float}  # (a C loop: the usual case)
            plain = np.ones(len(values), bool) if everyone else np.array(
                [type(v) is float for v in values], bool)
            numbers = np.array(values if everyone else [v for v, p in zip(values, plain) if p],
                               dtype=float)
            # + 0.0: a cell never holds -0 in Excel (a file may say "-0")
            c.val[rows[plain]] = numbers + 0.0
            c.err[rows[plain]], c.irr[rows[plain]] = 0, False
            for i in () if everyone else np.flatnonzero(~plain).tolist():
                self.put(sheet, row_list[i], col, values[i])

    def put_block(self, sheet: str, col: int, first: int, block, scale: np.ndarray) -> None:
        """Write a NumBlock or a list of values to rows ``first ..``."""
        if isinstance(block, NumBlock) and not block.boolean:
            n = len(block.val)
            c = self._column(sheet, col, first + n - 1)
            sl = slice(first, first + n)
            c.val[sl], c.err[sl], c.irr[sl], c.scale[sl] = block.val, block.err, False, scale
            for r in [r for r in c.objs if first <= r < first + n] if c.objs else ():
                del c.objs[r]
            return
        items = block.items if isinstance(block, ObjBlock) else to_items(block)
        n = len(items)
        c = self._column(sheet, col, first + n - 1)
        sl = slice(first, first + n)
        plain = type_mask(items, FLOAT)
        codes = error_codes(items)
        c.val[sl] = floats_where(items, plain)
        c.err[sl] = codes
        irr = ~plain & (codes == 0)
        c.irr[sl] = irr
        c.scale[sl] = scale
        objs = c.objs
        for r in [r for r in objs if first <= r < first + n] if objs else ():
            del objs[r]
        for i in np.flatnonzero(irr).tolist():  # the rows holding text, booleans, nothing
            objs[first + i] = items[i]

    def get(self, sheet: str, row: int, col: int):
        c = self.cols.get((sheet, col))
        if c is None or row >= len(c.val) or row < 1:
            return None
        if c.irr[row]:
            return c.objs.get(row)
        e = c.err[row]
        return ExcelError.from_code(int(e)) if e else float(c.val[row])

    def scale(self, sheet: str, row: int, col: int) -> float:
        c = self.cols.get((sheet, col))
        return 0.0 if c is None or row >= len(c.val) else float(c.scale[row])

    def block(self, sheet: str, col: int, first: int, last: int) -> NumBlock | ObjBlock:
        """Rows ``first..last`` of a column: a NumBlock view when all are numbers/errors."""
        n = last - first + 1
        c = self.cols.get((sheet, col))
        if c is None:
            return ObjBlock([None] * n)
        if last < len(c.val) and not c.irr[first:last + 1].any():
            return NumBlock(c.val[first:last + 1], c.err[first:last + 1])
        return ObjBlock(_python_values(c, first, last))

    def numbers(self, sheet: str, col: int, rows: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Rows ``rows`` of a column holding values: (whether each is a number, neither
        an error nor text, a boolean or nothing; the values, NaN where no number; the
        operand scales)."""
        c = self.cols[(sheet, col)]
        return ~c.irr[rows] & (c.err[rows] == 0), c.val[rows], c.scale[rows]

    def column_values(self, sheet: str, col: int, r1: int, r2: int) -> list:
        """The values of rows ``r1..r2`` of a column, as Python values."""
        c = self.cols.get((sheet, col))
        if c is None:
            return [None] * (r2 - r1 + 1)
        if r2 < len(c.val) and not c.irr[r1:r2 + 1].any():
            return to_items(NumBlock(c.val[r1:r2 + 1], c.err[r1:r2 + 1]))
        return _python_values(c, r1, r2)

    def rect(self, sheet: str, r1: int, c1: int, r2: int, c2: int) -> Range:
        """Values of a rectangle, row by row. Cached: evaluation in dependency order
        reads a rectangle only once everything in it is final."""
        r1, c1, r2, c2 = self.clip(sheet, r1, c1, r2, c2)
        key = (sheet, r1, c1, r2, c2)
        rows = self.rect_cache.get(key)
        if rows is None:
            columns = [self.column_values(sheet, c, r1, r2) for c in range(c1, c2 + 1)]
            rows = self.rect_cache[key] = Range.of(zip(*columns))
        return rows

    def forget_rects(self) -> None:
        """Drop the rectangles' kept values and scales (their cells are to change)."""
        self.rect_cache.clear()
        self.scale_cache.clear()

    def rect_scale(self, sheet: str, r1: int, c1: int, r2: int, c2: int) -> float:
        """Largest magnitude among the numbers of a rectangle (kept, as ``rect``'s
        values are: a rectangle is read once its cells are computed)."""
        r1, c1, r2, c2 = self.clip(sheet, r1, c1, r2, c2)
        key = (sheet, r1, c1, r2, c2)
        found = self.scale_cache.get(key)
        if found is None:
            found = self.scale_cache[key] = self._rect_scale(sheet, r1, c1, r2, c2)
        return found

    def _rect_scale(self, sheet: str, r1: int, c1: int, r2: int, c2: int) -> float:
        scale = 0.0
        for col in range(c1, c2 + 1):
            c = self.cols.get((sheet, col))
            if c is None:
                continue
            top = min(r2 + 1, len(c.val))
            ok = ~c.irr[r1:top] & (c.err[r1:top] == 0)
            if ok.any():
                scale = max(scale, float(np.abs(c.val[r1:top][ok]).max()))
            for r, v in c.objs.items():
                if r1 <= r <= r2 and c.irr[r]:
                    scale = max(scale, value_scale(v))
        return scale


def _python_values(c: _Column, first: int, last: int) -> list:
    """``[Store.get(sheet, r, col) for r in range(first, last + 1)]`` of column ``c``,
    with Python work only for the cells that hold text, booleans, nothing or errors."""
    out = [None] * (last - first + 1)
    lo, hi = max(first, 1), min(last, len(c.val) - 1)
    if hi < lo:
        return out
    irr, err = c.irr[lo:hi + 1], c.err[lo:hi + 1]
    if irr.all():  # (a column of text: C loops)
        out[lo - first:hi - first + 1] = map(c.objs.get, range(lo, hi + 1))
        return out
    values = c.val[lo:hi + 1].tolist()
    at = np.flatnonzero(irr)
    if len(at):  # set in an object array, in C loops
        array = np.fromiter(values, object, len(values))
        array[at] = np.fromiter(map(c.objs.get, (at + lo).tolist()), object, len(at))
        values = array.tolist()
    for i in np.flatnonzero((err != 0) & ~irr).tolist():
        values[i] = ExcelError.from_code(int(err[i]))
    out[lo - first:hi - first + 1] = values
    return out


_CODE = {e: e.code for e in ExcelError}
_NAN_FOR_ERROR = dict.fromkeys(ExcelError, math.nan)
FLOAT = frozenset({float})


def type_mask(values, types: frozenset) -> np.ndarray:
    """Whether each value's type is one of ``types`` (exactly: a bool is no int), in C
    loops."""
    return np.fromiter(map(types.__contains__, map(type, values)), bool, len(values))


def floats_where(values: list, mask: np.ndarray) -> np.ndarray:
    """The values where ``mask`` holds, as floats; NaN elsewhere."""
    if mask.all():
        return np.array(values, float)
    out = np.full(len(values), np.nan)
    out[mask] = list(compress(values, mask))
    return out


def error_codes(items: list) -> np.ndarray:
    """The error code of each value (0 where it is none), in C loops."""
    try:
        return np.fromiter(map(_CODE.get, items, repeat(0)), np.uint8, len(items))
    except TypeError:  # an unhashable value (an array): one by one
        return np.array([x.code if isinstance(x, ExcelError) else 0 for x in items], np.uint8)


def with_nan(numbers: list) -> list:
    """Numbers and errors (hashable values) with NaN for each error, in a C loop."""
    return list(map(_NAN_FOR_ERROR.get, numbers, numbers))


def to_items(num: NumBlock) -> list:
    """Python values of a NumBlock."""
    if not num.boolean and not num.err.any():
        return num.val.tolist()
    out = []
    for v, e in zip(num.val.tolist(), num.err.tolist()):
        if e:
            out.append(ExcelError.from_code(e))
        else:
            out.append(bool(v) if num.boolean else v)
    return out


def value_scale(value) -> float:
    """Largest magnitude among the numbers in a value, a Range or a 2-D list."""
    if isinstance(value, Range):
        value = value.rows
    if isinstance(value, (list, tuple)):
        return max((value_scale(v) for row in value for v in row), default=0.0)
    if isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value):
        return abs(float(value))
    return 0.0


class Names:
    """Defined names, each parsed once (case-insensitive): workbook-level ones and
    sheet-scoped ones (``local[sheet]``), which win on their own sheet. A name that
    does not parse is in ``errors`` (keyed ``NAME`` or ``Sheet!NAME``)."""

    def __init__(self, names: dict[str, str], local: dict[str, dict[str, str]] | None = None,
                 prepare=None):
        self.nodes: dict[str, ast.Node] = {}
        self.local: dict[str, dict[str, ast.Node]] = {}
        self.errors: dict[str, str] = {}
        for name, text in names.items():
            self._add(self.nodes, name.upper(), name, text, prepare)
        for sheet, scope in (local or {}).items():
            nodes = self.local.setdefault(sheet.lower(), {})
            for name, text in scope.items():
                self._add(nodes, name.upper(), f"{sheet}!{name}", text, prepare)

    def _add(self, nodes, key, label, text, prepare) -> None:
        try:
            node = parse_name(text)
            nodes[key] = prepare(node) if prepare else node
        except FormulaSyntaxError as exc:
            self.errors[label.upper()] = str(exc)

    def node(self, name: str, sheet: str | None = None, home: str | None = None
             ) -> ast.Node | None:
        """The tree of ``name`` as written in a formula of sheet ``home``
        (``sheet``: the qualifier of ``Sheet2!Name``)."""
        key = name.upper()
        if sheet is not None and "]" in sheet:  # another workbook's name: not one of ours
            return None
        if sheet is not None:
            scope = self.local.get(sheet.lower(), {})
            return scope.get(key, self.nodes.get(key))
        if home is not None:
            found = self.local.get(home.lower(), {}).get(key)
            if found is not None:
                return found
        return self.nodes.get(key)

    def error(self, name: str, sheet: str | None = None, home: str | None = None) -> str | None:
        """Why ``name`` (seen as :meth:`node` sees it) does not parse, or None."""
        key = name.upper()
        for label in ([f"{sheet}!{key}".upper()] if sheet else
                      [f"{home}!{key}".upper()] if home else []) + [key]:
            if label in self.errors:
                return label
        return None


class SheetResolver(Resolver):
    """The scalar evaluator's view of the store from cells of one sheet: every
    :class:`~workbook_gen.formula.resolver.Resolver` method answered from the store."""

    MAX_NAME_DEPTH = 16

    def __init__(self, store: Store, names: Names, sheet: str, depth: int = 0):
        self.store, self.names, self.sheet, self.depth = store, names, sheet, depth

    def _sheet(self, sheet):
        return self.sheet if sheet is None else self.store.sheet(sheet)

    def cell(self, sheet, row, col):
        if sheet is not None and "]" in sheet:  # another workbook: the file's cache
            return self.store.external.cell(sheet, row, col)
        return self.store.get(self._sheet(sheet), row, col)

    def range(self, sheet, row1, col1, row2, col2):
        if sheet is not None and "]" in sheet:
            return self.store.external.rect(sheet, row1, col1, row2, col2)
        return self.store.rect(self._sheet(sheet), row1, col1, row2, col2)

    def hidden_rows(self, sheet) -> frozenset[int]:
        """The hidden rows of a sheet (SUBTOTAL 101-111, AGGREGATE)."""
        return self.store.hidden.get(self._sheet(sheet), frozenset())

    def spill_area(self, sheet, row: int, col: int) -> tuple[int, int] | None:
        """(last row, last column) of the array formula anchored at the cell, or None
        (ANCHORARRAY)."""
        found = self.store.array_formulas.get((self._sheet(sheet), row, col))
        return None if found is None else found[1]

    def filtered_rows(self, sheet) -> frozenset[int]:
        """The rows of a sheet a filter hid (SUBTOTAL 1-11 leave them out too)."""
        return self.store.filtered.get(self._sheet(sheet), frozenset())

    def charset(self) -> str:
        """The workbook's character set for CHAR and CODE ("cp1252" or "mac_roman")."""
        return self.store.charset

    def olap(self, connection: str):
        """The cube functions' cache of a connection (xlsx.olap.OlapCache), or None."""
        return self.store.olap.get(connection.casefold())

    def topics(self, progid: str):
        """{(server, topics...): last value} of an RTD server's calls, or None."""
        return self.store.topics.get(progid.casefold())

    def subtotal_cells(self, sheet) -> list[tuple[int, int]]:
        """(row, col) of a sheet's cells holding SUBTOTAL or AGGREGATE (left out by them)."""
        return self.store.subtotal_cells(self._sheet(sheet))

    def has_formula(self, sheet, row, col) -> bool:
        return self.store.has_formula(self._sheet(sheet), row, col)

    def formula_text(self, sheet, row, col) -> tuple[str, bool] | None:
        return self.store.formula_text(self._sheet(sheet), row, col)

    def sheet_number(self, sheet: str | None) -> int | None:
        """The 1-based place of a sheet (None: this one) among all the workbook's sheets,
        its name matched regardless of case; None if there is no such sheet."""
        folded = (self.sheet if sheet is None else sheet).casefold()
        return next((i + 1 for i, name in enumerate(self.store.all_sheets)
                     if name.casefold() == folded), None)

    def sheet_count(self) -> int:
        return len(self.store.all_sheets)

    @property
    def stored(self) -> bool:
        """Are the formulas as a file stores them (``_xlfn.`` prefixes and all)?"""
        return self.store.stored

    def sheets_between(self, first: str, last: str) -> list[str] | None:
        return self.store.sheets_between(first, last)

    def range_scale(self, sheet, row1, col1, row2, col2) -> float:
        if sheet is not None and "]" in sheet:
            rows = self.range(sheet, row1, col1, row2, col2).rows
            return max((value_scale(v) for row in rows for v in row), default=0.0)
        return self.store.rect_scale(self._sheet(sheet), row1, col1, row2, col2)

    def name_node(self, name: str):
        """The tree of a defined name seen from this sheet (a LAMBDA called by name)."""
        return self.names.node(name, None, self.sheet)

    def name(self, name, sheet):
        node = self.names.node(name, sheet, self.sheet)
        if node is None and sheet is not None and sheet[:1] == "[":  # another workbook's
            node = self.store.external.name(sheet, name)
        if node is None or self.depth >= self.MAX_NAME_DEPTH:
            return ExcelError.NAME
        from workbook_gen.formula.scalar import Evaluator  # the reference semantics

        home = self.sheet if sheet is None else self.store.sheet(sheet)
        inner = SheetResolver(self.store, self.names, home, self.depth + 1)
        value = Evaluator(inner, "excel", None).arg(node)
        if isinstance(value, Range) and value.ref is not None and value.ref.sheet is None:
            value = value.with_ref(value.ref._replace(sheet=home))  # where the name points
        return value
