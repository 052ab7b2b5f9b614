"""Probability distributions (Excel 2010 names and their legacy aliases): beta, binomial,
chi-squared, exponential, F, gamma, hypergeometric, lognormal, negative binomial,
Poisson, Student's t, Weibull; their inverses; CONFIDENCE.*, GAMMA, GAMMALN, ERF-free
helpers. Special functions are evaluated by mpmath at 30 digits and rounded to a float;
inverses are found by bisection on the distribution function (Excel's own inverses are
iterative searches too). Argument checks follow Microsoft's pages: a probability outside
its range, a non-positive shape or scale, a degrees-of-freedom below 1 is #NUM!; integer
arguments (trials, degrees of freedom) are truncated."""

from __future__ import annotations

import math

import mpmath

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.numeric import DPS, args_of, flag, numeric, with_flag
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError

def invert(cdf, p, lo, hi):
    """x with cdf(x) = p: bracketed (hi doubled until cdf(hi) >= p), then the
    Anderson-Bjorck root finder (a few evaluations), bisection if it strays."""
    p = mpmath.mpf(p)
    for _ in range(2000):
        if cdf(hi) >= p:
            break
        lo, hi = hi, hi * 2
    else:
        return ExcelError.NUM
    lo, hi = mpmath.mpf(lo), mpmath.mpf(hi)
    try:
        x = mpmath.findroot(lambda t: cdf(t) - p, (lo, hi), solver="anderson",
                            tol=mpmath.mpf(10) ** -(2 * DPS - 20), maxsteps=200)
        if lo <= x <= hi and abs(cdf(x) - p) <= abs(p) * mpmath.mpf(10) ** -18 + mpmath.mpf(10) ** -28:
            return x
    except (ValueError, ZeroDivisionError):
        pass
    for _ in range(200):
        mid = (lo + hi) / 2
        if cdf(mid) < p:
            lo = mid
        else:
            hi = mid
        if hi - lo <= abs(hi) * mpmath.mpf(10) ** -20:
            break
    return (lo + hi) / 2


def _prob(p, closed_low=False):
    """A probability argument in (0, 1] (or [0, 1] with ``closed_low``)."""
    return (0 <= p <= 1) if closed_low else (0 < p <= 1)


# -- beta --------------------------------------------------------------------------------

def _beta_cdf(x, a, b):
    return mpmath.betainc(a, b, 0, x, regularized=True)


def beta_dist(x, a, b, cum, lo=0.0, hi=1.0):
    if a <= 0 or b <= 0 or x < lo or x > hi or lo == hi:
        return ExcelError.NUM
    z = mpmath.mpf(x - lo) / (hi - lo)
    if cum:
        return _beta_cdf(z, a, b)
    if (z == 0 and a < 1) or (z == 1 and b < 1):
        return ExcelError.NUM
    return z ** (a - 1) * (1 - z) ** (b - 1) / mpmath.beta(a, b) / (hi - lo)


def beta_inv(p, a, b, lo=0.0, hi=1.0):
    if a <= 0 or b <= 0 or not _prob(p) or lo >= hi:
        return ExcelError.NUM
    z = invert(lambda t: _beta_cdf(min(t, 1), a, b), p, 0, 1)
    return z if isinstance(z, ExcelError) else lo + z * (hi - lo)


@register("BETA.DIST", 4, 6)
def _beta_dist(ctx, x, a, b, cumulative, lo=0.0, hi=1.0):
    cum = flag(cumulative)
    if isinstance(cum, ExcelError):
        return cum
    return numeric(lambda x, a, b, lo, hi: beta_dist(x, a, b, cum, lo, hi))(
        ctx, x, a, b, 0.0 if lo is None else lo, 1.0 if hi is None else hi)


register("BETADIST", 3, 5)(numeric(lambda x, a, b, lo=0.0, hi=1.0: beta_dist(
    x, a, b, True, lo, hi)))
