"""numfmt/dates.py (through TEXT): date and time codes against Python's datetime on
random serials (rounded to the second, as Excel displays them): yyyy yy mmmm mmm mm m
dddd ddd dd d, hh h mm (minutes after h, before s) ss, AM/PM, elapsed [h] [m] [s]."""

from __future__ import annotations

import datetime as dt
import random

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse

EPOCH = dt.datetime(1899, 12, 30)
RNG = random.Random(23)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def moments(n=200):
    for _ in range(n):
        seconds = RNG.randint(367 * 86400, 80000 * 86400)
        yield seconds / 86400, EPOCH + dt.timedelta(seconds=seconds)


def test_date_codes():
    for serial, when in moments():
        s = repr(serial)
        assert ev(f'=TEXT({s},"yyyy-mm-dd")') == when.strftime("%Y-%m-%d")
        assert ev(f'=TEXT({s},"yy/m/d")') == f"{when:%y}/{when.month}/{when.day}"
        assert ev(f'=TEXT({s},"mmmm mmm dddd ddd")') == when.strftime("%B %b %A %a")
        assert ev(f'=TEXT({s},"dd.mm.yyyy")') == when.strftime("%d.%m.%Y")


def test_time_codes():
    for serial, when in moments():
        s = repr(serial)
        assert ev(f'=TEXT({s},"hh:mm:ss")') == when.strftime("%H:%M:%S")
        assert ev(f'=TEXT({s},"h:mm AM/PM")') == \
            f"{when.hour % 12 or 12}:{when:%M} {'AM' if when.hour < 12 else 'PM'}"
        assert ev(f'=TEXT({s},"mm")') == when.strftime("%m")       # month, without h or s
        assert ev(f'=TEXT({s},"h mm")') == f"{when.hour} {when:%M}"   # minutes after h


@pytest.mark.parametrize("seconds", [0, 59, 3600, 86399, 90061, 400000, 3 * 86400 + 1])
def test_elapsed_time(seconds):
    s = repr(seconds / 86400)
    h, rest = divmod(seconds, 3600)
    m, sec = divmod(rest, 60)
    assert ev(f'=TEXT({s},"[h]:mm:ss")') == f"{h}:{m:02d}:{sec:02d}"
    assert ev(f'=TEXT({s},"[m]:ss")') == f"{seconds // 60}:{sec:02d}"
    assert ev(f'=TEXT({s},"[s]")') == str(seconds)
