"""Find the blocks of a column whose formulas are the same in relative (R1C1) form.

Parsing every cell is the slow part of reading a workbook (about 0.2 ms a formula), so
a column is cut into runs without parsing: two formulas belong to the same run when
their texts are equal after replacing every digit run by a marker (the "skeleton")
and their digit runs are equal except the row numbers of relative references, which
differ by exactly the row offset. Those two conditions mean the text of row ``r`` is the
text of the run's first row with relative rows shifted by ``r - first``: its tree is
``shift(first_tree, r - first, 0)`` and its ``to_relative`` key is the same. Only the
first formula of each run is parsed. (Formulas equal in R1C1 form but written
differently, e.g. with other spacing, start new runs: correct, just less grouped.)
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from workbook_gen.errors import FormulaSyntaxError
from workbook_gen.formula import ast
from workbook_gen.formula import tokenizer as tk
from workbook_gen.formula.parser import parse
from workbook_gen.formula.printer import render

_DIGITS = re.compile(r"[0-9]+")


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


def _relative_rows(text: str) -> np.ndarray:
    """Per digit run of ``text``: True where it is the row of a relative reference."""
    starts = set()
    for token in tk.tokenize(text):
        if token.kind != tk.REF:
            continue
        _, body = tk.split_sheet(token.text)
        offset = token.pos + len(token.text) - len(body)
        for m in tk.CELL_PARTS.finditer(body):
            if not m.group(3):
                starts.add(offset + m.start(4))
    return np.array([m.start() in starts for m in _DIGITS.finditer(text)], bool)


def _consistent(texts: list[str], rows: list[int], rel: np.ndarray) -> int:
    """How many leading texts (same skeleton) follow the first by a pure row shift."""
    digits = np.array([_DIGITS.findall(t) for t in texts])
    if digits.ndim != 2 or digits.shape[1] != len(rel):
        return 1
    if digits.shape[1] == 0:
        return len(texts)
    ok = np.ones(len(texts), bool)
    fixed = ~rel
    if fixed.any():
        ok &= (digits[:, fixed] == digits[0, fixed]).all(axis=1)
    if rel.any():
        text = digits[:, rel]
        short = (np.char.str_len(text) <= 7).all(axis=1)
        moved = np.where(short[:, None], text, "0").astype(np.int64)
        offset = np.asarray(rows) - rows[0]
        ok &= short & (moved == moved[0] + offset[:, None]).all(axis=1)
        ok &= (moved <= ast.MAX_ROW).all(axis=1)
    bad = np.flatnonzero(~ok)
    return int(bad[0]) if len(bad) else len(texts)


def find_runs(column: list[tuple[int, str]], sheet: str, col: int,
              syntax_errors: dict) -> list[Run]:
    """Cut one column's formulas (sorted by row) into runs; bad formulas go to
    ``syntax_errors[(sheet, row, col)]`` and into no run."""
    skeletons = [_DIGITS.sub("\0", text) for _, text in column]
    runs = []
    i = 0
    while i < len(column):
        row, text = column[i]
        try:
            node = parse(text)
        except FormulaSyntaxError as exc:
            syntax_errors[(sheet, row, col)] = str(exc)
            i += 1
            continue
        j = i + 1
        while (j < len(column) and column[j][0] == row + (j - i)
               and skeletons[j] == skeletons[i]):
            j += 1
        if j > i + 1:
            span = column[i:j]
            j = i + _consistent([t for _, t in span], [r for r, _ in span], _relative_rows(text))
        runs.append(Run(sheet, col, row, row + (j - i) - 1, node))
        i = j
    return runs


def group_formulas(formulas) -> tuple[list[Run], dict]:
    """Runs of every column of ``formulas`` {(sheet, row, col): text}, and syntax errors."""
    columns: dict[tuple[str, int], list[tuple[int, str]]] = {}
    for (sheet, row, col), text in formulas.items():
        columns.setdefault((sheet, col), []).append((row, text))
    runs: list[Run] = []
    errors: dict = {}
    for (sheet, col), cells in columns.items():
        cells.sort()
        runs.extend(find_runs(cells, sheet, col, errors))
    return runs, errors
