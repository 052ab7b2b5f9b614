"""formula/functions/financial/oddbonds.py: ODDLPRICE, ODDLYIELD, ODDFPRICE and ODDFYIELD
against the formulas of Microsoft's pages (support.microsoft.com, "ODDLPRICE function",
"ODDLYIELD function", "ODDFPRICE function", "ODDFYIELD function"), evaluated here in
mpmath at 50 digits with day counts written out independently (actual days from datetime,
30/360 US and European by their rules), over random bonds; their published examples; and
their documented refusals ("#NUM! unless maturity > settlement > last_interest", "...
maturity >= first_coupon > settlement > issue", a negative rate or yield, a price or
redemption <= 0)."""

from __future__ import annotations

import calendar
import datetime as dt
import random

import mpmath
import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

RNG = random.Random(2008)
EPOCH = dt.date(1899, 12, 30)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def sd(d: dt.date) -> int:
    return (d - EPOCH).days


def month_end(d: dt.date) -> bool:
    return d.day == calendar.monthrange(d.year, d.month)[1]


def shift(d: dt.date, months: int, eom: bool) -> dt.date:
    y, m = divmod(d.year * 12 + d.month - 1 + months, 12)
    last = calendar.monthrange(y, m + 1)[1]
    return dt.date(y, m + 1, last if eom else min(d.day, last))


def days(a: dt.date, b: dt.date, basis: int) -> int:
    if basis in (1, 2, 3):
        return (b - a).days
    d1, d2 = a.day, b.day
    if basis == 4:
        d1, d2 = min(d1, 30), min(d2, 30)
    else:  # 30/360 US (SIA)
        feb = lambda d: d.month == 2 and month_end(d)  # noqa: E731
        if feb(a) and feb(b):
            d2 = 30
        if feb(a):
            d1 = 30
        if d2 == 31 and d1 >= 30:
            d2 = 30
        d1 = min(d1, 30)
    return 360 * (b.year - a.year) + 30 * (b.month - a.month) + d2 - d1


def odd_last_sums(s, m, last, f, b):
    """sum DC_i/NL_i, sum A_i/NL_i, sum DSC_i/NL_i over the quasi-coupon periods counted
    forward from the last interest date (NL_i: the period's days in the basis)."""
    step, eom = 12 // f, month_end(last)
    dcs = acs = dscs = mpmath.mpf(0)
    k = 0
    while True:
        q0, q1 = shift(last, k * step, eom), shift(last, (k + 1) * step, eom)
        if q0 >= m:
            return dcs, acs, dscs
        nl = mpmath.mpf(days(q0, q1, b))
        end = min(q1, m)
        dcs += days(q0, end, b) / nl
        if s > q0:
            acs += days(q0, min(s, end), b) / nl
        if s < end:
            dscs += days(max(s, q0), end, b) / nl
        k += 1


def oddl_price(s, m, last, r, y, red, f, b):
    dcs, acs, dscs = odd_last_sums(s, m, last, f, b)
    c = 100 * mpmath.mpf(r) / f
    return (red + dcs * c) / (1 + dscs * mpmath.mpf(y) / f) - acs * c


def oddl_yield(s, m, last, r, p, red, f, b):
    dcs, acs, dscs = odd_last_sums(s, m, last, f, b)
    c = 100 * mpmath.mpf(r) / f
    paid = p + acs * c
    return (red + dcs * c - paid) / paid * f / dscs


def oddf_price_short(s, m, issue, first, r, y, red, f, b):
    """The page's short-first-coupon formula: E the coupon period's days (actual in basis
    1, 360/f or 365/f otherwise), DFC issue to first coupon, A issue to settlement, DSC
    settlement to first coupon, N the coupons from the first to maturity."""
    step, eom = 12 // f, month_end(first)
    prev = shift(first, -step, eom)
    e = mpmath.mpf((first - prev).days) if b == 1 else mpmath.mpf(365 if b == 3 else 360) / f
    n = 1
    while shift(first, n * step, eom) <= m:
        n += 1
    dfc, a = days(issue, first, b), days(issue, s, b)
    dsc = (first - s).days if b in (1, 2, 3) else e - days(prev, s, b)
    v = 1 + mpmath.mpf(y) / f
    c = 100 * mpmath.mpf(r) / f
    x = dsc / e
    price = red / v ** (n - 1 + x) + c * (dfc / e) / v ** x
    price += sum(c / v ** (k - 1 + x) for k in range(2, n + 1))
    return price - c * a / e


