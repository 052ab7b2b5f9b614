"""formula/functions/engineering.py: BASE/DECIMAL against Python's int(text, base), ROMAN
and ARABIC against a classic-form converter written here, the BIT* functions against
Python's integer operators, ERF/ERFC against math.erf, the reciprocal trigonometric and
hyperbolic functions against math, MULTINOMIAL and SERIESSUM from their definitions."""

from __future__ import annotations

import math
import random

import pytest

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


def test_erf_and_the_reciprocal_functions_as_math():
    for _ in range(100):
        x = RNG.uniform(-3, 3)
        y = x + RNG.uniform(0.1, 2)
        assert ev(f"=ERF({x!r})") == pytest.approx(math.erf(x), rel=1e-13, abs=1e-15)
        assert ev(f"=ERF.PRECISE({x!r})") == pytest.approx(math.erf(x), rel=1e-13, abs=1e-15)
        assert ev(f"=ERF({x!r},{y!r})") == pytest.approx(math.erf(y) - math.erf(x), rel=1e-12)
        assert ev(f"=ERFC({x!r})") == pytest.approx(math.erfc(x), rel=1e-13)
        assert ev(f"=COT({x!r})") == pytest.approx(1 / math.tan(x), rel=1e-13)
        assert ev(f"=CSC({x!r})") == pytest.approx(1 / math.sin(x), rel=1e-13)
        assert ev(f"=SEC({x!r})") == pytest.approx(1 / math.cos(x), rel=1e-13)
        assert ev(f"=COTH({x!r})") == pytest.approx(1 / math.tanh(x), rel=1e-13)
        assert ev(f"=CSCH({x!r})") == pytest.approx(1 / math.sinh(x), rel=1e-13)
        assert ev(f"=SECH({x!r})") == pytest.approx(1 / math.cosh(x), rel=1e-13)
        assert ev(f"=ACOT({x!r})") == pytest.approx(math.pi / 2 - math.atan(x), rel=1e-13)
    assert ev("=ACOTH(3)") == pytest.approx(math.atanh(1 / 3), rel=1e-14)
    assert ev("=ACOTH(0.5)") == ExcelError.NUM   # |x| >= 1
    assert ev("=COT(0)") == ExcelError.DIV0


def test_multinomial_and_seriessum_from_their_definitions():
    for _ in range(50):
        parts = [RNG.randint(0, 8) for _ in range(RNG.randint(1, 4))]
        want = math.factorial(sum(parts)) // math.prod(math.factorial(p) for p in parts)
        assert ev(f"=MULTINOMIAL({','.join(map(str, parts))})") == want
    # Microsoft's example: cos(pi/4) by the first four terms of its series
    coefficients = [1, -1 / 2, 1 / 24, -1 / 720]
    x = math.pi / 4
    want = sum(a * x ** (0 + 2 * i) for i, a in enumerate(coefficients))
    text = ",".join(repr(a) for a in coefficients)
    assert ev(f"=SERIESSUM(PI()/4,0,2,{{{text}}})") == pytest.approx(want, rel=1e-15)
    assert want == pytest.approx(0.707103, abs=5e-7)
