"""formula/functions/depreciation.py against the definitions Microsoft gives: SYD's
sum-of-years digits, DB's fixed rate rounded to three places with a partial first and
last year, VDB's declining balance switching to straight line, CUMIPMT/CUMPRINC as sums
of IPMT/PPMT, ISPMT's even principal, FVSCHEDULE's product, MIRR's formula, DOLLARDE/
DOLLARFR, TBILLPRICE/TBILLYIELD; with Microsoft's worked examples."""

from __future__ import annotations

import math
import random

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse

RNG = random.Random(23)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def db_schedule(cost, salvage, life, month):
    rate = round(1 - (salvage / cost) ** (1 / life), 3)
    out, total = [], 0.0
    first = cost * rate * month / 12
    out.append(first)
    total = first
    for _ in range(2, life + 1):
        d = (cost - total) * rate
        out.append(d)
        total += d
    if month < 12:
        out.append((cost - total) * rate * (12 - month) / 12)
    return out


def vdb_schedule(cost, salvage, life, factor=2.0):
    """Declining balance per period, switching to straight line when that is larger."""
    out, book = [], cost
    for p in range(int(life)):
        ddb = min(book * factor / life, max(0.0, book - salvage))
        sl = max(0.0, (book - salvage) / (life - p))
        d = max(ddb, sl)
        out.append(d)
        book -= d
    return out


def test_syd_db_vdb_as_defined():
    for _ in range(30):
        cost, life = RNG.uniform(1e3, 1e6), RNG.randint(2, 12)
        salvage = cost * RNG.uniform(0.01, 0.3)
        years = sum(range(1, life + 1))
        for per in range(1, life + 1):
            assert ev(f"=SYD({cost!r},{salvage!r},{life},{per})") == pytest.approx(
                (cost - salvage) * (life - per + 1) / years, rel=1e-12)
        month = RNG.randint(1, 12)
        schedule = db_schedule(cost, salvage, life, month)
        for per, d in enumerate(schedule, 1):
            assert ev(f"=DB({cost!r},{salvage!r},{life},{per},{month})") == pytest.approx(
                d, rel=1e-9), (per, month)
        for per, d in enumerate(vdb_schedule(cost, salvage, life), 1):
            assert ev(f"=VDB({cost!r},{salvage!r},{life},{per - 1},{per})") == pytest.approx(
                d, rel=1e-9, abs=1e-9), per
        assert ev(f"=VDB({cost!r},{salvage!r},{life},0,{life})") == pytest.approx(
            cost - salvage, rel=1e-9)


def test_cumulative_payments_and_ispmt():
    for _ in range(10):
        rate, nper, pv = RNG.uniform(0.001, 0.02), RNG.randint(12, 120), RNG.uniform(1e4, 1e6)
        a = RNG.randint(1, nper)
        b = RNG.randint(a, nper)
        for kind in (0, 1):
            ipmt = sum(ev(f"=IPMT({rate!r},{p},{nper},{pv!r},0,{kind})") for p in range(a, b + 1))
            ppmt = sum(ev(f"=PPMT({rate!r},{p},{nper},{pv!r},0,{kind})") for p in range(a, b + 1))
            assert ev(f"=CUMIPMT({rate!r},{nper},{pv!r},{a},{b},{kind})") == pytest.approx(
                ipmt, rel=1e-9, abs=1e-9)
            assert ev(f"=CUMPRINC({rate!r},{nper},{pv!r},{a},{b},{kind})") == pytest.approx(
                ppmt, rel=1e-9)
        per = RNG.randint(0, nper)
        assert ev(f"=ISPMT({rate!r},{per},{nper},{pv!r})") == pytest.approx(
            -pv * rate * (1 - per / nper), rel=1e-12)


def test_products_rates_and_fractions():
    rates = [RNG.uniform(-0.1, 0.2) for _ in range(6)]
    assert ev("=FVSCHEDULE(100,{" + ",".join(map(repr, rates)) + "})") == pytest.approx(
        100 * math.prod(1 + r for r in rates), rel=1e-14)
    flows = [-120000, 39000, 30000, 21000, 37000, 46000]
    f, r = 0.1, 0.12
    n = len(flows) - 1
    pos = sum(v * (1 + r) ** (n - i) for i, v in enumerate(flows) if v > 0)
    neg = sum(v / (1 + f) ** i for i, v in enumerate(flows) if v < 0)
    assert ev("=MIRR({" + ",".join(map(str, flows)) + "},0.1,0.12)") == pytest.approx(
        (pos / -neg) ** (1 / n) - 1, rel=1e-12)
    for fraction in (2, 8, 16, 32):
        for _ in range(10):
            whole, part = RNG.randint(0, 99), RNG.randint(0, fraction - 1)
            digits = len(str(fraction))
            text = f"{whole}.{part:0{digits}d}"
            assert ev(f"=DOLLARDE({text},{fraction})") == pytest.approx(whole + part / fraction)
            assert ev(f"=DOLLARFR({whole + part / fraction!r},{fraction})") == \
                pytest.approx(float(text))


def test_microsofts_examples():
    assert ev("=DB(1000000,100000,6,1,7)") == pytest.approx(186083.33, abs=0.005)
    assert ev("=SYD(30000,7500,10,1)") == pytest.approx(4090.91, abs=0.005)
    assert ev("=CUMIPMT(0.09/12,30*12,125000,13,24,0)") == pytest.approx(-11135.23, abs=0.005)
    assert ev("=CUMPRINC(0.09/12,30*12,125000,13,24,0)") == pytest.approx(-934.1071, abs=5e-5)
    assert ev("=MIRR({-120000,39000,30000,21000,37000,46000},0.1,0.12)") == pytest.approx(
        0.126094, abs=5e-7)
    assert ev("=TBILLPRICE(39538,39600,0.09)") == pytest.approx(98.45, abs=0.005)
    # TBILLYIELD: 360 * (100 - price) / (price * days), days = 62
    assert ev("=TBILLYIELD(39538,39600,98.45)") == pytest.approx(
        360 * (100 - 98.45) / (98.45 * 62), rel=1e-12)
