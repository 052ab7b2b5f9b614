"""WEEKNUM and ISOWEEKNUM (formula/functions/weeks.py) against Python's calendar:
ISOWEEKNUM is ``date.isocalendar().week``; WEEKNUM's system 1 counts weeks that begin on
the return type's weekday from the week holding 1 January, and return type 21 is ISO 8601
(Microsoft's WEEKNUM page). Serial n is 1899-12-30 + n days from 1901 on (in 1900 Excel
keeps its fictitious 29 February, and its weekdays before March are not the calendar's)."""

from __future__ import annotations

import datetime as dt
import random

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

EPOCH = dt.date(1899, 12, 30)
SERIALS = random.Random(6).sample(range(367, 80000), 200) + [
    serial for year in (2004, 2005, 2010, 2015, 2020, 2021, 2027)  # years around 53-week ones
    for serial in ((dt.date(year, 1, d) - EPOCH).days for d in (1, 2, 3, 4, 7))]
# return type -> the weekday (Monday 0) a week begins on
BEGINS = {1: 6, 2: 0, 11: 0, 12: 1, 13: 2, 14: 3, 15: 4, 16: 5, 17: 6}


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def weeknum(d: dt.date, begins: int) -> int:
    """Week 1 holds 1 January; each later week begins on weekday ``begins``."""
    jan1 = dt.date(d.year, 1, 1)
    first_start = jan1 - dt.timedelta(days=(jan1.weekday() - begins) % 7)
    return (d - first_start).days // 7 + 1


def test_isoweeknum_is_iso_8601():
    for serial in SERIALS:
        d = EPOCH + dt.timedelta(days=serial)
        assert ev(f"=ISOWEEKNUM({serial})") == d.isocalendar().week, d
        assert ev(f"=WEEKNUM({serial},21)") == d.isocalendar().week, d


@pytest.mark.parametrize("kind", sorted(BEGINS))
def test_weeknum_counts_from_the_week_of_1_january(kind):
    for serial in SERIALS:
        d = EPOCH + dt.timedelta(days=serial)
        assert ev(f"=WEEKNUM({serial},{kind})") == weeknum(d, BEGINS[kind]), (d, kind)


def test_microsofts_examples_and_bad_return_types():
    # WEEKNUM("2012-03-09") = 10 (weeks from Sunday), 11 with return type 2
    assert ev("=WEEKNUM(DATE(2012,3,9))") == 10
    assert ev("=WEEKNUM(DATE(2012,3,9),2)") == 11
    assert ev("=ISOWEEKNUM(DATE(2012,3,9))") == 10
    assert ev("=WEEKNUM(45000,3)") == ExcelError.NUM
    assert ev("=ISOWEEKNUM(-1)") == ExcelError.NUM
