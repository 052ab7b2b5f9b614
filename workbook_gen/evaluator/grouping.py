"""Find the blocks of a column whose formulas are the same in relative (R1C1) form.

Parsing every cell is the slow part of reading a workbook (about 0.2 ms a formula), so
a column is cut into runs parsing only the first formula of each: the first text is
cut at the row numbers of its relative references (a ``template``), and row ``r`` joins
the run when its text is exactly those pieces joined by the rows moved by ``r - first``. Its tree is then
``shift(first_tree, r - first, 0)`` and its ``to_relative`` key the same. Formulas
equal in R1C1 form but written differently (other spacing) start new runs: correct,
only less grouped.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from itertools import repeat

import numpy as np

from workbook_gen.errors import FormulaSyntaxError, WorkbookReadError
from workbook_gen.evaluator.keys import column_groups, groups_by, pick
from workbook_gen.formula import ast
from workbook_gen.formula import tokenizer as tk
from workbook_gen.formula.parser import parse
from workbook_gen.formula.printer import render


@dataclass(frozen=True)
class Run:
    """Rows ``first..last`` of one column, all ``shift(node, row - first, 0)``."""

    sheet: str
    col: int
    first: int
    last: int
    node: ast.Node


def expand_shared(master: str, master_row: int, master_col: int, row: int, col: int) -> str:
    """The text of a shared-formula follower at (row, col) from its master's text."""
    node = ast.shift(parse(master), row - master_row, col - master_col)
    return render(node)


def template(text: str) -> tuple[list[int], list[str], list[int]] | None:
    """``text`` cut at the rows of its relative references: ``(rows, between, which)``,
    the distinct rows (references to the same row share one), the text around them, and
    which of ``rows`` each cut is (the text at row ``r`` of a run starting at ``first``
    is ``between`` joined by ``rows[which[k]] + r - first``); None if a row is written
    oddly (``A05``)."""
    spans = []
    for token in tk.tokenize(text):
        if token.kind != tk.REF:
            continue
        _, body = tk.split_sheet(token.text)
        offset = token.pos + len(token.text) - len(body)
        for m in tk.CELL_PARTS.finditer(body):
            if not m.group(3):
                spans.append((offset + m.start(4), offset + m.end(4)))
    rows, between, which, at = [], [], [], 0
    field: dict[int, int] = {}  # row -> its index in rows
    for a, b in spans:
        if text[a] == "0":
            return None
        between.append(text[at:a])
        row = int(text[a:b])
        if row not in field:
            field[row] = len(rows)
            rows.append(row)
        which.append(field[row])
        at = b
    between.append(text[at:])
    return rows, between, which


# The audit's CPU cost on a 2-core machine (measured, see xlsx/limits.py): up to 44 us a
# formula cell of a run, and 0.5 ms more for each formula parsed and evaluated on its own
# (100,000 formulas that each differ from the cell above: 53 s). A workbook whose cost
# exceeds the budget is refused while it is being grouped, before the long part.
COST_CELL, COST_PARSED, BUDGET = 44e-6, 5e-4, 60.0
_TOO_MANY = ("too many formulas that differ from the cell above them (each is parsed and "
             f"evaluated on its own, about {COST_PARSED * 1e3:g} ms each): the audit would "
             f"take over {BUDGET:g} s of CPU")


def find_runs(rows: list[int], texts: list[str], sheet: str, col: int,
              syntax_errors: dict, allowed: list[int] | None = None) -> list[Run]:
    """Cut one column's formulas (``texts`` at ``rows``, sorted) into runs; formulas that
    do not parse go to ``syntax_errors[(sheet, row, col)]`` and into no run.
    ``allowed[0]``: how many more formulas may be parsed (WorkbookReadError beyond)."""
    runs = []
    i, n = 0, len(texts)
    while i < n:
        row, text = rows[i], texts[i]
        if allowed is not None:
            allowed[0] -= 1
            if allowed[0] < 0:
                raise WorkbookReadError(_TOO_MANY)
        try:
            node = parse(text)
        except FormulaSyntaxError as exc:
            syntax_errors[(sheet, row, col)] = str(exc)
            i += 1
            continue
        j = i + 1
        shape = template(text) if j < n and rows[j] == row + 1 else None
        if shape is not None:
            j = _run_end(rows, texts, i, shape)
        runs.append(Run(sheet, col, row, row + (j - i) - 1, node))
        i = j
    return runs


