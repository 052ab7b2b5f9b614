"""formula/functions/statfit.py: NORM.DIST/NORM.S.DIST/NORM.INV/NORM.S.INV and STANDARDIZE
against scipy.stats.norm, and FORECAST against numpy's least-squares line.

The lower tail is computed as 0.5 * (1 + erf(z / sqrt 2)) (Python's NormalDist), which
keeps only absolute accuracy there: NORM.S.DIST(-7.9, TRUE) is 1.388e-15 against the
true 1.3945e-15. Below z = -3 the test asks 1e-16 absolute, not relative (reported)."""

from __future__ import annotations

import random

import numpy as np
import pytest
from scipy import stats

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def test_normal_distribution_as_scipy():
    for _ in range(200):
        x, mean, sd = RNG.uniform(-30, 30), RNG.uniform(-5, 5), RNG.uniform(0.1, 8)
        z = (x - mean) / sd
        assert ev(f"=NORM.DIST({x!r},{mean!r},{sd!r},TRUE)") == pytest.approx(
            stats.norm.cdf(x, mean, sd), rel=1e-13, abs=1e-16 if z < -3 else 1e-300)
        assert ev(f"=NORM.DIST({x!r},{mean!r},{sd!r},FALSE)") == pytest.approx(
            stats.norm.pdf(x, mean, sd), rel=1e-15 * (1 + z * z), abs=1e-300)  # exp(-z^2/2)
        assert ev(f"=STANDARDIZE({x!r},{mean!r},{sd!r})") == pytest.approx(z, rel=1e-15)
        zs = max(-8.0, min(8.0, z))
        assert ev(f"=NORM.S.DIST({zs!r},TRUE)") == pytest.approx(
            stats.norm.cdf(zs), rel=1e-13, abs=1e-16 if zs < -3 else 1e-300)
        p = RNG.choice([RNG.uniform(1e-12, 1e-3), RNG.uniform(0.001, 0.999),
                        1 - RNG.uniform(1e-12, 1e-3)])
        assert ev(f"=NORM.S.INV({p!r})") == pytest.approx(stats.norm.ppf(p), rel=1e-14)
        assert ev(f"=NORM.INV({p!r},{mean!r},{sd!r})") == pytest.approx(
            stats.norm.ppf(p, mean, sd), rel=1e-13, abs=1e-13)
    assert ev("=NORMSDIST(1)") == ev("=NORM.S.DIST(1,TRUE)")
    assert ev("=NORM.S.INV(0)") == ExcelError.NUM and ev("=NORM.S.INV(1)") == ExcelError.NUM
    assert ev("=NORM.DIST(1,0,0,TRUE)") == ExcelError.NUM


def test_forecast_as_a_least_squares_line():
    for _ in range(20):
        n = RNG.randint(3, 15)
        xs = [RNG.uniform(-10, 10) for _ in range(n)]
        ys = [2 * x + RNG.gauss(0, 1) for x in xs]
        slope, intercept = np.polyfit(xs, ys, 1)
        x = RNG.uniform(-20, 20)
        text = "{" + ",".join(map(repr, ys)) + "},{" + ",".join(map(repr, xs)) + "}"
        assert ev(f"=FORECAST({x!r},{text})") == pytest.approx(slope * x + intercept,
                                                               rel=1e-10, abs=1e-10)
    assert ev("=FORECAST(1,{1,2},{3,3})") == ExcelError.DIV0      # no spread in x
