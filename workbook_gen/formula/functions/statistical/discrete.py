"""Discrete distributions: binomial (BINOM.DIST, BINOM.INV, BINOM.DIST.RANGE and the
legacy BINOMDIST, CRITBINOM), negative binomial, hypergeometric, Poisson. Sums of exact
probability terms in mpmath at 30 digits, rounded to a float; counts truncated."""

from __future__ import annotations

import math

import mpmath

from workbook_gen.formula.functions.numeric import numeric, with_flag
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError


# -- binomial family ---------------------------------------------------------------------

def binom_pmf(k, n, p):
    return mpmath.binomial(n, k) * mpmath.mpf(p) ** k * (1 - mpmath.mpf(p)) ** (n - k)


def binom_dist(k, n, p, cum):
    k, n = math.trunc(k), math.trunc(n)
    if k < 0 or k > n or not 0 <= p <= 1:
        return ExcelError.NUM
    if cum:
        return mpmath.fsum(binom_pmf(i, n, p) for i in range(k + 1))
    return binom_pmf(k, n, p)


def binom_inv(n, p, alpha):
    n = math.trunc(n)
    if n < 0 or not 0 <= p <= 1 or not 0 <= alpha <= 1:
        return ExcelError.NUM
    total = mpmath.mpf(0)
    for k in range(n + 1):
        total += binom_pmf(k, n, p)
        if total >= alpha:
            return k
    return n


def binom_range(n, p, s, s2=None):
    n, s = math.trunc(n), math.trunc(s)
    s2 = s if s2 is None else math.trunc(s2)
    if not 0 <= p <= 1 or not 0 <= s <= n or not s <= s2 <= n:
        return ExcelError.NUM
    return mpmath.fsum(binom_pmf(i, n, p) for i in range(s, s2 + 1))


def negbinom(f, s, p, cum):
    f, s = math.trunc(f), math.trunc(s)
    if f < 0 or s < 1 or not 0 < p < 1:
        return ExcelError.NUM
    pmf = lambda i: mpmath.binomial(i + s - 1, s - 1) * mpmath.mpf(p) ** s * (1 - mpmath.mpf(p)) ** i
    return mpmath.fsum(pmf(i) for i in range(f + 1)) if cum else pmf(f)


def hypgeom(k, n, big_k, big_n, cum, dialect="excel"):
    """Counts truncated; zeros allowed (HYPGEOM.DIST(0,0,0,0,FALSE) = 1). Outside the
    support the cumulative form is 0 below and 1 above it (Mac Excel 16, formulas__test.xlsx
    STATISTICAL!AG54, AI54; LibreOffice 7.4 the same), the mass #NUM! (Microsoft's rule;
    LibreOffice: 0). LibreOffice refuses k > n with #VALUE! (measured)."""
    k, n, big_k, big_n = (math.trunc(v) for v in (k, n, big_k, big_n))
    if k < 0 or n < 0 or big_k < 0 or big_n < 0 or n > big_n or big_k > big_n:
        return ExcelError.NUM
    if dialect == "libreoffice" and k > n:
        return ExcelError.VALUE
    lo, hi = max(0, n - big_n + big_k), min(n, big_k)
    if not lo <= k <= hi:
        if cum:
            return 0 if k < lo else 1
        return 0 if dialect == "libreoffice" else ExcelError.NUM
    pmf = lambda i: (mpmath.binomial(big_k, i) * mpmath.binomial(big_n - big_k, n - i)
                     / mpmath.binomial(big_n, n))
    return mpmath.fsum(pmf(i) for i in range(lo, k + 1)) if cum else pmf(k)


def poisson(x, mean, cum):
    x = math.trunc(x)
    if x < 0 or mean < 0:
        return ExcelError.NUM
    if cum:
        return mpmath.gammainc(x + 1, mean, mpmath.inf, regularized=True)
    return mpmath.mpf(mean) ** x * mpmath.exp(-mean) / mpmath.factorial(x)


register("BINOM.DIST", 4, 4, aliases=("BINOMDIST",))(with_flag(binom_dist))
register("BINOM.INV", 3, 3, aliases=("CRITBINOM",))(numeric(binom_inv))
register("BINOM.DIST.RANGE", 3, 4)(numeric(binom_range))
register("NEGBINOM.DIST", 4, 4)(with_flag(negbinom))
register("NEGBINOMDIST", 3, 3)(numeric(lambda f, s, p: negbinom(f, s, p, False)))
register("HYPGEOM.DIST", 5, 5)(with_flag(hypgeom, dialect=True))
register("HYPGEOMDIST", 4, 4)(numeric(lambda k, n, bk, bn: hypgeom(k, n, bk, bn, False)))
register("POISSON.DIST", 3, 3, aliases=("POISSON",))(with_flag(poisson))
