"""NETWORKDAYS.INTL and WORKDAY.INTL: working days with a chosen weekend.

The weekend is a code (1 = Saturday and Sunday ... 7 = Friday and Saturday, 11 = Sunday
only ... 17 = Saturday only) or seven characters of 0/1 from Monday to Sunday, 1 meaning
a day off (another code is #NUM!; other text #VALUE!; "1111111" is #VALUE! for
WORKDAY.INTL, which could never end, and counts no day in NETWORKDAYS.INTL). Serial numbers count weekdays
continuously (serial 1 is a Sunday, as in Excel; :mod:`..serials`)."""

from __future__ import annotations

import math

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.date.core import _holidays, serial_arg
from workbook_gen.formula.functions.serials import max_serial, weekday
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError

# Monday = 0 ... Sunday = 6
_CODES = {1: (5, 6), 2: (6, 0), 3: (0, 1), 4: (1, 2), 5: (2, 3), 6: (3, 4), 7: (4, 5),
          11: (6,), 12: (0,), 13: (1,), 14: (2,), 15: (3,), 16: (4,), 17: (5,)}


def weekend_days(v, all_allowed: bool = False) -> frozenset[int] | ExcelError:
    if v is None:
        return frozenset((5, 6))
    if isinstance(v, str):
        if len(v) != 7 or set(v) - {"0", "1"} or (v == "1111111" and not all_allowed):
            return ExcelError.VALUE
        return frozenset(i for i, ch in enumerate(v) if ch == "1")
    x = c.to_number(v)
    if isinstance(x, ExcelError):
        return x
    days = _CODES.get(math.trunc(x))
    return ExcelError.NUM if days is None else frozenset(days)


def _args(weekend, holidays, all_allowed=False):
    off = weekend_days(weekend, all_allowed)
    hol = _holidays(holidays)
    for x in (off, hol):
        if isinstance(x, ExcelError):
            return x
    return off, hol


@register("NETWORKDAYS.INTL", 2, 4, ("scalar", "scalar", "scalar", "range"), omitted=True)
def _networkdays_intl(ctx, start, end, weekend=None, holidays=None):
    a, b = serial_arg(start), serial_arg(end)
    got = _args(weekend, holidays, True)  # every day off: 0 working days
    for x in (a, b, got):
        if isinstance(x, ExcelError):
            return x
    off, hol = got
    a, b = math.floor(a), math.floor(b)
    lo, hi = sorted((a, b))
    n = sum(1 for d in range(lo, hi + 1) if weekday(d) not in off and d not in hol)
    return float(n if a <= b else -n)


@register("WORKDAY.INTL", 2, 4, ("scalar", "scalar", "scalar", "range"), omitted=True)
def _workday_intl(ctx, start, days, weekend=None, holidays=None):
    s, k = serial_arg(start), c.to_number(days)
    got = _args(weekend, holidays)
    for x in (s, k, got):
        if isinstance(x, ExcelError):
            return x
    off, hol = got
    d, k = math.floor(s), math.trunc(k)
    step = 1 if k > 0 else -1
    while k:
        d += step
        if d < 1 or d > max_serial():
            return ExcelError.NUM
        if weekday(d) not in off and d not in hol:
            k -= step
    return float(d)
