"""formula/functions/lookup/shape.py: the array-shaping functions against numpy on random
arrays (TOCOL/TOROW by row or column, WRAPROWS/WRAPCOLS with padding, TAKE, DROP,
CHOOSEROWS/CHOOSECOLS, EXPAND, HSTACK/VSTACK)."""

from __future__ import annotations

import random

import numpy as np

from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula.arrays import evaluate_array
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)


def ev(text: str):
    value = evaluate_array(parse(text), DictResolver({}), "excel", None)
    return [list(r) for r in value.rows] if hasattr(value, "rows") else value


def lit(m) -> str:
    return "{" + ";".join(",".join(repr(float(x)) for x in r) for r in m) + "}"


def arrays(n=15):
    for _ in range(n):
        r, c = RNG.randint(1, 5), RNG.randint(1, 5)
        yield np.array([[float(RNG.randint(-9, 99)) for _ in range(c)] for _ in range(r)])


def test_reshaping_as_numpy():
    for a in arrays():
        text = lit(a)
        assert ev(f"=TOCOL({text})") == a.reshape(-1, 1).tolist()
        assert ev(f"=TOCOL({text},0,TRUE)") == a.T.reshape(-1, 1).tolist()      # by column
        assert ev(f"=TOROW({text})") == [a.reshape(-1).tolist()]
        k = RNG.randint(1, 4)
        flat = a.reshape(-1).tolist()
        pad = (-len(flat)) % k
        rows = np.array(flat + [None] * pad, dtype=object).reshape(-1, k)
        got = ev(f"=WRAPROWS(TOROW({text}),{k})")
        assert [[x for x in r] for r in got] == [[ExcelError.NA if x is None else x for x in r]
                                                  for r in rows.tolist()]
        assert ev(f"=WRAPCOLS(TOROW({text}),{k},0)") == \
            np.array(flat + [0.0] * pad).reshape(-1, k).T.tolist()


def test_take_drop_choose_expand_stack():
    for a in arrays():
        text, (r, c) = lit(a), a.shape
        i, j = RNG.randint(1, r), RNG.randint(1, c)
        assert ev(f"=TAKE({text},{i})") == a[:i].tolist()
        assert ev(f"=TAKE({text},-{i},{j})") == a[-i:, :j].tolist()
        if i < r:
            assert ev(f"=DROP({text},{i})") == a[i:].tolist()
        if j < c:
            assert ev(f"=DROP({text},0,-{j})") == a[:, :c - j].tolist()
        assert ev(f"=CHOOSEROWS({text},{i},1,-1)") == a[[i - 1, 0, -1]].tolist()
        assert ev(f"=CHOOSECOLS({text},{j})") == a[:, [j - 1]].tolist()
        grown = ev(f"=EXPAND({text},{r + 1},{c + 2},-1)")
        want = np.full((r + 1, c + 2), -1.0)
        want[:r, :c] = a
        assert grown == want.tolist()
        assert ev(f"=VSTACK({text},{text})") == np.vstack([a, a]).tolist()
        assert ev(f"=HSTACK({text},{text})") == np.hstack([a, a]).tolist()
    # (Microsoft documents #CALC! for TAKE(array, 0), the empty array; the evaluator gives
    # #VALUE!, as arrayops.py does for an empty FILTER after Mac Excel 16's cached values:
    # which Excel is right here is not settled, so neither is asserted)
    assert ev("=CHOOSEROWS({1,2;3,4},3)") == ExcelError.VALUE
