"""formula/functions/finance.py: the time-value-of-money functions satisfy Excel's
documented equation pv*(1+r)^n + pmt*(1+r*type)*((1+r)^n-1)/r + fv = 0 (each function
solved for its unknown, on random loans), NPV/XNPV are their discounted sums, IRR/XIRR
zero them, IPMT+PPMT make PMT and follow the amortisation schedule, and Microsoft's worked
examples give Microsoft's results."""

from __future__ import annotations

import datetime as dt
import random

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse

RNG = random.Random(23)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def balance(rate, nper, pmt, pv, fv, kind):
    if rate == 0:
        return pv + pmt * nper + fv
    g = (1 + rate) ** nper
    return pv * g + pmt * (1 + rate * kind) * (g - 1) / rate + fv


def loans(n=40):
    for _ in range(n):
        yield (RNG.choice([0.0, RNG.uniform(0.0005, 0.02)]), RNG.randint(2, 360),
               RNG.uniform(1e3, 5e5), RNG.choice([0.0, RNG.uniform(-1e4, 1e4)]),
               RNG.randint(0, 1))


def test_each_tvm_function_solves_the_equation():
    for rate, nper, pv, fv, kind in loans():
        pmt = ev(f"=PMT({rate!r},{nper},{pv!r},{fv!r},{kind})")
        scale = abs(pv) + abs(fv) + abs(pmt) * nper
        assert abs(balance(rate, nper, pmt, pv, fv, kind)) <= 1e-9 * scale
        assert ev(f"=PV({rate!r},{nper},{pmt!r},{fv!r},{kind})") == pytest.approx(pv, rel=1e-9)
        assert ev(f"=FV({rate!r},{nper},{pmt!r},{pv!r},{kind})") == pytest.approx(fv, rel=1e-9,
                                                                              abs=1e-6)
        assert ev(f"=NPER({rate!r},{pmt!r},{pv!r},{fv!r},{kind})") == pytest.approx(nper,
                                                                                rel=1e-9)
        if rate:
            assert ev(f"=RATE({nper},{pmt!r},{pv!r},{fv!r},{kind})") == pytest.approx(
                rate, rel=1e-6)


def test_ipmt_and_ppmt_follow_the_schedule():
    for rate, nper, pv, _, _ in list(loans(10)):
        rate = rate or 0.01
        nper = min(nper, 60)
        pmt = ev(f"=PMT({rate!r},{nper},{pv!r})")
        owed = pv
        for per in range(1, nper + 1):
            interest = -owed * rate
            ipmt = ev(f"=IPMT({rate!r},{per},{nper},{pv!r})")
            ppmt = ev(f"=PPMT({rate!r},{per},{nper},{pv!r})")
            assert ipmt == pytest.approx(interest, rel=1e-9, abs=1e-9 * pv)
            assert ipmt + ppmt == pytest.approx(pmt, rel=1e-12)
            owed += ppmt
        assert abs(owed) <= 1e-8 * pv


def test_npv_irr_xnpv_xirr():
    for _ in range(20):
        flows = [-RNG.uniform(1e3, 1e5)] + [RNG.uniform(0, 4e4) for _ in range(RNG.randint(2, 8))]
        rate = RNG.uniform(0.01, 0.2)
        values = "{" + ",".join(repr(f) for f in flows) + "}"
        # NPV discounts the first value one period too (Microsoft)
        assert ev(f"=NPV({rate!r},{values})") == pytest.approx(
            sum(f / (1 + rate) ** (i + 1) for i, f in enumerate(flows)), rel=1e-12)
        irr = ev(f"=IRR({values})")
        if isinstance(irr, float):
            assert abs(sum(f / (1 + irr) ** i for i, f in enumerate(flows))) <= 1e-7 * sum(
                map(abs, flows))
        start = dt.date(2008, 1, 1)
        days = sorted(RNG.sample(range(1, 2000), len(flows) - 1))
        dates = [start] + [start + dt.timedelta(d) for d in days]
        serials = "{" + ",".join(str((d - dt.date(1899, 12, 30)).days) for d in dates) + "}"
        assert ev(f"=XNPV({rate!r},{values},{serials})") == pytest.approx(
            sum(f / (1 + rate) ** ((d - start).days / 365) for f, d in zip(flows, dates)),
            rel=1e-12)
        xirr = ev(f"=XIRR({values},{serials})")
        if isinstance(xirr, float):
            assert abs(sum(f / (1 + xirr) ** ((d - start).days / 365)
                           for f, d in zip(flows, dates))) <= 1e-6 * sum(map(abs, flows))


@pytest.mark.parametrize("formula, result, digits", [
    ("=PMT(0.08/12,10,10000)", -1037.03, 2),                       # Microsoft PMT
    ("=PV(0.08/12,12*20,500,,0)", -59777.15, 2),                   # PV
    ("=FV(0.06/12,10,-200,-500,1)", 2581.40, 2),                   # FV
    ("=NPER(0.12/12,-100,-1000,10000,1)", 59.6738657, 7),          # NPER
    ("=RATE(4*12,-200,8000)", 0.0077, 4),                          # RATE, monthly
    ("=NPV(0.1,-10000,3000,4200,6800)", 1188.44, 2),               # NPV
    ("=IRR({-70000,12000,15000,18000,21000,26000})", 0.0866, 4),   # IRR: 8.66%
    # XIRR: Microsoft shows 0.373362535; Excel stops iterating within 0.000001 % (2e-9 here)
    ("=XIRR({-10000,2750,4250,3250,2750},{39448,39508,39751,39859,39904},0.1)", 0.373362535, 8),
    ("=SLN(30000,7500,10)", 2250.0, 9),
    ("=DDB(2400,300,10*365,1)", 1.32, 2),
    ("=RRI(96,10000,11000)", 0.0009933, 7),
])
def test_microsofts_examples(formula, result, digits):
    assert ev(formula) == pytest.approx(result, abs=0.5 * 10.0 ** -digits)
