"""formula/arrays.py: array formulas lift operators and scalar functions over arrays as
Excel documents: a row and a column broadcast to a grid (numpy's broadcasting), a single
row or column repeats, arrays of different sizes are #N/A beyond the smaller one; errors
stay in their elements; IF picks element by element; aggregates take the whole result."""

from __future__ import annotations

import math
import random

import numpy as np
import pytest

from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula.arrays import evaluate_array
from workbook_gen.xlerror import ExcelError

RNG = np.random.default_rng(23)


def ev(text: str):
    value = evaluate_array(parse(text), DictResolver({}), "excel", None)
    return [list(r) for r in value.rows] if hasattr(value, "rows") else value


def lit(a) -> str:
    return "{" + ";".join(",".join(repr(float(x)) for x in r) for r in np.atleast_2d(a)) + "}"


@pytest.mark.parametrize("op, fn", [("+", np.add), ("-", np.subtract), ("*", np.multiply),
                                    ("/", np.divide)])
def test_broadcasting_as_numpy(op, fn):
    for _ in range(20):
        r, c = int(RNG.integers(1, 5)), int(RNG.integers(1, 5))
        row = RNG.integers(1, 9, (1, c)).astype(float)
        col = RNG.integers(1, 9, (r, 1)).astype(float)
        grid = RNG.integers(1, 9, (r, c)).astype(float)
        assert ev(f"={lit(row)}{op}{lit(col)}") == fn(row, col).tolist()
        assert ev(f"={lit(grid)}{op}{lit(row)}") == fn(grid, row).tolist()
        assert ev(f"={lit(grid)}{op}{lit(col)}") == fn(grid, col).tolist()
        assert ev(f"={lit(grid)}{op}2") == fn(grid, 2.0).tolist()


def test_sizes_that_differ_are_na_beyond_the_smaller():
    for _ in range(20):
        a, b = int(RNG.integers(1, 6)), int(RNG.integers(1, 6))
        x, y = RNG.integers(1, 9, a).astype(float), RNG.integers(1, 9, b).astype(float)
        got = ev(f"={lit(x)}*{lit(y)}")[0]
        n = max(a, b)
        if min(a, b) == 1:   # a single element repeats
            assert got == (x * y).tolist()
        else:
            assert got == [x[i] * y[i] if i < min(a, b) else ExcelError.NA for i in range(n)]


def test_errors_stay_in_their_elements_and_if_picks_each():
    xs = [4.0, -1.0, 0.0, 9.0]
    got = ev(f"=SQRT({lit(xs)})")[0]
    assert got == [2.0, ExcelError.NUM, 0.0, 3.0]
    got = ev(f"=1/{lit(xs)}")[0]
    assert got == [0.25, -1.0, ExcelError.DIV0, 1 / 9]
    cond, a, b = [1, 0, 1, 0], [1.0, 2, 3, 4], [7.0, 8, 9, 10]
    assert ev(f"=IF({lit(cond)},{lit(a)},{lit(b)})")[0] == [1.0, 8.0, 3.0, 10.0]
    row, col = RNG.integers(1, 9, (1, 3)), RNG.integers(1, 9, (2, 1))
    assert ev(f"=SUM({lit(row)}*{lit(col)})") == float((row * col).sum())
    assert ev('={1,2}&"x"')[0] == ["1x", "2x"]
