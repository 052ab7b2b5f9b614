"""formula/functions/text/arrays.py: TEXTBEFORE, TEXTAFTER and TEXTSPLIT against Python's
str on random texts (occurrences from either end, rows and columns, ignore_empty)."""

from __future__ import annotations

import random


from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula.arrays import evaluate_array
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)


def ev(text: str):
    value = evaluate_array(parse(text), DictResolver({}), "excel", None)
    return [list(r) for r in value.rows] if hasattr(value, "rows") else value


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