@register("BETA.INV", 3, 5, aliases=("BETAINV",))
def _beta_inv(ctx, p, a, b, lo=0.0, hi=1.0):
    """Excel's probability is in (0, 1): Mac Excel 16 caches #NUM! for BETA.INV(TRUE,3,2)
    (formulas__test.xlsx STATISTICAL!AO9, where TRUE is 1 for BETA.DIST). LibreOffice 7.4
    (measured) takes [0, 1]: BETAINV(0,3,2) is 0, BETAINV(1,3,2) is 1."""
    xs = args_of(p, a, b, 0.0 if lo is None else lo, 1.0 if hi is None else hi)
    if isinstance(xs, ExcelError):
        return xs
    x, a, b, lo, hi = xs
    if ctx.dialect == "libreoffice" and x in (0.0, 1.0) and a > 0 and b > 0 and lo < hi:
        return c.result(lo if x == 0.0 else hi)
    if x >= 1:
        return ExcelError.NUM
    return numeric(beta_inv)(ctx, *xs)


# -- gamma and chi-squared ---------------------------------------------------------------

def gamma_cdf(x, a, b):
    return mpmath.gammainc(a, 0, mpmath.mpf(x) / b, regularized=True)


def gamma_dist(x, a, b, cum):
    if x < 0 or a <= 0 or b <= 0:
        return ExcelError.NUM
    if cum:
        return gamma_cdf(x, a, b)
    if x == 0 and a < 1:
        return ExcelError.NUM
    return mpmath.mpf(x) ** (a - 1) * mpmath.exp(-mpmath.mpf(x) / b) / (mpmath.gamma(a) * mpmath.mpf(b) ** a)


def gamma_inv(p, a, b):
    if not 0 <= p < 1 or a <= 0 or b <= 0:
        return ExcelError.NUM
    if p == 0:
        return 0
    return invert(lambda t: gamma_cdf(t, a, b), p, 0, max(a * b, 1))


def _df(d):
    d = math.trunc(d)
    return d if 1 <= d <= 10 ** 10 else None


def chisq_dist(x, df, cum):
    df = _df(df)
    if df is None or x < 0:
        return ExcelError.NUM
    return gamma_dist(x, df / 2, 2, cum)


def chisq_rt(x, df):
    df = _df(df)
    if df is None or x < 0:
        return ExcelError.NUM
    return mpmath.gammainc(df / 2, mpmath.mpf(x) / 2, mpmath.inf, regularized=True)


def chisq_inv(p, df):
    df = _df(df)
    if df is None or not 0 <= p <= 1:
        return ExcelError.NUM
    return gamma_inv(p, df / 2, 2) if p < 1 else ExcelError.NUM


def chisq_inv_rt(p, df):
    df = _df(df)
    if df is None or not 0 < p <= 1:
        return ExcelError.NUM
    if p == 1:
        return 0
    return invert(lambda t: -chisq_rt(t, df), -mpmath.mpf(p), 0, max(df, 1))


def gammaln(x):
    return ExcelError.NUM if x <= 0 else mpmath.loggamma(x)


def gamma_fn(x):
    if x <= 0 and x == int(x):
        return ExcelError.NUM
    return mpmath.gamma(x)


register("GAMMA.DIST", 4, 4, aliases=("GAMMADIST",))(with_flag(gamma_dist))
register("GAMMA.INV", 3, 3, aliases=("GAMMAINV",))(numeric(gamma_inv))
register("GAMMALN", 1, 1, aliases=("GAMMALN.PRECISE",))(numeric(gammaln))
register("GAMMA", 1, 1)(numeric(gamma_fn))
register("CHISQ.DIST", 3, 3)(with_flag(chisq_dist))
register("CHISQ.DIST.RT", 2, 2, aliases=("CHIDIST",))(numeric(chisq_rt))
register("CHISQ.INV", 2, 2)(numeric(chisq_inv))
register("CHISQ.INV.RT", 2, 2, aliases=("CHIINV",))(numeric(chisq_inv_rt))


