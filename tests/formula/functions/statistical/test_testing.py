"""formula/functions/stattests.py against scipy.stats: T.TEST (paired, equal and unequal
variances; one and two tails), F.TEST (two-tailed), CHISQ.TEST (the chi-squared
p-value of observed against expected, (r-1)(c-1) degrees of freedom), Z.TEST (one-tailed,
the sample's standard deviation when none is given); TRIMMEAN (the trimmed count rounded
down to even, Microsoft), PERMUTATIONA (n^k), PROB from its definition."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def row(xs) -> str:
    return "{" + ",".join(repr(float(x)) for x in xs) + "}"


def grid(m) -> str:
    return "{" + ";".join(",".join(repr(float(x)) for x in r) for r in m) + "}"


@pytest.mark.parametrize("seed", range(6))
def test_t_f_and_z_tests(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(5, 30))
    a = rng.normal(10, 2, n)
    b = a + rng.normal(0.8, 1.5, n)
    c = rng.normal(11, 3, int(rng.integers(5, 30)))
    for tails in (1, 2):
        f = 2 if tails == 1 else 1   # scipy's p is two-tailed
        assert ev(f"=T.TEST({row(a)},{row(b)},{tails},1)") == pytest.approx(
            stats.ttest_rel(a, b).pvalue / f, rel=1e-9)
        assert ev(f"=T.TEST({row(a)},{row(c)},{tails},2)") == pytest.approx(
            stats.ttest_ind(a, c).pvalue / f, rel=1e-9)
        assert ev(f"=T.TEST({row(a)},{row(c)},{tails},3)") == pytest.approx(
            stats.ttest_ind(a, c, equal_var=False).pvalue / f, rel=1e-8)
    va, vc = np.var(a, ddof=1), np.var(c, ddof=1)
    f_stat = va / vc
    p = 2 * min(stats.f.cdf(f_stat, n - 1, len(c) - 1), stats.f.sf(f_stat, n - 1, len(c) - 1))
    assert ev(f"=F.TEST({row(a)},{row(c)})") == pytest.approx(p, rel=1e-9)
    x = 10.3
    z = (a.mean() - x) / (a.std(ddof=1) / math.sqrt(n))
    assert ev(f"=Z.TEST({row(a)},{x})") == pytest.approx(stats.norm.sf(z), rel=1e-9)
    assert ev(f"=Z.TEST({row(a)},{x},2)") == pytest.approx(
        stats.norm.sf((a.mean() - x) / (2 / math.sqrt(n))), rel=1e-9)


def test_chisq_test():
    rng = np.random.default_rng(9)
    expected = rng.uniform(5, 40, (3, 4))
    observed = np.round(expected + rng.normal(0, 3, (3, 4)))
    chi2 = ((observed - expected) ** 2 / expected).sum()
    assert ev(f"=CHISQ.TEST({grid(observed)},{grid(expected)})") == pytest.approx(
        stats.chi2.sf(chi2, 2 * 3), rel=1e-9)
    # a single row: r - 1 = 0, so c - 1 degrees of freedom (Microsoft)
    o, e = observed[0], expected[0]
    assert ev(f"=CHISQ.TEST({row(o)},{row(e)})") == pytest.approx(
        stats.chi2.sf(((o - e) ** 2 / e).sum(), 3), rel=1e-9)


def test_trimmean_permutationa_prob():
    data = [4.0, 5, 6, 7, 2, 3, 4, 5, 1, 2, 3]               # Microsoft's TRIMMEAN example
    assert ev(f"=TRIMMEAN({row(data)},0.2)") == pytest.approx(3.777777778, abs=5e-10)
    for percent in (0.1, 0.25, 0.4, 0.5):
        trimmed = 2 * math.floor(len(data) * percent / 2)
        ordered = sorted(data)[trimmed // 2: len(data) - trimmed // 2]
        assert ev(f"=TRIMMEAN({row(data)},{percent})") == pytest.approx(np.mean(ordered))
    assert ev(f"=TRIMMEAN({row(data)},1)") == ExcelError.NUM
    assert ev("=PERMUTATIONA(3,2)") == 9 and ev("=PERMUTATIONA(2,2)") == 4
    xs, ps = [0.0, 1, 2, 3], [0.2, 0.3, 0.1, 0.4]             # Microsoft's PROB example
    assert ev(f"=PROB({row(xs)},{row(ps)},2)") == pytest.approx(0.1)
    assert ev(f"=PROB({row(xs)},{row(ps)},1,3)") == pytest.approx(0.8)
    assert ev(f"=PROB({row(xs)},{row([0.2, 0.3, 0.1, 0.3])},1,3)") == ExcelError.NUM