def _run_end(rows: list[int], texts: list[str], i: int, shape) -> int:
    """The index after the last row of the run starting at ``i`` whose text is ``shape``
    (a ``template``) filled: the expected texts are made and compared a block at a time
    (C loops), blocks growing fourfold so that a run of one costs no more than a few."""
    fields, between, which = shape
    n, row = len(texts), rows[i]
    j, step = i + 1, 8
    while j < n:
        end = min(n, j + step)
        consecutive = range(row + j - i, row + end - i)
        got_rows = rows[j:end]
        broken = got_rows != list(consecutive)
        if broken:
            end = j + next(k for k, (a, b) in enumerate(zip(got_rows, consecutive)) if a != b)
            if end == j:
                return j
        got, expected = texts[j:end], _expected(fields, between, which, j - i, end - i)
        if got != expected:
            return j + next(k for k, (a, b) in enumerate(zip(got, expected)) if a != b)
        if broken:
            return end
        j, step = end, step * 4
    return j


def _expected(fields: list[int], between: list[str], which: list[int], lo: int,
              hi: int) -> list[str]:
    """The texts of a template's rows moved by ``lo .. hi - 1``: ``between`` joined by the
    rows' numbers, in C loops (joining is twice as fast as ``str.format``)."""
    if not fields:  # no relative row: the same text all along
        return [between[0]] * (hi - lo)
    numbers = [list(map(str, range(f + lo, f + hi))) for f in fields]
    if len(fields) == 1:
        return list(map(str.join, numbers[0], repeat(between)))
    parts = []
    for k, text in enumerate(between[:-1]):
        parts += (repeat(text), numbers[which[k]])
    parts.append(repeat(between[-1]))
    return list(map("".join, zip(*parts)))


def group_formulas(formulas, budget: float | None = None) -> tuple[list[Run], dict]:
    """Runs of every column of ``formulas`` {(sheet, row, col): text}, and syntax errors.
    ``budget``: seconds of CPU the audit may cost (default: BUDGET)."""
    grouped = Grouped()
    grouped.add(list(formulas), list(formulas.values()), budget)
    grouped.check(len(formulas), budget)
    return grouped.runs, grouped.errors


@dataclass
class Grouped:
    """Runs and syntax errors of formulas grouped a part at a time (each part a sheet, or
    several, whole: their columns are those of the whole), and the formulas parsed."""

    runs: list[Run] = field(default_factory=list)
    errors: dict = field(default_factory=dict)
    parsed: int = 0
    formulas: int = 0

    def add(self, keys: list, texts: list[str], budget: float | None = None) -> None:
        """Group the formulas ``texts`` of cells ``keys`` (sheet, row, col)."""
        self._add(_columns(keys, texts), len(keys), budget)

    def add_sheet(self, sheet: str, rows: list[int], cols: list[int], texts: list[str],
                  budget: float | None = None) -> None:
        """Group the formulas ``texts`` of one sheet's cells at ``rows``, ``cols``."""
        columns = []
        if texts:
            at = np.array(rows, np.int64)
            columns = [(sheet, cols[g[0]]) + _in_rows(at, g, texts)
                       for g in groups_by(np.array(cols, np.int64))]
        self._add(columns, len(texts), budget)

    def _add(self, columns, n: int, budget: float | None) -> None:
        self.formulas += n
        allowed = [allowance(self.formulas, budget) - self.parsed]
        before = allowed[0]
        for sheet, col, rows, col_texts in columns:
            self.runs.extend(find_runs(rows, col_texts, sheet, col, self.errors, allowed))
        self.parsed += before - allowed[0]

    def merge(self, part: "Grouped") -> None:
        """Add the runs of the next part, grouped on its own."""
        self.runs += part.runs
        self.errors.update(part.errors)
        self.parsed += part.parsed
        self.formulas += part.formulas

    def check(self, total: int, budget: float | None = None) -> None:
        """Refuse, as find_runs does, when the whole workbook (``total`` formulas) allows
        fewer parsed formulas than its parts parsed."""
        if self.parsed > allowance(total, budget):
            raise WorkbookReadError(_TOO_MANY)


def allowance(formulas: int, budget: float | None = None) -> int:
    """How many formulas may be parsed on their own in a workbook of ``formulas``."""
    return int(((BUDGET if budget is None else budget) - COST_CELL * formulas) / COST_PARSED)


def _columns(keys: list, texts: list[str]) -> list[tuple[str, int, list[int], list[str]]]:
    """``(sheet, col, rows, texts)`` of each column of the formulas ``texts`` of cells
    ``keys``, rows ascending, the columns in the order of their first formula."""
    groups, rows = column_groups(keys)
    return [(sheet, col) + _in_rows(rows, idx, texts) for sheet, col, idx in groups]


def _in_rows(rows: np.ndarray, idx: np.ndarray, texts: list[str]) -> tuple[list[int], list[str]]:
    """(rows, texts) of one column's cells ``idx``, rows ascending."""
    col_rows = rows[idx]
    if len(idx) > 1 and not (np.diff(col_rows) > 0).all():
        idx = idx[np.argsort(col_rows, kind="stable")]
        col_rows = rows[idx]
    return col_rows.tolist(), pick(texts, idx)
