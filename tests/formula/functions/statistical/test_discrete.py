"""The discrete distributions (formula/functions/discrete.py: BINOM.*, NEGBINOM.DIST,
HYPGEOM.DIST, POISSON.DIST and their legacy names) against scipy.stats, with Microsoft's
worked examples and Excel's domain errors."""

from __future__ import annotations

import random

import pytest
from scipy import stats

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def cases(seed: str, n: int = 40):
    rng = random.Random(seed)
    for _ in range(n):
        trials = rng.randint(1, 60)
        yield rng.randint(0, trials), trials, round(rng.uniform(0.01, 0.99), 3)


def test_binom_dist_and_range():
    for k, n, p in cases("binom"):
        assert ev(f"=BINOM.DIST({k},{n},{p},FALSE)") == pytest.approx(
            stats.binom.pmf(k, n, p), rel=1e-11, abs=1e-300)
        assert ev(f"=BINOM.DIST({k},{n},{p},TRUE)") == pytest.approx(
            stats.binom.cdf(k, n, p), rel=1e-11)
        lo = k // 2
        assert ev(f"=BINOM.DIST.RANGE({n},{p},{lo},{k})") == pytest.approx(
            stats.binom.cdf(k, n, p) - stats.binom.cdf(lo - 1, n, p), rel=1e-10, abs=1e-15)


def test_binom_inv_is_the_smallest_k_reaching_alpha():
    for k, n, p in cases("binom.inv"):
        alpha = round(random.Random(k * n).uniform(0.01, 0.99), 4)
        assert ev(f"=BINOM.INV({n},{p},{alpha})") == stats.binom.ppf(alpha, n, p)


def test_negbinom_hypgeom_poisson():
    for k, n, p in cases("others"):
        failures, successes = k, max(1, n - k)
        assert ev(f"=NEGBINOM.DIST({failures},{successes},{p},FALSE)") == pytest.approx(
            stats.nbinom.pmf(failures, successes, p), rel=1e-11, abs=1e-300)
        assert ev(f"=NEGBINOM.DIST({failures},{successes},{p},TRUE)") == pytest.approx(
            stats.nbinom.cdf(failures, successes, p), rel=1e-11)
        population, draws = n + 20, n
        good = random.Random(n).randint(k, k + 20)
        assert ev(f"=HYPGEOM.DIST({k},{draws},{good},{population},FALSE)") == pytest.approx(
            stats.hypergeom.pmf(k, population, good, draws), rel=1e-11, abs=1e-300)
        assert ev(f"=HYPGEOM.DIST({k},{draws},{good},{population},TRUE)") == pytest.approx(
            stats.hypergeom.cdf(k, population, good, draws), rel=1e-11)
        mean = p * 20
        assert ev(f"=POISSON.DIST({k},{mean},FALSE)") == pytest.approx(
            stats.poisson.pmf(k, mean), rel=1e-11, abs=1e-300)
        assert ev(f"=POISSON.DIST({k},{mean},TRUE)") == pytest.approx(
            stats.poisson.cdf(k, mean), rel=1e-11)


def test_microsofts_examples_legacy_names_and_errors():
    assert ev("=BINOM.DIST(6,10,0.5,FALSE)") == pytest.approx(0.2050781, abs=5e-8)
    assert ev("=BINOM.INV(6,0.5,0.75)") == 4
    assert ev("=NEGBINOM.DIST(10,5,0.25,TRUE)") == pytest.approx(0.3135141, abs=5e-8)
    assert ev("=HYPGEOM.DIST(1,4,8,20,TRUE)") == pytest.approx(0.4654, abs=5e-5)
    assert ev("=POISSON.DIST(2,5,TRUE)") == pytest.approx(0.124652, abs=5e-7)
    assert ev("=NEGBINOMDIST(10,5,0.25)") == ev("=NEGBINOM.DIST(10,5,0.25,FALSE)")
    assert ev("=HYPGEOMDIST(1,4,8,20)") == ev("=HYPGEOM.DIST(1,4,8,20,FALSE)")
    assert ev("=BINOM.DIST(6.9,10,0.5,FALSE)") == ev("=BINOM.DIST(6,10,0.5,FALSE)")  # truncated
    assert ev("=BINOM.DIST(11,10,0.5,FALSE)") == ExcelError.NUM    # k > trials
    assert ev("=BINOM.DIST(1,10,1.5,FALSE)") == ExcelError.NUM     # p > 1
    assert ev("=POISSON.DIST(-1,5,TRUE)") == ExcelError.NUM
