"""NETWORKDAYS(.INTL) and WORKDAY(.INTL) (formula/functions/workdays.py) against numpy's
business-day calendar (numpy.busday_count / busday_offset), on random spans, weekend
masks and holidays. Serial n is 1899-12-30 + n days (the 1900 system past 1900-03-01)."""

from __future__ import annotations

import datetime as dt
import random

import numpy as np
import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

EPOCH = dt.date(1899, 12, 30)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def day(serial: int) -> np.datetime64:
    return np.datetime64(EPOCH + dt.timedelta(days=serial))


def serial(d: np.datetime64) -> int:
    return int((d - np.datetime64(EPOCH)).astype(int))


CASES = random.Random(23).sample(range(40000, 47000), 40)
MASKS = ["0000011", "1000001", "0000001", "1111100", "0101010"]  # Monday first, 1 = weekend


@pytest.mark.parametrize("start", CASES[:20])
def test_networkdays_counts_as_numpy(start):
    rng = random.Random(start)
    end = start + rng.randint(-400, 400)
    holidays = sorted({start + rng.randint(-300, 300) for _ in range(6)})
    mask = rng.choice(MASKS)
    week = [c == "0" for c in mask]
    hol = ",".join(map(str, holidays))
    lo, hi = sorted((start, end))
    # numpy counts [lo, hi); Excel counts both ends and is negative when end < start
    count = int(np.busday_count(day(lo), day(hi) + 1, weekmask=week,
                                holidays=[day(h) for h in holidays]))
    want = count if end >= start else -count
    assert ev(f'=NETWORKDAYS.INTL({start},{end},"{mask}",{{{hol}}})') == want
    if mask == "0000011":
        assert ev(f"=NETWORKDAYS({start},{end},{{{hol}}})") == want


@pytest.mark.parametrize("start", CASES[20:])
def test_workday_offsets_as_numpy(start):
    rng = random.Random(start)
    days = rng.randint(-300, 300)
    holidays = sorted({start + rng.randint(-300, 300) for _ in range(6)})
    mask = rng.choice(MASKS)
    week = [c == "0" for c in mask]
    hol = ",".join(map(str, holidays))
    # Excel starts from the start date whatever it is: roll it to the side it moves to
    calendar = np.busdaycalendar(weekmask=week, holidays=[day(h) for h in holidays])
    roll = "forward" if days < 0 else "backward"   # the start itself never counts
    if days == 0:
        want = start
    else:
        first = np.busday_offset(day(start), 0, roll=roll, busdaycal=calendar)
        want = serial(np.busday_offset(first, days, roll="forward", busdaycal=calendar))
    assert ev(f'=WORKDAY.INTL({start},{days},"{mask}",{{{hol}}})') == want


def test_weekend_numbers_and_bad_masks():
    # weekend code 1 = Saturday/Sunday, 2 = Sunday/Monday, 11 = Sunday only (Microsoft)
    assert ev("=NETWORKDAYS.INTL(45000,45030,1)") == ev('=NETWORKDAYS.INTL(45000,45030,"0000011")')
    assert ev("=NETWORKDAYS.INTL(45000,45030,2)") == ev('=NETWORKDAYS.INTL(45000,45030,"1000001")')
    assert ev("=NETWORKDAYS.INTL(45000,45030,11)") == ev('=NETWORKDAYS.INTL(45000,45030,"0000001")')
    # Microsoft: "Using 1111111 will always return 0"; its two worked examples
    assert ev('=NETWORKDAYS.INTL(45000,45030,"1111111")') == 0
    assert ev("=NETWORKDAYS.INTL(DATE(2006,1,1),DATE(2006,1,31))") == 22
    assert ev("=NETWORKDAYS.INTL(DATE(2006,2,28),DATE(2006,1,31))") == -21
    assert ev('=NETWORKDAYS.INTL(45000,45030,"000001")') == ExcelError.VALUE
    assert ev("=NETWORKDAYS.INTL(45000,45030,8)") == ExcelError.NUM
