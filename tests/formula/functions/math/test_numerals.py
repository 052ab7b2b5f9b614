"""formula/functions/math/numerals.py: BASE and DECIMAL against Python's int(text, base),
ROMAN and ARABIC against a classic-form converter written here (and Microsoft's
simplified form)."""

from __future__ import annotations

import random


from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)
DIGITS = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ"


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def to_base(n: int, base: int) -> str:
    out = ""
    while True:
        n, d = divmod(n, base)
        out = DIGITS[d] + out
        if not n:
            return out


def roman(n: int) -> str:
    pairs = [(1000, "M"), (900, "CM"), (500, "D"), (400, "CD"), (100, "C"), (90, "XC"),
             (50, "L"), (40, "XL"), (10, "X"), (9, "IX"), (5, "V"), (4, "IV"), (1, "I")]
    out = ""
    for value, letters in pairs:
        while n >= value:
            out, n = out + letters, n - value
    return out


def test_base_and_decimal_round_trip_as_int():
    for _ in range(200):
        n, base = RNG.randrange(0, 2**40), RNG.randint(2, 36)
        text = ev(f"=BASE({n},{base})")
        assert text == to_base(n, base) and int(text, base) == n
        assert ev(f'=DECIMAL("{text.lower()}",{base})') == n
    assert ev("=BASE(7,2,8)") == "00000111"          # min_length pads with zeros
    assert ev("=BASE(7,1)") == ExcelError.NUM        # radix 2..36
    assert ev('=DECIMAL("19",8)') == ExcelError.NUM  # 9 is no octal digit


def test_roman_and_arabic():
    for n in list(range(1, 400)) + RNG.sample(range(400, 4000), 200):
        assert ev(f"=ROMAN({n})") == roman(n)
        assert ev(f'=ARABIC("{roman(n)}")') == n
    assert ev("=ROMAN(499,0)") == "CDXCIX"   # classic form
    assert ev("=ROMAN(499,4)") == "ID"       # simplified form (Microsoft's example)
    assert ev("=ROMAN(4000)") == ExcelError.VALUE
    assert ev('=ARABIC("-XL")') == -40
    assert ev('=ARABIC("XQ")') == ExcelError.VALUE
