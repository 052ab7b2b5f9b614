"""formula/functions/date.py against Python's datetime and dateutil's relativedelta on
random dates from 1901 to 2199 (serial n is 1899-12-30 + n days there): DATE with
overflowing months and days, YEAR/MONTH/DAY/WEEKDAY (its return types), EDATE/EOMONTH,
DAYS, DATEDIF's units, TIME and its parts, YEARFRAC's actual bases; Excel's fictitious
1900-02-29 (serial 60) and its errors."""

from __future__ import annotations

import calendar
import datetime as dt
import random

import pytest
from dateutil.relativedelta import relativedelta

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

EPOCH = dt.date(1899, 12, 30)
RNG = random.Random(23)
DATES = [EPOCH + dt.timedelta(RNG.randint(367, 109500)) for _ in range(150)] + [
    dt.date(2000, 2, 29), dt.date(2024, 1, 31), dt.date(2023, 12, 31), dt.date(1904, 2, 28)]


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def serial(d: dt.date) -> int:
    return (d - EPOCH).days


def test_date_and_its_parts():
    for d in DATES:
        s = serial(d)
        assert ev(f"=DATE({d.year},{d.month},{d.day})") == s
        assert (ev(f"=YEAR({s})"), ev(f"=MONTH({s})"), ev(f"=DAY({s})")) == \
            (d.year, d.month, d.day)
        assert ev(f"=WEEKDAY({s})") == (d.isoweekday() % 7) + 1          # Sunday 1
        assert ev(f"=WEEKDAY({s},2)") == d.isoweekday()                  # Monday 1
        assert ev(f"=WEEKDAY({s},3)") == d.weekday()                     # Monday 0
        assert ev(f"=WEEKDAY({s},16)") == (d.weekday() + 2) % 7 + 1      # Saturday 1
        # months and days beyond their range roll over, as datetime arithmetic does
        m, k = RNG.randint(-30, 30), RNG.randint(-400, 400)
        want = dt.date(d.year, 1, 1) + relativedelta(months=d.month - 1 + m) + \
            dt.timedelta(days=d.day - 1 + k)
        assert ev(f"=DATE({d.year},{d.month + m},{d.day + k})") == serial(want)


def test_edate_eomonth_days():
    for d in DATES:
        s, m = serial(d), RNG.randint(-40, 40)
        assert ev(f"=EDATE({s},{m})") == serial(d + relativedelta(months=m))
        end = d + relativedelta(months=m)
        end = end.replace(day=calendar.monthrange(end.year, end.month)[1])
        assert ev(f"=EOMONTH({s},{m})") == serial(end)
        other = DATES[RNG.randrange(len(DATES))]
        assert ev(f"=DAYS({serial(other)},{s})") == (other - d).days


def test_datedif_units():
    for d in DATES:
        e = d + dt.timedelta(RNG.randint(0, 3000))
        r = relativedelta(e, d)
        a, b = serial(d), serial(e)
        assert ev(f'=DATEDIF({a},{b},"D")') == (e - d).days
        assert ev(f'=DATEDIF({a},{b},"M")') == r.years * 12 + r.months
        assert ev(f'=DATEDIF({a},{b},"Y")') == r.years
        assert ev(f'=DATEDIF({a},{b},"YM")') == r.months
    assert ev('=DATEDIF(45000,44000,"D")') == ExcelError.NUM          # start after end


def test_time_and_its_parts():
    for _ in range(100):
        h, m, s = RNG.randint(0, 23), RNG.randint(0, 59), RNG.randint(0, 59)
        t = ev(f"=TIME({h},{m},{s})")
        assert t == pytest.approx((h * 3600 + m * 60 + s) / 86400, abs=1e-15)
        assert (ev(f"=HOUR({t!r})"), ev(f"=MINUTE({t!r})"), ev(f"=SECOND({t!r})")) == (h, m, s)
    assert ev("=TIME(25,0,0)") == pytest.approx(1 / 24)                # rolls over the day


def test_yearfrac_actual_bases():
    for d in DATES[:60]:
        e = d + dt.timedelta(RNG.randint(1, 2000))
        a, b = serial(d), serial(e)
        assert ev(f"=YEARFRAC({a},{b},2)") == pytest.approx((e - d).days / 360, rel=1e-14)
        assert ev(f"=YEARFRAC({a},{b},3)") == pytest.approx((e - d).days / 365, rel=1e-14)
        assert ev(f"=YEARFRAC({b},{a},3)") == ev(f"=YEARFRAC({a},{b},3)")   # order-free


def test_excels_1900_and_errors():
    assert ev("=DATE(1900,2,29)") == 60 and ev("=DAY(60)") == 29 and ev("=MONTH(60)") == 2
    assert ev("=DATE(1900,3,1)") == 61
    assert ev("=DATE(1899,12,31)") == serial(dt.date(3799, 12, 31))   # year < 1900: + 1900
    assert ev("=DATE(10000,1,1)") == ExcelError.NUM
    assert ev("=YEAR(-1)") == ExcelError.NUM
    assert ev('=DATEDIF(1,2,"Q")') == ExcelError.NUM
