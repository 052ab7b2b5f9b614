"""Week numbers: WEEKNUM (week starting Sunday, Monday, ... or ISO) and ISOWEEKNUM, on
Excel's calendar: before the 29 February 1900 that never was, Excel's weekdays are a day
early (serial 1, 1900-01-01, is a Sunday, as WEEKDAY says) and serial 0 is 1900-01-00."""

from __future__ import annotations

import datetime as dt

from workbook_gen.formula.functions.date.core import (_ymd_date, date_and_number, from_serial,
                                                     serial_arg, to_serial)
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.functions.serials import serial_1900
from workbook_gen.xlerror import ExcelError


@register("WEEKNUM", 1, 2)
def _weeknum(ctx, v, kind=1.0):
    if isinstance(v, bool):  # Analysis ToolPak: no booleans (formulas__test DATE & TIME!Y23)
        return ExcelError.VALUE
    got = date_and_number(v, kind)
    if isinstance(got, ExcelError):
        return got
    ymd, k = got
    if int(k) == 21:
        return _isoweeknum(ctx, v)
    first = {1: 6, 17: 6, 2: 0, 11: 0, 12: 1, 13: 2, 14: 3, 15: 4, 16: 5}.get(int(k))
    if first is None:
        return ExcelError.NUM
    if ymd[2] == 0:  # 1900-01-00: week 0 (formulas__test DATE & TIME!U23:W23)
        return 0.0
    d = _ymd_date(ymd)
    jan1 = dt.date(d.year, 1, 1)
    # 1900 starts on a Sunday in Excel's calendar (its 29 February shifts the weekdays)
    offset = ((6 if d.year == 1900 else jan1.weekday()) - first) % 7
    day = int(to_serial(d)) if d.year == 1900 else d.timetuple().tm_yday  # (with 29 Feb)
    return float((day - 1 + offset) // 7 + 1)


@register("ISOWEEKNUM", 1, 1)
def _isoweeknum(ctx, v):
    n = serial_arg(v)
    if isinstance(n, ExcelError):
        return n
    n = int(n)
    if serial_1900(n) >= 61:
        return float(_ymd_date(from_serial(n)).isocalendar()[1])
    # before the 29 February 1900 that never was, Excel's weekdays are a day early (serial
    # 1 is a Sunday, as WEEKDAY says): 1900-01-01 is in week 52 of 1899, 1900-01-08 in week
    # 1 (formulas__test DATE & TIME!S12:Y12; serial 0 is the Saturday before)
    weekday = (n + 5) % 7 + 1  # ISO: Monday 1 .. Sunday 7
    week = (n - weekday + 10) // 7  # (n is the day of 1900)
    return float(week) if week >= 1 else 52.0  # (1899 has 52 ISO weeks)
