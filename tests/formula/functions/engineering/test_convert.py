"""formula/functions/engineering/convert.py: CONVERT against the units' legal definitions
(the 1959 international yard and pound, the standard atmosphere, temperature scales),
with its metric and binary prefixes, and its refusals."""

from __future__ import annotations

import random

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


# (from, to, factor): 1 from = factor to, by definition
DEFINED = [("in", "m", 0.0254), ("ft", "m", 0.3048), ("yd", "m", 0.9144),
           ("mi", "m", 1609.344), ("Nmi", "m", 1852.0), ("lbm", "kg", 0.45359237),
           ("ozm", "g", 0.45359237e3 / 16), ("hr", "sec", 3600.0), ("day", "mn", 1440.0),
           ("atm", "Pa", 101325.0), ("cal", "J", 4.1868), ("lbf", "N", 4.4482216152605),
           ("km", "m", 1e3), ("mm", "m", 1e-3), ("um", "m", 1e-6), ("GJ", "J", 1e9),
           ("kibyte", "byte", 1024.0), ("Mibit", "bit", 2.0**20), ("byte", "bit", 8.0)]


@pytest.mark.parametrize("src, dst, factor", DEFINED)
def test_convert_by_definition(src, dst, factor):
    for x in (1.0, 2.5, -7.25, RNG.uniform(-1e3, 1e3)):
        assert ev(f'=CONVERT({x!r},"{src}","{dst}")') == pytest.approx(x * factor, rel=1e-14)
        assert ev(f'=CONVERT({x!r},"{dst}","{src}")') == pytest.approx(x / factor, rel=1e-14)


def test_temperatures_and_refusals():
    for _ in range(50):
        c = RNG.uniform(-200, 500)
        assert ev(f'=CONVERT({c!r},"C","F")') == pytest.approx(c * 9 / 5 + 32, rel=1e-14)
        assert ev(f'=CONVERT({c!r},"C","K")') == pytest.approx(c + 273.15, rel=1e-14)
    assert ev('=CONVERT(68,"F","C")') == pytest.approx(20.0, rel=1e-15)  # Microsoft
    assert ev('=CONVERT(2.5,"ft","sec")') == ExcelError.NA   # another quantity
    assert ev('=CONVERT(1,"kin","m")') == ExcelError.NA      # inch takes no prefix
    assert ev('=CONVERT(1,"xyz","m")') == ExcelError.NA
