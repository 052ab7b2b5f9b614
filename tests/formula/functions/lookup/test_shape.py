"""formula/functions/dynamic.py: the array-shaping functions against numpy on random
arrays (SEQUENCE, TOCOL/TOROW by row or column, WRAPROWS/WRAPCOLS with padding, TAKE,
DROP, CHOOSEROWS/CHOOSECOLS, EXPAND, HSTACK/VSTACK) and the text splitters against
Python's str (TEXTBEFORE, TEXTAFTER, TEXTSPLIT)."""

from __future__ import annotations

import random

import numpy as np
import pytest

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


def test_sequence_as_arange():
    for _ in range(20):
        r, c, start, step = RNG.randint(1, 6), RNG.randint(1, 6), RNG.randint(-5, 5), \
            RNG.choice([1, 2, -3, 0.5])
        want = (start + step * np.arange(r * c)).reshape(r, c)
        assert ev(f"=SEQUENCE({r},{c},{start},{step})") == want.tolist()


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


def q(s: str) -> str:
    return '"' + s + '"'


def test_text_before_after_split_as_str():
    words = ["ab", "c", "", "def", "g"]
    for _ in range(40):
        parts = [RNG.choice(words) for _ in range(RNG.randint(2, 5))]
        s = "-".join(parts)
        n = RNG.randint(1, len(parts) - 1)
        assert ev(f'=TEXTBEFORE({q(s)},"-",{n})') == "-".join(parts[:n])
        assert ev(f'=TEXTAFTER({q(s)},"-",{n})') == "-".join(parts[n:])
        assert ev(f'=TEXTAFTER({q(s)},"-",-{n})') == "-".join(parts[len(parts) - n:])
        assert ev(f'=TEXTSPLIT({q(s)},"-")') == [parts]
        assert ev(f'=TEXTSPLIT({q(s)},,"-")') == [[p] for p in parts]
        if any(parts):   # ignore_empty drops the empty pieces
            assert ev(f'=TEXTSPLIT({q(s)},"-",,TRUE)') == [[p for p in parts if p]]
    assert ev('=TEXTBEFORE("abc","x")') == ExcelError.NA
    assert ev('=TEXTBEFORE("aXbxc","x",1,1)') == "a"            # match_mode 1: any case
