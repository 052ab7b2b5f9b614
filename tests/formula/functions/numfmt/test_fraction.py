"""numfmt/fraction.py (through TEXT): "# ?/?", "# ??/??" and "# ???/???" show the whole part
and the last convergent of the fraction's continued fraction whose denominator fits in
9, 99 or 999 (Excel's choice, as SheetJS's ssf measured it: not always the closest
fraction), computed here by the textbook recurrence; fixed denominators ("# ?/4",
"# ??/16") round the numerator of the binary fraction half up; "?/?" without the whole
part folds it into the numerator."""

from __future__ import annotations

import math
import random
from fractions import Fraction

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse

RNG = random.Random(23)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def numbers(n=200):
    for _ in range(n):
        yield round(RNG.uniform(0, 50), RNG.randint(1, 6))
    yield from (0.75, 3.14159, 2.5, 0.333333, 1.0)


def parse_shown(text: str) -> Fraction:
    parts = text.split()
    total = Fraction(0)
    for p in parts:
        if "/" in p:
            a, b = p.split("/")
            total += Fraction(int(a), int(b))
        else:
            total += int(p)
    return total


def convergents(x: Fraction):
    """h/k of x's continued fraction, in order (the recurrence h_n = a_n h_n-1 + h_n-2)."""
    h0, h1, k0, k1 = 0, 1, 1, 0
    while True:
        a = math.floor(x)
        h0, h1, k0, k1 = h1, a * h1 + h0, k1, a * k1 + k0
        yield Fraction(h1, k1)
        if x == a:
            return
        x = 1 / (x - a)


@pytest.mark.parametrize("digits", [1, 2, 3])
def test_last_convergent_that_fits(digits):
    pattern = "# " + "?" * digits + "/" + "?" * digits
    limit = 10 ** digits - 1
    for x in numbers():
        text = ev(f'=TEXT({x!r},"{pattern}")')
        whole = math.floor(x)
        fits = [c for c in convergents(Fraction(x - whole)) if c.denominator <= limit]
        shown = parse_shown(text)
        assert shown - whole in fits, (x, text)
        if shown - whole != fits[-1]:   # an earlier one only when already within 1e-13
            assert abs(shown - Fraction(x)) <= Fraction(x - whole) * Fraction(1, 10**13), \
                (x, text)


@pytest.mark.parametrize("den", [2, 4, 8, 16, 100])
def test_fixed_denominators_round_half_up(den):
    places = len(str(den))
    pattern = "# " + "?" * places + "/" + str(den)
    for x in numbers():
        text = ev(f'=TEXT({x!r},"{pattern}")')
        whole = math.floor(x)
        num = math.floor(Fraction(x - whole) * den + Fraction(1, 2))
        got = parse_shown(text)
        assert got == whole + Fraction(num, den), (x, text)


def test_microsofts_forms():
    assert ev('=TEXT(0.75,"# ?/?")').strip() == "3/4"
    assert ev('=TEXT(3.14159,"# ??/???")') == "3 16/113"
    assert ev('=TEXT(2.5,"?/?")') == "5/2"