# -- F and t ------------------------------------------------------------------------------

def f_cdf(x, d1, d2):
    x = mpmath.mpf(x)
    return mpmath.betainc(d1 / 2, d2 / 2, 0, d1 * x / (d1 * x + d2), regularized=True)


def f_dist(x, d1, d2, cum):
    d1, d2 = _df(d1), _df(d2)
    if d1 is None or d2 is None or x < 0:
        return ExcelError.NUM
    if cum:
        return f_cdf(x, d1, d2)
    x = mpmath.mpf(x)
    return (mpmath.sqrt((d1 * x) ** d1 * d2 ** d2 / (d1 * x + d2) ** (d1 + d2))
            / (x * mpmath.beta(mpmath.mpf(d1) / 2, mpmath.mpf(d2) / 2)))


def f_rt(x, d1, d2):
    d1, d2 = _df(d1), _df(d2)
    if d1 is None or d2 is None or x < 0:
        return ExcelError.NUM
    x = mpmath.mpf(x)
    return mpmath.betainc(d2 / 2, d1 / 2, 0, d2 / (d1 * x + d2), regularized=True)


def f_inv(p, d1, d2):
    d1, d2 = _df(d1), _df(d2)
    if d1 is None or d2 is None or not 0 <= p < 1:
        return ExcelError.NUM
    return 0 if p == 0 else invert(lambda t: f_cdf(t, d1, d2), p, 0, 1)


def f_inv_rt(p, d1, d2):
    d1, d2 = _df(d1), _df(d2)
    if d1 is None or d2 is None or not 0 < p <= 1:
        return ExcelError.NUM
    return 0 if p == 1 else invert(lambda t: -f_rt(t, d1, d2), -mpmath.mpf(p), 0, 1)


def t_cdf(x, df):
    return 1 - t_upper(x, df)


def t_upper(x, df):
    """P(T > x), from the tail's own incomplete beta function: a far tail (T.DIST.2T(60,60)
    is 2.8e-55, formulas__test.xlsx STATISTICAL!X103) is not lost in 1 - cdf."""
    x = mpmath.mpf(x)
    tail = mpmath.betainc(mpmath.mpf(df) / 2, mpmath.mpf(0.5), 0, df / (df + x * x),
                          regularized=True) / 2
    return tail if x > 0 else 1 - tail


def t_dist(x, df, cum):
    if df == 0 and not cum:  # the density's 1/sqrt(df): Excel's #DIV/0! (STATISTICAL!R102)
        return ExcelError.DIV0
    if df < 1:
        return ExcelError.NUM
    if cum:
        return t_cdf(x, df)
    x = mpmath.mpf(x)
    return ((1 + x * x / df) ** (-(mpmath.mpf(df) + 1) / 2)
            / (mpmath.sqrt(df) * mpmath.beta(mpmath.mpf(0.5), mpmath.mpf(df) / 2)))


def t_rt(x, df):
    return ExcelError.NUM if df < 1 else t_upper(x, df)


def t_2t(x, df):
    return ExcelError.NUM if df < 1 or x < 0 else 2 * t_upper(x, df)


def tdist(x, df, tails):
    df, tails = math.trunc(df), math.trunc(tails)
    if df < 1 or x < 0 or tails not in (1, 2):
        return ExcelError.NUM
    return tails * t_upper(x, df)


def t_inv(p, df):
    if df < 1 or not 0 < p < 1:
        return ExcelError.NUM
    if p == 0.5:
        return 0
    x = invert(lambda t: t_cdf(t, df), max(p, 1 - p), 0, 1)
    return x if p > 0.5 else -x


