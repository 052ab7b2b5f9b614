"""formula/functions/statistical/core.py: the aggregates against numpy and Python's
statistics on random ranges (text, booleans and blanks in a range are skipped, as
Microsoft documents; the *A forms count TRUE as 1 and text as 0), LARGE/SMALL/RANK against
sorting, MODE against collections.Counter, SUMPRODUCT against numpy.dot."""

from __future__ import annotations

import collections
import random
import statistics

import numpy as np
import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)


def cells(values, col="A") -> dict:
    return {f"{col}{i}": v for i, v in enumerate(values, 1)}


def ev(text: str, data: dict):
    return evaluate(parse(text), DictResolver(data))


def sample(n: int) -> list:
    """Numbers with some text, booleans and blanks among them."""
    out = []
    for _ in range(n):
        kind = RNG.random()
        out.append(RNG.choice(["x", "7", True, False, None]) if kind < 0.2
                   else round(RNG.uniform(-100, 100), RNG.randint(0, 4)))
    return out


AGGREGATES = {
    "SUM": np.sum, "AVERAGE": np.mean, "MIN": np.min, "MAX": np.max,
    "MEDIAN": statistics.median, "STDEV.S": lambda x: np.std(x, ddof=1),
    "STDEV.P": np.std, "VAR.S": lambda x: np.var(x, ddof=1), "VAR.P": np.var,
    "STDEV": lambda x: np.std(x, ddof=1), "VARP": np.var, "COUNT": len,
}


@pytest.mark.parametrize("name", sorted(AGGREGATES))
def test_aggregates_skip_what_is_not_a_number(name):
    for n in (3, 10, 57):
        values = sample(n)
        numbers = [v for v in values if type(v) in (int, float)]
        data = cells(values)
        got = ev(f"={name}(A1:A{n})", data)
        if len(numbers) < 2 and name in ("STDEV.S", "VAR.S", "STDEV"):
            assert got == ExcelError.DIV0
            continue
        assert got == pytest.approx(AGGREGATES[name](np.array(numbers, float)), rel=1e-12,
                                    abs=1e-12), (name, values)


def test_the_a_forms_count_booleans_and_text():
    values = [3.0, True, "text", False, 9.0]
    data = cells(values)
    as_numbers = [3.0, 1.0, 0.0, 0.0, 9.0]
    assert ev("=AVERAGEA(A1:A5)", data) == pytest.approx(np.mean(as_numbers))
    assert ev("=MAXA(A1:A5)", data) == 9.0 and ev("=MINA(A1:A5)", data) == 0.0
    assert ev("=COUNTA(A1:A6)", data) == 5 and ev("=COUNTBLANK(A1:A6)", data) == 1
    assert ev("=AVERAGE(A1:A5)", data) == 6.0                 # the plain form skips them


def test_large_small_rank_mode_sumproduct():
    values = [float(RNG.randint(-20, 20)) for _ in range(40)]
    data = {**cells(values), **cells(values[::-1], "B")}
    ordered = sorted(values)
    for k in (1, 2, 7, 40):
        assert ev(f"=LARGE(A1:A40,{k})", data) == ordered[-k]
        assert ev(f"=SMALL(A1:A40,{k})", data) == ordered[k - 1]
    assert ev("=LARGE(A1:A40,41)", data) == ExcelError.NUM
    x = values[5]
    assert ev(f"=RANK({x},A1:A40)", data) == 1 + sum(v > x for v in values)
    assert ev(f"=RANK({x},A1:A40,1)", data) == 1 + sum(v < x for v in values)
    ties = [i + 1 for i, v in enumerate(sorted(values, reverse=True)) if v == x]
    assert ev(f"=RANK.AVG({x},A1:A40)", data) == pytest.approx(statistics.fmean(ties))
    counts = collections.Counter(values)
    top = max(counts.values())
    first = next(v for v in values if counts[v] == top)     # the first of the most frequent
    assert ev("=MODE.SNGL(A1:A40)", data) == (first if top > 1 else ExcelError.NA)
    assert ev("=SUMPRODUCT(A1:A40,B1:B40)", data) == pytest.approx(
        float(np.dot(values, values[::-1])))
