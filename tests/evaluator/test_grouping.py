"""Cutting a column of formulas into runs (workbook_gen/evaluator/grouping.py) against an
independent rule: a row continues the run above it exactly when its text is the run's
first formula parsed, shifted down by the rows between (formula.ast.shift) and printed."""

from __future__ import annotations

import random

import pytest

from workbook_gen.evaluator.grouping import find_runs
from workbook_gen.formula import parse, render
from workbook_gen.formula.ast import shift

# templates over the row r: several relative rows, repeated ones, absolute ones, sheets
SHAPES = [
    "A{r}*2",
    "IF(Table!AC{a}=\"ok\",-(omega_1^2)*S{r}+l_BE/l_BC*(S{r}-R{r}),\"n/a\")",
    "SUM(B{a}:B{r})+$C$5-C{b}",
    "Data!A{r}+'My sheet'!B{b}*B{r}+A$2",
    "MAX(B4:M4)<=check_tol",
    "INDEX(Table!$B$5:$B$99,MATCH(MAX(C{a}:C{b}),C{a}:C{b},0))",
]


def _text(shape: str, r: int) -> str:
    return shape.format(r=r, a=r - 3, b=r + 6)


def _reference_runs(rows: list[int], texts: list[str]) -> list[tuple[int, int]]:
    runs, i = [], 0
    while i < len(rows):
        first, tree, j = rows[i], parse(texts[i]), i + 1
        while j < len(rows) and rows[j] == rows[j - 1] + 1 \
                and texts[j] == render(shift(tree, rows[j] - first, 0)):
            j += 1
        runs.append((first, rows[j - 1]))
        i = j
    return runs


@pytest.mark.parametrize("seed", range(40))
def test_runs_are_those_the_shifted_first_formula_gives(seed):
    rng = random.Random(seed)
    rows, texts, r = [], [], 10
    while len(rows) < rng.randint(5, 400):
        shape, length = rng.choice(SHAPES), rng.choice([1, 2, 7, 40, 150])
        slip = rng.random() < 0.3  # one row of the block off by one row, or a gap
        for k in range(length):
            row = r + k
            text = _text(shape, row + (1 if slip and k == length // 2 else 0))
            rows.append(row)
            texts.append(text)
        r += length + (rng.random() < 0.2)
    runs = find_runs(rows, texts, "S", 1, {})
    assert [(run.first, run.last) for run in runs] == _reference_runs(rows, texts)
    for run in runs:  # each run's tree is its first formula's
        assert render(run.node) == texts[rows.index(run.first)]
