"""The sheets as a grid of cell kinds, for the findings: what each cell holds (a formula
and its R1C1 form, a number, text, a boolean, an error, nothing) and what each formula
reads.

Built from the audit's inputs and the evaluator's runs (a column's rows whose formulas
are equal in R1C1 form, one parsed tree per run): the R1C1 text is computed once per
run, and a formula's references at row ``first + dr`` of a run are the run's references
with their relative rows moved by ``dr``.
"""

from __future__ import annotations

from bisect import bisect_right
from collections.abc import Iterator
from dataclasses import dataclass

from ..errors import FormulaSyntaxError
from ..formula import ast
from ..formula.parser import parse_name
from ..formula.printer import to_relative
from ..xlerror import ExcelError

Key = tuple[str, int, int]

FORMULA, NUMBER, TEXT, BOOL, ERROR, EMPTY = "formula", "number", "text", "bool", "error", None


@dataclass(frozen=True, slots=True)
class Ref:
    """A reference a formula makes: a rectangle (one cell when r1 == r2 and c1 == c2)."""

    sheet: str
    r1: int
    c1: int
    r2: int
    c2: int
    node: object        # the CellRef or RangeRef of the tree
    function: str       # the innermost function the reference is an argument of ("" if none)
    guarded: bool       # read by a test (ISBLANK, IF's condition, a comparison with "")

    @property
    def single(self) -> bool:
        return self.r1 == self.r2 and self.c1 == self.c2


# functions that look at a cell without using its value as a number
_TESTS = frozenset({
    "ISBLANK", "ISNUMBER", "ISTEXT", "ISNONTEXT", "ISERROR", "ISERR", "ISNA", "ISLOGICAL",
    "ISREF", "ISFORMULA", "ISEVEN", "ISODD", "COUNT", "COUNTA", "COUNTBLANK", "COUNTIF",
    "COUNTIFS", "N", "T", "LEN", "ROW", "ROWS", "COLUMN", "COLUMNS", "CELL", "OFFSET",
    "INDIRECT", "IFERROR", "IFNA", "TYPE", "AND", "OR", "NOT",
})


