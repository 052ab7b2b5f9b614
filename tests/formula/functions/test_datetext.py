"""formula/functions/datetext.py: dates and times read from text, as DATEVALUE, TIMEVALUE
and VALUE read them in an en-US Excel, against Python's datetime writing the same moment
in each form (ISO, m/d/yyyy, d-mmm-yyyy, mmmm d, yyyy, d mmmm yyyy, 24-hour and AM/PM
times); a day that does not exist is #VALUE!."""

from __future__ import annotations

import datetime as dt
import random

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

EPOCH = dt.date(1899, 12, 30)
RNG = random.Random(23)
FORMS = ["{d:%Y-%m-%d}", "{d.month}/{d.day}/{d.year}", "{d.day}-{d:%b}-{d.year}",
         "{d:%B} {d.day}, {d.year}", "{d.day} {d:%B} {d.year}", "{d:%Y}/{d:%m}/{d:%d}"]


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


@pytest.mark.parametrize("form", FORMS)
def test_datevalue_of_each_form(form):
    for _ in range(60):
        d = EPOCH + dt.timedelta(RNG.randint(367, 2958465 - 1))
        text = form.format(d=d)
        assert ev(f'=DATEVALUE("{text}")') == (d - EPOCH).days, text
        assert ev(f'=VALUE("{text}")') == (d - EPOCH).days, text


def test_timevalue_24_hour_and_am_pm():
    for _ in range(200):
        t = dt.time(RNG.randint(0, 23), RNG.randint(0, 59), RNG.randint(0, 59))
        seconds = t.hour * 3600 + t.minute * 60 + t.second
        for text in (f"{t:%H:%M:%S}", f"{t:%I:%M:%S %p}"):
            assert ev(f'=TIMEVALUE("{text}")') == pytest.approx(seconds / 86400, abs=1e-15)
    d = dt.date(2024, 3, 5)
    assert ev('=VALUE("2024-03-05 18:00")') == pytest.approx((d - EPOCH).days + 0.75)


def test_days_that_do_not_exist():
    assert ev('=DATEVALUE("Feb 29, 2023")') == ExcelError.VALUE
    assert ev('=DATEVALUE("13/13/2024")') == ExcelError.VALUE
    assert ev('=DATEVALUE("Feb 29, 2024")') == (dt.date(2024, 2, 29) - EPOCH).days