def t_inv_2t(p, df):
    df = math.trunc(df)
    if df < 1 or not 0 < p <= 1:
        return ExcelError.NUM
    return 0 if p == 1 else t_inv(1 - mpmath.mpf(p) / 2, df)


register("F.DIST", 4, 4)(with_flag(f_dist))
register("F.DIST.RT", 3, 3, aliases=("FDIST",))(numeric(f_rt))
register("F.INV", 3, 3)(numeric(f_inv))
register("F.INV.RT", 3, 3, aliases=("FINV",))(numeric(f_inv_rt))
register("T.DIST", 3, 3)(with_flag(t_dist))
register("T.DIST.RT", 2, 2)(numeric(t_rt))
register("T.DIST.2T", 2, 2)(numeric(t_2t))
register("TDIST", 3, 3)(numeric(tdist))
register("T.INV", 2, 2)(numeric(t_inv))
register("T.INV.2T", 2, 2, aliases=("TINV",))(numeric(t_inv_2t))


# -- continuous one-liners ----------------------------------------------------------------

def expon(x, lam, cum):
    if x < 0 or lam <= 0:
        return ExcelError.NUM
    return -mpmath.expm1(-lam * mpmath.mpf(x)) if cum else lam * mpmath.exp(-lam * mpmath.mpf(x))


def weibull(x, a, b, cum):
    if x < 0 or a <= 0 or b <= 0:
        return ExcelError.NUM
    z = (mpmath.mpf(x) / b) ** a
    if cum:
        return -mpmath.expm1(-z)
    return a / mpmath.mpf(b) ** a * mpmath.mpf(x) ** (a - 1) * mpmath.exp(-z)


def _ncdf(z):
    return mpmath.ncdf(z)


def lognorm(x, m, s, cum):
    if x <= 0 or s <= 0:
        return ExcelError.NUM
    z = (mpmath.log(x) - m) / s
    if cum:
        return _ncdf(z)
    return mpmath.npdf(z) / (s * x)


def lognorm_inv(p, m, s):
    if not 0 < p < 1 or s <= 0:
        return ExcelError.NUM
    z = invert(_ncdf, p, -40, 40)
    return mpmath.exp(m + s * z)


def confidence_norm(alpha, sd, n):
    n = math.trunc(n)
    if not 0 < alpha < 1 or sd <= 0 or n < 1:
        return ExcelError.NUM
    z = invert(_ncdf, 1 - mpmath.mpf(alpha) / 2, -40, 40)
    return z * sd / mpmath.sqrt(n)


def confidence_t(alpha, sd, n):
    n = math.trunc(n)
    if not 0 < alpha < 1 or sd <= 0 or n < 1:
        return ExcelError.NUM
    if n == 1:
        return ExcelError.DIV0
    return t_inv_2t(alpha, n - 1) * sd / mpmath.sqrt(n)


register("EXPON.DIST", 3, 3, aliases=("EXPONDIST",))(with_flag(expon))
register("WEIBULL.DIST", 4, 4, aliases=("WEIBULL",))(with_flag(weibull))
register("LOGNORM.DIST", 4, 4)(with_flag(lognorm))
register("LOGNORMDIST", 3, 3)(numeric(lambda x, m, s: lognorm(x, m, s, True)))
register("LOGNORM.INV", 3, 3, aliases=("LOGINV",))(numeric(lognorm_inv))
register("CONFIDENCE.NORM", 3, 3, aliases=("CONFIDENCE",))(numeric(confidence_norm))
register("CONFIDENCE.T", 3, 3)(numeric(confidence_t))
register("FISHER", 1, 1)(numeric(
    lambda x: ExcelError.NUM if abs(x) >= 1 else mpmath.atanh(x)))
register("FISHERINV", 1, 1)(numeric(mpmath.tanh))
register("PHI", 1, 1)(numeric(mpmath.npdf))
register("GAUSS", 1, 1)(numeric(lambda z: _ncdf(z) - mpmath.mpf(0.5)))
