"""The sheets as a grid of cell kinds, for the findings: what each cell holds (a formula
and its R1C1 form, a number, text, a boolean, an error, nothing) and what each formula
reads.

Built from the audit's inputs and the evaluator's runs (a column's rows whose formulas
are equal in R1C1 form, one parsed tree per run): the R1C1 text is computed once per
run, and a formula's references at row ``first + dr`` of a run are the run's references
with their relative rows moved by ``dr``.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from ..errors import FormulaSyntaxError
from ..formula import ast, parse
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
        self.array = set(inputs.array_cells)
        self.sheets = {s.lower(): s for s in inputs.book.sheet_names}
        self.runs = [r for r in runs]
        self.run_of: dict[Key, int] = {}
        self.key_of_run: list[str] = []
        for i, run in enumerate(self.runs):
            self.key_of_run.append(ast.to_relative(run.node, run.first, run.col))
            for row in range(run.first, run.last + 1):
                self.run_of[(run.sheet, row, run.col)] = i
        self._names: dict[str, ast.Node | None] = {}
        self._lines: dict[str, tuple[set, set, tuple]] | None = None

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
        run = self.run_of.get(key)
        return None if run is None else self.key_of_run[run]

    def emptiness(self, key: Key) -> str | None:
        """Why an empty cell stands out: "an empty column", "outside the used range";
        None otherwise (an empty cell in a column of data, or a blank row between blocks,
        is most often left blank on purpose)."""
        if self._lines is None:
            self._lines = {}
            for sheet, row, col in (*self.formulas, *self.constants):
                rows, cols, box = self._lines.get(sheet, (set(), set(), (row, col, row, col)))
                rows.add(row)
                cols.add(col)
                box = (min(box[0], row), min(box[1], col), max(box[2], row), max(box[3], col))
                self._lines[sheet] = (rows, cols, box)
        sheet, row, col = key
        _, cols, box = self._lines.get(sheet, (set(), set(), (0, 0, 0, 0)))
        if not (box[0] <= row <= box[2] and box[1] <= col <= box[3]):
            return "outside the sheet's used range"
        if col not in cols:
            return "an empty column"
        return None

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
        run_index = self.run_of.get(key)
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
                    node = parse(str(text).lstrip("="))
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
