"""formula/functions/arrayops.py: SORT, SORTBY, UNIQUE and FILTER against Python's
sorted (stable, Excel's type order: numbers < text < booleans, text case-insensitive),
dict-ordered uniqueness and list comprehensions, on random tables. An empty result is
#VALUE!, the value Mac Excel 16 cached in formulas__test.xlsx (newer builds document
#CALC!; arrayops.py's docstring)."""

from __future__ import annotations

import random

import pytest

from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula.arrays import evaluate_array
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)


def ev(text: str):
    value = evaluate_array(parse(text), DictResolver({}), "excel", None)
    return [list(r) for r in value.rows] if hasattr(value, "rows") else value


def lit(rows) -> str:
    def one(v):
        if isinstance(v, bool):
            return "TRUE" if v else "FALSE"
        if isinstance(v, str):
            return '"' + v + '"'
        return repr(float(v))
    return "{" + ";".join(",".join(one(v) for v in r) for r in rows) + "}"


def key(v):
    """Excel's sort key: numbers, then text (case-insensitive), then FALSE, TRUE."""
    if isinstance(v, bool):
        return (2, v)
    if isinstance(v, str):
        return (1, v.lower())
    return (0, v)


def table(n_rows: int, n_cols: int):
    pool = [1.0, 2.0, 3.5, -4.0, "a", "B", "b", True, False]
    return [[RNG.choice(pool) for _ in range(n_cols)] for _ in range(n_rows)]


@pytest.mark.parametrize("seed", range(10))
def test_sort_and_sortby(seed):
    rows = table(RNG.randint(1, 8), RNG.randint(1, 3))
    col = RNG.randint(1, len(rows[0]))
    for order in (1, -1):
        # (Python's reverse sort is stable too: ties keep their order)
        want = sorted(rows, key=lambda r: key(r[col - 1]), reverse=order == -1)
        assert ev(f"=SORT({lit(rows)},{col},{order})") == want
    by = [[RNG.randint(1, 5)] for _ in rows]
    want = [r for _, r in sorted(zip((b[0] for b in by), rows), key=lambda p: p[0])]
    assert ev(f"=SORTBY({lit(rows)},{lit(by)})") == want


@pytest.mark.parametrize("seed", range(10))
def test_unique_and_filter(seed):
    rows = table(RNG.randint(1, 10), RNG.randint(1, 2))
    seen = {}
    for r in rows:
        seen.setdefault(tuple(key(v) for v in r), r)
    assert ev(f"=UNIQUE({lit(rows)})") == list(seen.values())
    counts = {}
    for r in rows:
        counts[tuple(key(v) for v in r)] = counts.get(tuple(key(v) for v in r), 0) + 1
    once = [r for r in rows if counts[tuple(key(v) for v in r)] == 1]
    assert ev(f"=UNIQUE({lit(rows)},FALSE,TRUE)") == (once or ExcelError.VALUE)
    mask = [[RNG.choice([True, False])] for _ in rows]
    kept = [r for r, m in zip(rows, mask) if m[0]]
    assert ev(f"=FILTER({lit(rows)},{lit(mask)})") == (kept or ExcelError.VALUE)
    assert ev(f'=FILTER({lit(rows)},{lit([[False]] * len(rows))},"none")') == "none"
