"""formula/functions/criteria.py (with math/conditional.py's SUMIF): COUNTIF, SUMIF,
AVERAGEIF, SUMIFS, MAXIFS, MINIFS and COUNTIFS against a Python filter of the same
comparisons on random columns; text criteria case-insensitive with ? * and ~."""

from __future__ import annotations

import random
import statistics

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)


def cells(values, col="A") -> dict:
    return {f"{col}{i}": v for i, v in enumerate(values, 1)}


def ev(text: str, data: dict):
    return evaluate(parse(text), DictResolver(data))


CRITERIA = [(">10", lambda v: v > 10), ("<=-5", lambda v: v <= -5), ("<>0", lambda v: v != 0),
            ("=12.5", lambda v: v == 12.5), ("25", lambda v: v == 25)]


@pytest.mark.parametrize("criterion, keep", CRITERIA)
def test_criteria_functions_as_a_filter(criterion, keep):
    n = 60
    xs = [float(RNG.choice([RNG.randint(-20, 30), 12.5, 25])) for _ in range(n)]
    ys = [round(RNG.uniform(-50, 50), 2) for _ in range(n)]
    data = {**cells(xs, "A"), **cells(ys, "B")}
    picked = [y for x, y in zip(xs, ys) if keep(x)]
    assert ev(f'=COUNTIF(A1:A{n},"{criterion}")', data) == len(picked)
    assert ev(f'=SUMIF(A1:A{n},"{criterion}",B1:B{n})', data) == pytest.approx(sum(picked))
    assert ev(f'=SUMIFS(B1:B{n},A1:A{n},"{criterion}")', data) == pytest.approx(sum(picked))
    if picked:
        assert ev(f'=AVERAGEIF(A1:A{n},"{criterion}",B1:B{n})', data) == \
            pytest.approx(statistics.fmean(picked))
        assert ev(f'=MAXIFS(B1:B{n},A1:A{n},"{criterion}")', data) == max(picked)
        assert ev(f'=MINIFS(B1:B{n},A1:A{n},"{criterion}")', data) == min(picked)
    else:
        assert ev(f'=AVERAGEIF(A1:A{n},"{criterion}",B1:B{n})', data) == ExcelError.DIV0
    both = [y for x, y in zip(xs, ys) if keep(x) and y > 0]
    assert ev(f'=COUNTIFS(A1:A{n},"{criterion}",B1:B{n},">0")', data) == len(both)


def test_text_criteria_are_case_insensitive_with_wildcards():
    words = ["apple", "Apricot", "banana", "APPLE", "grape", "a?c", "abc"]
    data = cells(words)
    assert ev('=COUNTIF(A1:A7,"apple")', data) == 2
    assert ev('=COUNTIF(A1:A7,"ap*")', data) == 3
    assert ev('=COUNTIF(A1:A7,"a?c")', data) == 2
    assert ev('=COUNTIF(A1:A7,"a~?c")', data) == 1          # ~ escapes the wildcard
