"""formula/functions/engineering/special.py: ERF, ERF.PRECISE and ERFC against Python's
math.erf and math.erfc (and, on the way, the reciprocal trigonometric and hyperbolic
functions against math); DELTA and GESTEP."""

from __future__ import annotations

import math
import random

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


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


def test_delta_and_gestep():
    assert ev("=DELTA(5,4)") == 0 and ev("=DELTA(5,5)") == 1 and ev("=DELTA(0)") == 1
    assert ev("=GESTEP(5,4)") == 1 and ev("=GESTEP(-4,-5)") == 1 and ev("=GESTEP(-1)") == 0