class Grid:
    """Every cell of a workbook by kind; every formula cell's run."""

    def __init__(self, inputs, runs):
        self.inputs = inputs
        self.formulas = inputs.formulas
        self.cached = inputs.cached
        self.constants = inputs.constants
        # cells an array formula fills (its master included): compared with nothing
        self.array = set(inputs.array_cells) | set(inputs.array_master)
        self.sheets = {s.lower(): s for s in inputs.book.sheet_names}
        self.runs = [r for r in runs if (r.sheet, r.first, r.col) in self.formulas]
        self.key_of_run = [to_relative(run.node, run.first, run.col) for run in self.runs]
        by_column: dict[tuple[str, int], list[tuple[int, int]]] = {}
        for i, run in enumerate(self.runs):
            by_column.setdefault((run.sheet, run.col), []).append((run.first, i))
        self._starts = {}
        for column, starts in by_column.items():
            starts.sort()
            self._starts[column] = ([f for f, _ in starts], [i for _, i in starts])
        # formula cells in no run: those that did not parse
        self.unparsed = [] if sum(r.last - r.first + 1 for r in self.runs) == len(self.formulas) \
            else [k for k in self.formulas if self.run_index(k) is None]
        self._names: dict[str, ast.Node | None] = {}
        self._lines: dict[str, tuple[set, tuple]] | None = None

    def run_index(self, key: Key) -> int | None:
        """The index of the run holding formula cell ``key``, None if none does."""
        found = self._starts.get((key[0], key[2]))
        if found is None:
            return None
        starts, indexes = found
        at = bisect_right(starts, key[1]) - 1
        if at < 0 or self.runs[indexes[at]].last < key[1]:
            return None
        return indexes[at]

    def extent(self, sheet: str) -> tuple[set, tuple]:
        """The columns holding cells and the used range (r1, c1, r2, c2) of a sheet."""
        if self._lines is None:
            lines: dict[str, tuple[set, list]] = {}

            def add(s, r1, c, r2):
                cols, box = lines.setdefault(s, (set(), [r1, c, r2, c]))
                cols.add(c)
                box[:] = [min(box[0], r1), min(box[1], c), max(box[2], r2), max(box[3], c)]
            for run in self.runs:
                add(run.sheet, run.first, run.col, run.last)
            for s, r, c in (*self.unparsed, *self.constants):
                add(s, r, c, r)
            self._lines = {s: (cols, tuple(box)) for s, (cols, box) in lines.items()}
        return self._lines.get(sheet, (set(), (1, 1, 0, 0)))

    # what a cell holds -------------------------------------------------------------
    def kind(self, key: Key) -> str | None:
        if key in self.formulas:
            return FORMULA
        if key not in self.constants or key in self.array:
            return FORMULA if key in self.array else EMPTY
        return value_kind(self.constants[key])

    def value(self, key: Key):
        """The value the file shows (cached for a formula)."""
        if key in self.formulas:
            return self.cached.get(key)
        return self.constants.get(key)

    def r1c1(self, key: Key) -> str | None:
        """The formula's R1C1 text; None for a formula that did not parse, or no formula."""
        run = self.run_index(key)
        return None if run is None else self.key_of_run[run]

    def notable_empty(self, sheet: str, col: int, first: int, last: int):
        """(row, why) for the rows ``first..last`` of column ``col`` whose cell is empty
        and stands out: in an empty column, or outside the sheet's used range. An empty
        cell in a column of data, or a blank row between blocks, is most often left
        blank on purpose: not listed."""
        cols, box = self.extent(sheet)
        outside = "outside the sheet's used range"
        if col not in cols:
            inside_cols = box[1] <= col <= box[3]
            return [(r, "an empty column" if inside_cols and box[0] <= r <= box[2] else outside)
                    for r in range(first, last + 1)]
        return [(r, outside) for r in range(first, min(last, box[0] - 1) + 1)] + \
            [(r, outside) for r in range(max(first, box[2] + 1), last + 1)]

    def sheet(self, name: str | None, home: str) -> str | None:
        """The canonical name of a sheet a reference names; None for an external one."""
        if name is None:
            return home
        if name.startswith("["):
            return None
        return self.sheets.get(name.lower(), name)

    # what a formula reads --------------------------------------------------------
    def refs(self, key: Key, names: bool = True) -> Iterator[Ref]:
        """The references the formula of ``key`` makes (defined names followed)."""
        run_index = self.run_index(key)
        if run_index is None:
            return
        run = self.runs[run_index]
        yield from self._refs(run.node, key[0], key[1] - run.first, names, 0)

    def _refs(self, node, home: str, dr: int, names: bool, depth: int) -> Iterator[Ref]:
        stack = [(node, "", False)]
        while stack:
            n, function, guarded = stack.pop()
            if isinstance(n, ast.CellRef):
                sheet = self.sheet(n.sheet, home)
                if sheet is not None:
                    row = n.row if n.row_abs else n.row + dr
                    yield Ref(sheet, row, n.col, row, n.col, n, function, guarded)
                continue
            if isinstance(n, ast.RangeRef):
                sheet = self.sheet(n.sheet, home)
                if sheet is not None:
                    rows = [c.row if c.row_abs else c.row + dr for c in (n.first, n.last)]
                    cols = [n.first.col, n.last.col]
                    yield Ref(sheet, min(rows), min(cols), max(rows), max(cols), n, function,
                              guarded)
                continue
            if isinstance(n, ast.Name):
                if names and depth < 8:
                    inner = self._name(n.name, self.sheet(n.sheet, home) or home)
                    if inner is not None:
                        yield from self._refs(inner, home, 0, names, depth + 1)
                continue
            if isinstance(n, ast.Func):
                for i, arg in enumerate(n.args):
                    test = n.name in _TESTS or (n.name == "IF" and i == 0)
                    stack.append((arg, n.name, guarded or test))
                continue
            if isinstance(n, ast.Binary) and n.op in ("=", "<>") and any(
                    isinstance(side, ast.String) for side in (n.left, n.right)):
                stack.extend((side, function, True) for side in (n.left, n.right))
                continue
            stack.extend((child, function, guarded) for child in ast.children(n))

    def _name(self, name: str, sheet: str):
        folded = (sheet, name.upper())
        if folded not in self._names:
            book = self.inputs.book
            text = book.resolve_name(name, sheet if sheet.lower() in self.sheets else None)
            node = None
            if text is not None:
                try:
                    node = parse_name(text)
                except FormulaSyntaxError:
                    node = None
            self._names[folded] = node
        return self._names[folded]


def value_kind(value) -> str | None:
    if value is None:
        return EMPTY
    if isinstance(value, bool):
        return BOOL
    if isinstance(value, (int, float)):
        return NUMBER
    if isinstance(value, ExcelError):
        return ERROR
    return TEXT


def show_value(value: object) -> str:
    """A cell's value as a message shows it: a number to 15 significant digits (as Excel
    displays it), an error by its text, anything else (text, a boolean) as its repr."""
    if isinstance(value, float):
        return f"{value:.15g}"
    if isinstance(value, ExcelError):
        return value.value
    return repr(value)
