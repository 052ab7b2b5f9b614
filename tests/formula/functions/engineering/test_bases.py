"""formula/functions/engineering/bases.py: DEC2BIN/OCT/HEX and back against Python's
integers in Excel's 10-digit two's complement, with places padding and its errors."""

from __future__ import annotations

import random

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


# (from, to, factor): 1 from = factor to, by definition


def twos(n: int, base: int) -> str:
    """Excel's form: negatives as 10-digit two's complement in the base."""
    digits = {2: 10, 8: 30, 16: 40}[base]   # 10 digits = this many bits
    n %= 2**digits
    return format(n, {2: "b", 8: "o", 16: "X"}[base])


@pytest.mark.parametrize("base, name, limit", [(2, "BIN", 2**9), (8, "OCT", 2**29),
                                              (16, "HEX", 2**39)])
def test_dec2x_and_back(base, name, limit):
    for _ in range(200):
        n = RNG.randrange(-limit, limit)
        text = ev(f"=DEC2{name}({n})")
        assert text == twos(n, base), n
        assert ev(f'={name}2DEC("{text}")') == n
    assert ev(f"=DEC2{name}({limit})") == ExcelError.NUM
    assert ev(f"=DEC2{name}(3,4)") == twos(3, base).zfill(4)      # places pad with zeros
    assert ev(f"=DEC2{name}({limit - 1},1)") == ExcelError.NUM    # too few places
