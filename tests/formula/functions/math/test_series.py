"""formula/functions/math/series.py: MULTINOMIAL and SERIESSUM from their definitions
(Microsoft's SERIESSUM example: cos(pi/4) by four terms), SEQUENCE as numpy's arange."""

from __future__ import annotations

import math
import random

import numpy as np
import pytest

from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula.arrays import evaluate_array

RNG = random.Random(23)


def ev(text: str):
    value = evaluate_array(parse(text), DictResolver({}), "excel", None)
    return [list(r) for r in value.rows] if hasattr(value, "rows") else value


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


def test_sequence_as_arange():
    for _ in range(20):
        r, c, start, step = RNG.randint(1, 6), RNG.randint(1, 6), RNG.randint(-5, 5), \
            RNG.choice([1, 2, -3, 0.5])
        want = (start + step * np.arange(r * c)).reshape(r, c)
        assert ev(f"=SEQUENCE({r},{c},{start},{step})") == want.tolist()
