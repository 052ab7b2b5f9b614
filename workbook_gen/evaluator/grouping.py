"""Find the blocks of a column whose formulas are the same in relative (R1C1) form.

Parsing every cell is the slow part of reading a workbook (about 0.2 ms a formula), so
a column is cut into runs parsing only the first formula of each: the first text is
turned into a ``str.format`` template whose fields are the row numbers of its
relative references, and row ``r`` joins the run when its text is exactly that
template filled with the rows moved by ``r - first``. Its tree is then
``shift(first_tree, r - first, 0)`` and its ``to_relative`` key the same. Formulas
equal in R1C1 form but written differently (other spacing) start new runs: correct,
only less grouped.
"""

from __future__ import annotations

from dataclasses import dataclass

from workbook_gen.errors import FormulaSyntaxError, WorkbookReadError
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


def _escape(text: str) -> str:
    return text.replace("{", "{{").replace("}", "}}")


def template(text: str) -> tuple[str, list[int], list[str]] | None:
    """``text`` as a ``str.format`` template whose fields are the rows of its relative
    references, with the row of each field (references to the same row share a field) and
    the text between fields (so that with one field, ``str(row).join(between)`` is the
    template filled); None if a row is written oddly (``A05``)."""
    spans = []
    for token in tk.tokenize(text):
        if token.kind != tk.REF:
            continue
        _, body = tk.split_sheet(token.text)
        offset = token.pos + len(token.text) - len(body)
        for m in tk.CELL_PARTS.finditer(body):
            if not m.group(3):
                spans.append((offset + m.start(4), offset + m.end(4)))
    pieces, rows, between, at = [], [], [], 0
    field: dict[int, int] = {}  # row -> its field
    for a, b in spans:
        if text[a] == "0":
            return None
        between.append(text[at:a])
        pieces.append(_escape(text[at:a]))
        row = int(text[a:b])
        if row not in field:
            field[row] = len(rows)
            rows.append(row)
        pieces.append("{%d}" % field[row])
        at = b
    between.append(text[at:])
    pieces.append(_escape(text[at:]))
    return "".join(pieces), rows, between


# The audit's CPU cost on a 2-core machine (measured, see xlsx/limits.py): up to 44 us a
# formula cell of a run, and 0.5 ms more for each formula parsed and evaluated on its own
# (100,000 formulas that each differ from the cell above: 53 s). A workbook whose cost
# exceeds the budget is refused while it is being grouped, before the long part.
COST_CELL, COST_PARSED, BUDGET = 44e-6, 5e-4, 60.0


def find_runs(column: list[tuple[int, str]], sheet: str, col: int,
              syntax_errors: dict, allowed: list[int] | None = None) -> list[Run]:
    """Cut one column's formulas (sorted by row) into runs; formulas that do not parse
    go to ``syntax_errors[(sheet, row, col)]`` and into no run. ``allowed[0]``: how many
    more formulas may be parsed (WorkbookReadError beyond)."""
    runs = []
    i = 0
    while i < len(column):
        row, text = column[i]
        if allowed is not None:
            allowed[0] -= 1
            if allowed[0] < 0:
                raise WorkbookReadError(
                    "too many formulas that differ from the cell above them (each is parsed "
                    f"and evaluated on its own, about {COST_PARSED * 1e3:g} ms each): the "
                    f"audit would take over {BUDGET:g} s of CPU")
        try:
            node = parse(text)
        except FormulaSyntaxError as exc:
            syntax_errors[(sheet, row, col)] = str(exc)
            i += 1
            continue
        j = i + 1
        shape = template(text) if j < len(column) and column[j][0] == row + 1 else None
        if shape is not None:
            fmt, rows = shape[0].format, shape[1]
            n = len(column)
            if len(rows) == 1:  # the usual case: references to the cell's own row
                r0, first, between = rows[0] - i, row - i, shape[2]
                while j < n:
                    r, t = column[j]
                    if r != first + j or t != str(r0 + j).join(between):
                        break
                    j += 1
            else:
                while j < n and column[j][0] == row + (j - i):
                    dr = j - i
                    if column[j][1] != fmt(*[r + dr for r in rows]):
                        break
                    j += 1
        runs.append(Run(sheet, col, row, row + (j - i) - 1, node))
        i = j
    return runs


def group_formulas(formulas, budget: float | None = None) -> tuple[list[Run], dict]:
    """Runs of every column of ``formulas`` {(sheet, row, col): text}, and syntax errors.
    ``budget``: seconds of CPU the audit may cost (default: BUDGET)."""
    budget = BUDGET if budget is None else budget
    allowed = [int((budget - COST_CELL * len(formulas)) / COST_PARSED)]
    columns: dict[tuple[str, int], list[tuple[int, str]]] = {}
    for (sheet, row, col), text in formulas.items():
        cells = columns.get((sheet, col))
        if cells is None:
            cells = columns[(sheet, col)] = []
        cells.append((row, text))
    runs: list[Run] = []
    errors: dict = {}
    for (sheet, col), cells in columns.items():
        cells.sort()
        runs.extend(find_runs(cells, sheet, col, errors, allowed))
    return runs, errors