def random_odd_last():
    f = RNG.choice((1, 2, 4))
    last = dt.date(2000, 1, 1) + dt.timedelta(days=RNG.randrange(9000))
    if RNG.random() < 0.25:
        last = dt.date(last.year, last.month, calendar.monthrange(last.year, last.month)[1])
    m = last + dt.timedelta(days=RNG.randrange(20, 3 * 365))
    s = last + dt.timedelta(days=RNG.randrange(1, (m - last).days))
    return s, m, last, f


def test_oddlprice_and_oddlyield_by_microsofts_formulas():
    with mpmath.workdps(50):
        for _ in range(150):
            s, m, last, f = random_odd_last()
            b = RNG.randrange(5)
            r, y, red = RNG.uniform(0, 0.1), RNG.uniform(0, 0.12), RNG.choice((100, 105))
            args = f"{sd(s)},{sd(m)},{sd(last)},{r!r}"
            want = float(oddl_price(s, m, last, r, y, red, f, b))
            got = ev(f"=ODDLPRICE({args},{y!r},{red},{f},{b})")
            assert got == pytest.approx(want, rel=1e-13), (s, m, last, f, b)
            p = RNG.uniform(80, 110)
            want = float(oddl_yield(s, m, last, r, p, red, f, b))
            got = ev(f"=ODDLYIELD({args},{p!r},{red},{f},{b})")
            assert got == pytest.approx(want, rel=1e-12, abs=1e-15), (s, m, last, f, b)


def test_oddfprice_short_first_period_by_microsofts_formula():
    with mpmath.workdps(50):
        for _ in range(150):
            f, b = RNG.choice((1, 2, 4)), RNG.randrange(5)
            step = 12 // f
            first = dt.date(2001, 1, 1) + dt.timedelta(days=RNG.randrange(8000))
            eom = month_end(first)
            prev = shift(first, -step, eom)
            issue = prev + dt.timedelta(days=RNG.randrange(0, (first - prev).days - 1))
            s = issue + dt.timedelta(days=RNG.randrange(1, (first - issue).days))
            m = shift(first, step * RNG.randrange(0, 40), eom)
            r, y, red = RNG.uniform(0, 0.1), RNG.uniform(0, 0.12), 100
            want = float(oddf_price_short(s, m, issue, first, r, y, red, f, b))
            got = ev(f"=ODDFPRICE({sd(s)},{sd(m)},{sd(issue)},{sd(first)},{r!r},{y!r},"
                     f"{red},{f},{b})")
            assert got == pytest.approx(want, rel=1e-12), (s, m, issue, first, f, b)
            # ODDFYIELD finds the yield back from that (independent) price
            got_y = ev(f"=ODDFYIELD({sd(s)},{sd(m)},{sd(issue)},{sd(first)},{r!r},{want!r},"
                       f"{red},{f},{b})")
            assert got_y == pytest.approx(y, rel=1e-9, abs=1e-11), (s, m, issue, first, f, b)


@pytest.mark.parametrize("formula, published", [
    ("ODDLPRICE(DATE(2008,2,7),DATE(2008,6,15),DATE(2007,10,15),0.0375,0.0405,100,2,0)",
     99.87828601),
    ("ODDLYIELD(DATE(2008,4,20),DATE(2008,6,15),DATE(2007,12,24),0.0375,99.875,100,2,0)",
     0.045192),
    ("ODDFPRICE(DATE(2008,11,11),DATE(2021,3,1),DATE(2008,10,15),DATE(2009,3,1),0.0785,"
     "0.0625,100,2,1)", 113.597717),
    ("ODDFYIELD(DATE(2008,11,11),DATE(2021,3,1),DATE(2008,10,15),DATE(2009,3,1),0.0575,"
     "84.5,100,2,0)", 0.0772455),
])
def test_published_examples(formula, published):
    digits = len(repr(published).split(".")[1])
    assert ev("=" + formula) == pytest.approx(published, abs=0.6 * 10 ** -digits)


