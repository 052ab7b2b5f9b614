"""formula/functions/numeric.py: the BIT* functions against Python's integer operators on
random numbers below 2^48, and Excel's errors at and beyond that bound."""

from __future__ import annotations

import random


from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def test_bit_functions_as_integer_operators():
    for _ in range(200):
        a, b, s = RNG.randrange(0, 2**48), RNG.randrange(0, 2**48), RNG.randint(0, 20)
        assert ev(f"=BITAND({a},{b})") == a & b
        assert ev(f"=BITOR({a},{b})") == a | b
        assert ev(f"=BITXOR({a},{b})") == a ^ b
        assert ev(f"=BITRSHIFT({a},{s})") == a >> s
        small = a >> 20
        assert ev(f"=BITLSHIFT({small},{s})") == small << s
        assert ev(f"=BITLSHIFT({small},{-s})") == small >> s
    assert ev("=BITAND(2^48,1)") == ExcelError.NUM     # numbers below 2^48 only
    assert ev("=BITAND(1.5,1)") == ExcelError.NUM
    assert ev("=BITLSHIFT(1,48)") == ExcelError.NUM    # a result beyond 2^48 - 1
