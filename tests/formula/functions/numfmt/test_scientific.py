"""numfmt/scientific.py (through TEXT): "0.00E+00" and "0.000E-0" give Python's decimal
E formatting of the number's 15-digit decimal rounded half away from zero, the exponent
at least two (or one) digits, "E-" showing only a negative sign; engineering "##0.0E+0"
keeps exponents that are multiples of three."""

from __future__ import annotations

import random
from decimal import ROUND_HALF_UP, Context, Decimal

from workbook_gen.formula import DictResolver, evaluate, parse

RNG = random.Random(23)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def numbers(n=300):
    for _ in range(n):
        yield RNG.choice([-1, 1]) * RNG.uniform(1, 10) * 10.0 ** RNG.randint(-30, 30)
    yield from (1.0, 9.995, 0.000123, 12345.678, 1e100, -2.5e-7)


def e_format(x: float, digits: int, exp_width: int, plus: bool) -> str:
    d = Decimal(f"{x:.15g}")
    text = Context(prec=digits + 1, rounding=ROUND_HALF_UP).create_decimal(d)
    mantissa, exponent = f"{text:.{digits}E}".split("E")
    e = int(exponent)
    sign = "+" if e >= 0 and plus else ("-" if e < 0 else "")
    return f"{mantissa}E{sign}{abs(e):0{exp_width}d}"


def test_scientific_as_decimal():
    for x in numbers():
        assert ev(f'=TEXT({x!r},"0.00E+00")') == e_format(x, 2, 2, True), x
        assert ev(f'=TEXT({x!r},"0.000E-0")') == e_format(x, 3, 1, False), x


def test_engineering_exponents_are_multiples_of_three():
    for x in numbers():
        text = ev(f'=TEXT({x!r},"##0.0E+0")')
        mantissa, exponent = text.split("E")
        assert int(exponent) % 3 == 0, (x, text)
        assert 1 <= abs(float(mantissa)) < 1000 or float(mantissa) == 0, (x, text)
        assert abs(float(text) - x) <= 0.051 * 10.0 ** int(exponent), (x, text)
    assert ev('=TEXT(0.000123,"##0.0E+0")') == "123.0E-6"
