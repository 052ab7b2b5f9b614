"""formula/functions/math.py against exact arithmetic: ROUND/ROUNDUP/ROUNDDOWN round the
number's 15-digit decimal (Excel's ROUND(2.675,2) is 2.68) half away from zero (Python's
decimal); CEILING/FLOOR and their .MATH/.PRECISE forms and MROUND by Microsoft's rules
on exact fractions; QUOTIENT truncates; GCD/LCM as math.gcd/lcm; FACTDOUBLE, SUMSQ,
PRODUCT, LOG from their definitions; RANDBETWEEN within its bounds."""

from __future__ import annotations

import math
import random
from decimal import ROUND_DOWN, ROUND_HALF_UP, ROUND_UP, Decimal
from fractions import Fraction

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def xs(n=300):
    for _ in range(n):
        yield round(RNG.uniform(-1000, 1000), RNG.randint(0, 6))
    yield from (2.675, -2.5, 0.5, 1.005, 1234.5678, -0.0049999, 1e-10)


def decimal_round(x: float, digits: int, mode) -> float:
    d = Decimal(f"{x:.15g}")
    q = Decimal(1).scaleb(-digits)
    return float(d.quantize(q, rounding=mode)) if digits >= 0 else \
        float((d / Decimal(10) ** -digits).quantize(Decimal(1), rounding=mode)
              * Decimal(10) ** -digits)


@pytest.mark.parametrize("name, mode", [("ROUND", ROUND_HALF_UP), ("ROUNDUP", ROUND_UP),
                                        ("ROUNDDOWN", ROUND_DOWN)])
def test_round_family_on_the_15_digit_decimal(name, mode):
    for x in xs():
        digits = RNG.randint(-2, 4)
        assert ev(f"={name}({x!r},{digits})") == decimal_round(x, digits, mode), (x, digits)


def multiple(x: float, m: float, up: bool) -> float:
    """The multiple of m at or beyond x: up (towards +inf) or down, exactly, on the
    decimals Excel shows (785 is a multiple of 0.1, though not of the binary 0.1)."""
    q = Fraction(f"{x:.15g}") / Fraction(str(m))
    k = math.ceil(q) if up else math.floor(q)
    return float(k * Fraction(str(m)))


def test_ceiling_floor_and_mround():
    for x in xs():
        m = RNG.choice([0.5, 1, 2, 3, 0.1, 5])
        # CEILING.PRECISE / FLOOR.PRECISE: towards +inf / -inf whatever m's sign
        assert ev(f"=CEILING.PRECISE({x!r},{m})") == pytest.approx(multiple(x, m, True))
        assert ev(f"=FLOOR.PRECISE({x!r},{-m})") == pytest.approx(multiple(x, m, False))
        # CEILING(x, m) with signs alike: away from zero for negative x and m
        if x >= 0:
            assert ev(f"=CEILING({x!r},{m})") == pytest.approx(multiple(x, m, True))
            assert ev(f"=FLOOR({x!r},{m})") == pytest.approx(multiple(x, m, False))
        else:
            assert ev(f"=CEILING({x!r},{-m})") == pytest.approx(multiple(x, m, False))
            assert ev(f"=CEILING({x!r},{m})") == pytest.approx(multiple(x, m, True))
        # CEILING.MATH: mode 1 rounds negatives away from zero
        assert ev(f"=CEILING.MATH({x!r},{m})") == pytest.approx(multiple(x, m, True))
        want = multiple(x, m, x >= 0)
        assert ev(f"=CEILING.MATH({x!r},{m},1)") == pytest.approx(want)
        # MROUND: the nearest multiple, halves away from zero
        if x >= 0:
            q = Fraction(f"{x:.15g}") / Fraction(str(m))
            k = math.floor(q + Fraction(1, 2))
            assert ev(f"=MROUND({x!r},{m})") == pytest.approx(float(k * Fraction(str(m))))
    assert ev("=CEILING(2.5,-1)") == ExcelError.NUM     # a positive number, negative m
    assert ev("=MROUND(10,-3)") == ExcelError.NUM       # signs differ
    assert ev("=CEILING(2.5,0)") == 0 and ev("=FLOOR(2.5,0)") == ExcelError.DIV0


def test_integer_functions():
    for _ in range(200):
        a, b = RNG.randint(-10**6, 10**6), RNG.choice([1, -1]) * RNG.randint(1, 1000)
        assert ev(f"=QUOTIENT({a},{b})") == int(a / b)
        p, r = abs(a), abs(b)
        assert ev(f"=GCD({p},{r})") == math.gcd(p, r)
        assert ev(f"=LCM({p % 1000},{r})") == math.lcm(p % 1000, r)
    for n in range(0, 25):
        assert ev(f"=FACTDOUBLE({n})") == math.prod(range(n, 0, -2))
    assert ev("=FACTDOUBLE(-1)") == 1 and ev("=FACTDOUBLE(-2)") == ExcelError.NUM
    assert ev("=GCD(-1,2)") == ExcelError.NUM


def test_sums_products_logs_and_randbetween():
    values = [round(RNG.uniform(-9, 9), 3) for _ in range(20)]
    text = ",".join(map(repr, values))
    assert ev(f"=SUMSQ({text})") == pytest.approx(math.fsum(v * v for v in values))
    assert ev(f"=PRODUCT({text})") == pytest.approx(math.prod(values))
    assert ev(f"=SUM({text})") == pytest.approx(math.fsum(values))
    for x in (2.0, 8.0, 1000.0, 0.125):
        assert ev(f"=LOG({x})") == pytest.approx(math.log10(x), rel=1e-15)
        assert ev(f"=LOG({x},2)") == pytest.approx(math.log2(x), rel=1e-15)
    assert ev("=LOG(0)") == ExcelError.NUM and ev("=LOG(8,1)") == ExcelError.DIV0
    assert ev("=PI()") == math.pi
    draws = {ev("=RANDBETWEEN(-3,4)") for _ in range(400)}
    assert draws == set(range(-3, 5))
