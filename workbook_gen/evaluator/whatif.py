"""Data tables (What-If Analysis > Data Table: ``<f t="dataTable" ref r1 r2 dt2D dtr>``),
recomputed as Excel computes them.

Excel shows a data table's cells as ``{=TABLE(row_input, column_input)}``. Each cell is
the table's formula with its input cell(s) holding the value that heads the cell's row
or column (ECMA-376 Part 1, 18.3.1.40 ``f``: ``dt2D``, ``dtr`` "one-dimensional data
table is a row" (its input cell ``r1`` is a row input cell), ``r1``/``r2`` the input
cells, ``del1``/``del2`` an input cell deleted):

- one-dimensional, column input (``dtr`` 0): input values down the column left of the
  area, formulas along the row above it; cell (r, c) = formula (top - 1, c) with
  r1 := (r, left - 1);
- one-dimensional, row input (``dtr`` 1): input values along the row above, formulas
  down the column left; cell (r, c) = formula (r, left - 1) with r1 := (top - 1, c);
- two-dimensional: the formula at the corner (top - 1, left - 1); r1 (row input) takes
  the row above, r2 (column input) the column left;
- an input cell deleted: every cell is ``#REF!`` (the table's input reference is gone).

The formula is recomputed with the input cells replaced, and every formula cell between
them with it (on demand, a cell found not to read an input nor a changed cell is read
from the store ever after). What cannot be recomputed so (a cell not checked, a volatile
or unsupported function, an array formula or another data table on the way) raises
:class:`Unanswered` with the reason.
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass

from workbook_gen.evaluator.store import SheetResolver, value_scale
from workbook_gen.formula import ast
from workbook_gen.formula.functions import Unanswered
from workbook_gen.cellref import column_letters
from workbook_gen.formula.scalar import evaluate, unsupported_functions
from workbook_gen.formula.tokenizer import CELL_PARTS, column_number
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

MAX_RECOMPUTED = 50_000  # formula cells recomputed for one table, at most
CHANGING = frozenset({"NOW", "TODAY", "RAND", "RANDBETWEEN", "RANDARRAY"})


@dataclass(frozen=True)
class DataTable:
    sheet: str
    row1: int
    col1: int
    row2: int
    col2: int
    r1: tuple[int, int] | None  # (row, col) of the (row) input cell
    r2: tuple[int, int] | None  # of the column input cell (two-dimensional)
    two_d: bool
    row_input: bool  # dtr: a one-dimensional table whose input cell is a row input cell
    deleted: bool

    @classmethod
    def of(cls, sheet: str, row: int, col: int, area: tuple[int, int], attrs: dict):
        def cell(name):
            m = CELL_PARTS.fullmatch(attrs.get(name, "").replace("$", ""))
            return (int(m.group(4)), column_number(m.group(2))) if m else None
        yes = lambda name: attrs.get(name) in ("1", "true")  # noqa: E731
        return cls(sheet, row, col, area[0], area[1], cell("r1"), cell("r2"), yes("dt2D"),
                   yes("dtr"), yes("del1") or yes("del2"))

    def cells(self) -> list[tuple[str, int, int]]:
        return [(self.sheet, r, c) for r in range(self.row1, self.row2 + 1)
                for c in range(self.col1, self.col2 + 1)]

    def text(self) -> str:
        """As Excel shows it: ``TABLE(row input, column input)``."""
        ref = lambda rc: "" if rc is None else f"{column_letters(rc[1])}{rc[0]}"  # noqa: E731
        if self.two_d:
            return f"TABLE({ref(self.r1)},{ref(self.r2)})"
        return f"TABLE({ref(self.r1)},)" if self.row_input else f"TABLE(,{ref(self.r1)})"

    def plan(self, row: int, col: int):
        """(formula cell, {input cell: cell holding its value}) of the result (row, col)."""
        top, left = self.row1 - 1, self.col1 - 1
        if self.two_d:
            return (top, left), {self.r1: (top, col), self.r2: (row, left)}
        if self.row_input:
            return (row, left), {self.r1: (top, col)}
        return (top, col), {self.r1: (row, left)}


class _View:
    """The store as the table's formula sees it: input cells replaced, the formula cells
    that read them recomputed (a store for :class:`SheetResolver`)."""

    def __init__(self, store, run: "_Run"):
        self._store, self._run = store, run

    def __getattr__(self, name):  # everything else: the store's own
        return getattr(self._store, name)

    def get(self, sheet, row, col):
        return self._run.value((sheet, row, col))

    def rect(self, sheet, r1, c1, r2, c2):
        r1, c1, r2, c2 = self._store.clip(sheet, r1, c1, r2, c2)
        if not self._run.touches(sheet, r1, c1, r2, c2):
            return self._store.rect(sheet, r1, c1, r2, c2)
        return Range.of([[self.get(sheet, r, c) for c in range(c1, c2 + 1)]
                         for r in range(r1, r2 + 1)])


class _Run:
    """The recomputation of one table's cells, sharing what it learns between them."""

    def __init__(self, table, tables, store, names, dialect, prepare, not_checked):
        self.table, self.store, self.names, self.dialect = table, store, names, dialect
        self.prepare, self.not_checked = prepare, not_checked
        self.blocked = {c for t in tables for c in t.cells()}  # data tables' cells
        self.clean: set = set()      # formula cells that read no replaced value
        self.subs: dict = {}         # the replaced cells, for the current result cell
        self.memo: dict = {}         # recomputed values, for the current result cell
        self.stack: list[list[bool]] = []  # per cell under way: did it read a change?
        self.count = 0
        self.view = _View(store, self)
        by_col: dict = {}
        for (sheet, row, col) in store.formula_texts:
            by_col.setdefault((sheet, col), []).append(row)
        self.rows = {k: sorted(v) for k, v in by_col.items()}

    def touches(self, sheet, r1, c1, r2, c2) -> bool:
        """Does a rectangle hold a replaced cell or a formula cell not known clean?"""
        if any(s == sheet and r1 <= r <= r2 and c1 <= c <= c2 for s, r, c in self.subs):
            return True
        for col in range(c1, c2 + 1):
            rows = self.rows.get((sheet, col), ())
            for row in rows[bisect.bisect_left(rows, r1):bisect.bisect_right(rows, r2)]:
                if (sheet, row, col) not in self.clean:
                    return True
        return any(s == sheet and r1 <= r <= r2 and c1 <= c <= c2
                   for s, r, c in self.blocked)

    def value(self, key):
        if key in self.subs:
            self._changed()
            return self.subs[key]
        if key in self.blocked:
            raise Unanswered(f"data table: its formula reads a data table's cell: "
                             f"{_where(key)}")
        if key in self.not_checked:
            raise Unanswered(f"data table: depends on {_where(key)}: {self.not_checked[key]}")
        if key not in self.store.formula_texts:
            if self.store.has_formula(*key):
                raise Unanswered(f"data table: its formula reads an array formula's "
                                 f"cell: {_where(key)}")
            return self.store.get(*key)
        if key in self.clean:
            return self.store.get(*key)
        if key in self.memo:
            if self.memo[key] is _UNDER_WAY:
                raise Unanswered(f"data table: a circular reference: {_where(key)}")
            changed, value = self.memo[key]
            if changed:
                self._changed()
            return value
        return self._recompute(key)

    def _changed(self) -> None:
        if self.stack:
            self.stack[-1][0] = True

    def _recompute(self, key):
        self.count += 1
        if self.count > MAX_RECOMPUTED:
            raise Unanswered(f"data table: more than {MAX_RECOMPUTED} formula cells to "
                             "recompute")
        node = self.prepare(key)
        called = {n.name for n in ast.walk(node) if isinstance(n, ast.Func)}
        if called & CHANGING or unsupported_functions(node):
            raise Unanswered(f"data table: its formula reads a cell calling "
                             + ", ".join(sorted(called & CHANGING | unsupported_functions(node)))
                             + f": {_where(key)}")
        self.memo[key] = _UNDER_WAY
        self.stack.append([False])
        try:
            value = evaluate(node, SheetResolver(self.view, self.names, key[0]),
                             dialect=self.dialect, cell=key)
        finally:
            changed = self.stack.pop()[0]
        if changed:
            self._changed()
            self.memo[key] = (True, value)
        else:
            del self.memo[key]
            self.clean.add(key)
            value = self.store.get(*key)  # (the same: it read nothing replaced)
        return value

    def result(self, row: int, col: int):
        formula, inputs = self.table.plan(row, col)
        self.memo = {}
        self.subs = {(self.table.sheet, *cell): self.store.get(self.table.sheet, *source)
                     for cell, source in inputs.items()}
        return self.value((self.table.sheet, *formula))