def test_the_long_first_period_counts_whole_quasi_periods_as_one():
    """A first period of two quasi-coupon periods (issue before the previous quasi date):
    the page's long form, DC of the whole quasi period is 1 (its NL), with settlement in
    the second one; checked in basis 1 against the page's sums written out."""
    s, m = dt.date(2020, 6, 10), dt.date(2022, 3, 1)
    issue, first = dt.date(2019, 11, 15), dt.date(2020, 9, 1)   # quasi: 2019-09-01, 2020-03-01
    r, y, f = 0.06, 0.05, 2
    q = [dt.date(2019, 9, 1), dt.date(2020, 3, 1), first]
    nl = [(q[1] - q[0]).days, (q[2] - q[1]).days]
    dc_sum = mpmath.mpf((q[1] - issue).days) / nl[0] + 1
    a_sum = mpmath.mpf((q[1] - issue).days) / nl[0] + mpmath.mpf((s - q[1]).days) / nl[1]
    dsc = mpmath.mpf((first - s).days) / nl[1]
    n = 3                      # coupons after the first: 2021-03, 2021-09, 2022-03
    v, c = 1 + mpmath.mpf(y) / f, 100 * mpmath.mpf(r) / f
    want = 100 / v ** (n + dsc) + c * dc_sum / v ** dsc
    want += sum(c / v ** (j + dsc) for j in range(1, n + 1)) - c * a_sum
    got = ev(f"=ODDFPRICE({sd(s)},{sd(m)},{sd(issue)},{sd(first)},{r},{y},100,{f},1)")
    assert got == pytest.approx(float(want), rel=1e-13)


@pytest.mark.parametrize("formula, expected", [
    # maturity > settlement > last_interest
    ("ODDLPRICE(39500,39600,39500,0.04,0.04,100,2,0)", ExcelError.NUM),
    ("ODDLPRICE(39500,39500,39400,0.04,0.04,100,2,0)", ExcelError.NUM),
    ("ODDLPRICE(39500,39600,39400,-0.01,0.04,100,2,0)", ExcelError.NUM),
    ("ODDLPRICE(39500,39600,39400,0.04,-0.01,100,2,0)", ExcelError.NUM),
    ("ODDLPRICE(39500,39600,39400,0.04,0.04,0,2,0)", ExcelError.NUM),
    ("ODDLPRICE(39500,39600,39400,0.04,0.04,100,3,0)", ExcelError.NUM),
    ("ODDLPRICE(39500,39600,39400,0.04,0.04,100,2,5)", ExcelError.NUM),
    ('ODDLPRICE(39500,39600,"x",0.04,0.04,100,2,0)', ExcelError.VALUE),
    ("ODDLYIELD(39500,39600,39400,0.04,0,100,2,0)", ExcelError.NUM),      # price <= 0
    # maturity >= first_coupon > settlement > issue
    ("ODDFPRICE(39500,40000,39400,39500,0.04,0.04,100,2,0)", ExcelError.NUM),
    ("ODDFPRICE(39500,40000,39500,39600,0.04,0.04,100,2,0)", ExcelError.NUM),
    ("ODDFPRICE(39500,40000,39400,40100,0.04,0.04,100,2,0)", ExcelError.NUM),
    ("ODDFPRICE(39500,40000,39400,39600,0.04,-0.04,100,2,0)", ExcelError.NUM),
    ("ODDFYIELD(39500,40000,39400,39600,0.04,-1,100,2,0)", ExcelError.NUM),
    ('ODDFYIELD(39500,40000,39400,"x",0.04,90,100,2,0)', ExcelError.VALUE),
])
def test_refusals(formula, expected):
    assert ev("=" + formula) == expected
