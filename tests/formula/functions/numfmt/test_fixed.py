"""numfmt/fixed.py (through TEXT): fixed-point patterns give Python's decimal formatting
of the number's 15-digit decimal rounded half away from zero: "0", "0.00", "#,##0.00",
"0.0%", "000.000" (zero padding), "#.##" (no zeros forced), on random numbers."""

from __future__ import annotations

import random
from decimal import ROUND_HALF_UP, Decimal

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse

RNG = random.Random(23)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def numbers(n=300):
    for _ in range(n):
        yield round(RNG.uniform(-1e6, 1e6) * 10.0 ** RNG.randint(-6, 0), RNG.randint(0, 8))
    yield from (0.5, 1.5, 2.5, -0.5, 2.675, 1.005, 0.0, 999.995)


def rounded(x: float, places: int) -> Decimal:
    return Decimal(f"{x:.15g}").quantize(Decimal(1).scaleb(-places), rounding=ROUND_HALF_UP)


def signed(x: float, d: Decimal, text: str) -> str:
    return ("-" + text) if x < 0 and d != 0 else text


@pytest.mark.parametrize("places", [0, 2, 3])
def test_fixed_and_grouped(places):
    pattern = "0" + ("." + "0" * places if places else "")
    for x in numbers():
        d = rounded(x, places)
        assert ev(f'=TEXT({x!r},"{pattern}")') == signed(x, d, f"{abs(d):.{places}f}"), x
        assert ev(f'=TEXT({x!r},"#,##{pattern}")') == signed(x, d, f"{abs(d):,.{places}f}"), x


def test_percent_padding_and_optional_digits():
    for x in numbers():
        d = rounded(x * 100, 1)
        assert ev(f'=TEXT({x!r},"0.0%")') == signed(x, d, f"{abs(d):.1f}%"), x
        d = rounded(x, 3)
        whole, frac = f"{abs(d):.3f}".split(".")
        assert ev(f'=TEXT({x!r},"000.000")') == signed(x, d, f"{whole.zfill(3)}.{frac}"), x
        d = rounded(x, 2)
        text = f"{abs(d):.2f}".rstrip("0")
        text = text[1:] if text.startswith("0.") else text   # '#' shows no leading zero
        assert ev(f'=TEXT({x!r},"#.##")') == signed(x, d, text), x