_UNDER_WAY = object()


def _where(key) -> str:
    return f"{key[0]}!{column_letters(key[2])}{key[1]}"


def evaluate_table(table: DataTable, tables, store, names, dialect: str, prepare,
                   not_checked) -> dict:
    """{cell: value} of a data table's cells (raises Unanswered). ``prepare(cell)``: the
    tree of a formula cell; ``not_checked``: the cells not checked, with the reason."""
    if table.deleted:
        return dict.fromkeys(table.cells(), ExcelError.REF)
    if table.r1 is None or (table.two_d and table.r2 is None):
        raise Unanswered("data table: an input cell is missing from its <f>")
    run = _Run(table, tables, store, names, dialect, prepare, not_checked)
    return {(s, r, c): run.result(r, c) for s, r, c in table.cells()}


def put_tables(tables, store, names, dialect: str, prepare, not_checked, skip) -> None:
    """Recompute data tables into ``store``; ``skip(cell, why)`` for the cells of a table
    that cannot be."""
    for table in tables:
        done, why = table_values(table, tables, store, names, dialect, prepare, not_checked)
        for cell in table.cells():
            if done is None:
                skip(cell, why)
            else:
                store.put(*cell, done[cell], value_scale(done[cell]))


def table_values(table: DataTable, tables, store, names, dialect: str, prepare,
                 not_checked) -> tuple[dict | None, str]:
    """``(values, "")``, or ``(None, why)`` where the table cannot be recomputed."""
    try:
        return evaluate_table(table, tables, store, names, dialect, prepare, not_checked), ""
    except Unanswered as exc:
        return None, str(exc)
    except (ArithmeticError, ValueError, TypeError, IndexError, KeyError, AttributeError,
            RecursionError) as exc:  # a defect must not lose the file
        return None, f"evaluator failure: {type(exc).__name__}: {exc}"


__all__ = ["DataTable", "evaluate_table", "put_tables", "table_values"]
