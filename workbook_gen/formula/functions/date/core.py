"""Dates and times as Excel's serial numbers: DATE, YEAR, MONTH, DAY, TIME, HOUR, MINUTE,
SECOND, TODAY/NOW (volatile), EDATE, EOMONTH, YEARFRAC, WEEKDAY (WEEKNUM and ISOWEEKNUM in
:mod:`.weeks`), DAYS, DAYS360, DATEDIF, DATEVALUE, TIMEVALUE, NETWORKDAYS, WORKDAY.

Serial numbers and calendar dates convert in :mod:`..serials` (the 1900 system, with its 29
February 1900 that never was, or the 1904 system of a workbook saved with ``date1904``).
"""

from __future__ import annotations

import calendar
import datetime as dt
import math

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.datetext import parse_date_text
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.functions.serials import (  # noqa: F401  (re-exported)
    from_serial, max_serial, moment_serial, null_date_plus, to_serial, weekday,
)
from workbook_gen.xlerror import ExcelError


def _date(x) -> tuple[int, int, int] | ExcelError:
    n = serial_arg(x)
    return n if isinstance(n, ExcelError) else from_serial(n)


def serial_arg(v) -> float | ExcelError:
    """A date argument: a number, or text that reads as a date or a number."""
    if isinstance(v, str):
        x = c.text_to_number(v)
        if isinstance(x, ExcelError):
            x = parse_date_text(v)
        return x
    x = c.to_number(v)
    if isinstance(x, ExcelError):
        return x
    return ExcelError.NUM if x < 0 else x


def _ints(*vs):
    out = [c.to_number(v) for v in vs]
    bad = next((x for x in out if isinstance(x, ExcelError)), None)
    return bad if bad is not None else [int(math.floor(x)) if x >= 0 else int(x) for x in out]


def make_date(y: int, m: int, d: int) -> float | ExcelError:
    """DATE(y, m, d): years 0-1899 add 1900; months and days overflow into the next."""
    if 0 <= y < 1900:
        y += 1900
    if not 1900 <= y <= 9999:
        return ExcelError.NUM
    y, m = y + (m - 1) // 12, (m - 1) % 12 + 1
    base = dt.date(y, m, 1)
    serial = to_serial(base) + d - 1  # day arithmetic in serial space: DATE(1900,3,0) is 60
    return float(serial) if 0 <= serial <= max_serial() else ExcelError.NUM


@register("DATE", 3, 3)
def _date_fn(ctx, y, m, d):
    xs = _ints(y, m, d)
    return xs if isinstance(xs, ExcelError) else make_date(*xs)


def _part(i):
    def fn(ctx, v):
        ymd = _date(v)
        return ymd if isinstance(ymd, ExcelError) else float(ymd[i])
    return fn


register("YEAR", 1, 1)(_part(0))
register("MONTH", 1, 1)(_part(1))
register("DAY", 1, 1)(_part(2))


def _seconds(v):
    x = serial_arg(v)
    if isinstance(x, ExcelError):
        return x
    return int(round((x - math.floor(x)) * 86400.0)) % 86400  # to the nearest second


register("HOUR", 1, 1)(lambda ctx, v: c.result(_map(_seconds(v), lambda s: s // 3600)))
register("MINUTE", 1, 1)(lambda ctx, v: _map(_seconds(v), lambda s: s // 60 % 60))
register("SECOND", 1, 1)(lambda ctx, v: _map(_seconds(v), lambda s: s % 60))


def _map(x, fn):
    return x if isinstance(x, ExcelError) else float(fn(x))


@register("TIME", 3, 3)
def _time(ctx, h, m, s):
    xs = _ints(h, m, s)
    if isinstance(xs, ExcelError):
        return xs
    total = xs[0] * 3600 + xs[1] * 60 + xs[2]
    return ExcelError.NUM if total < 0 else (total % 86400) / 86400.0


@register("TODAY", 0, 0, volatile=True)
def _today(ctx):
    return to_serial(dt.date.today())


@register("NOW", 0, 0, volatile=True)
def _now(ctx):
    return moment_serial(dt.datetime.now())


def _ymd_date(ymd) -> dt.date:
    y, m, d = ymd
    if d == 0 or (m == 2 and d == 29 and y == 1900):  # the serials 0 and 60
        return dt.date(1900, 1, 1) if d == 0 else dt.date(1900, 2, 28)
    return dt.date(y, m, d)


def date_and_number(v, n):
    """(year, month, day) of a date argument and a number argument, or the first error."""
    ymd = _date(v)
    k = c.to_number(n)
    for x in (ymd, k):
        if isinstance(x, ExcelError):
            return x
    return ymd, k


def _add_months(v, months, end_of_month: bool):
    if isinstance(v, bool) or isinstance(months, bool):  # Analysis ToolPak: no booleans
        return ExcelError.VALUE
    got = date_and_number(v, months)
    if isinstance(got, ExcelError):
        return got
    (y, m, d), k = got
    total = y * 12 + (m - 1) + int(k)
    y, m = divmod(total, 12)
    m += 1
    if not 1900 <= y <= 9999:
        return ExcelError.NUM
    last = calendar.monthrange(y, m)[1]
    if d == 0 and not end_of_month:  # 1900-01-00 keeps its day 0: the day before the 1st
        return to_serial(dt.date(y, m, 1)) - 1  # (formulas__test DATE & TIME!V9:W9)
    serial = to_serial(dt.date(y, m, last if end_of_month else min(max(d, 1), last)))
    return serial if serial >= 0 else ExcelError.NUM  # (before 1904 in the 1904 system)


register("EDATE", 2, 2)(lambda ctx, v, k: _add_months(v, k, False))
register("EOMONTH", 2, 2)(lambda ctx, v, k: _add_months(v, k, True))


def _two_dates(a, b):
    x, y = serial_arg(a), serial_arg(b)
    for v in (x, y):
        if isinstance(v, ExcelError):
            return v
        if isinstance(from_serial(v), ExcelError):  # before 1900 or after 9999
            return ExcelError.NUM
    return math.floor(x), math.floor(y)


def _is_leap(y: int) -> bool:
    return calendar.isleap(y)


def days_30_360(start: tuple[int, int, int], start_feb_end: bool,
                end: tuple[int, int, int], end_feb_end: bool, european: bool) -> int:
    """Days from ``start`` to ``end`` (year, month, day) on a calendar of 30-day months:
    the US (NASD) rule of basis 0, where ``*_feb_end`` says a date is February's last
    day, or the European rule of basis 4."""
    (y1, m1, t1), (y2, m2, t2) = start, end
    if european:
        t1, t2 = min(t1, 30), min(t2, 30)
    else:
        if start_feb_end and end_feb_end:
            t2 = 30
        if start_feb_end:
            t1 = 30
        if t2 == 31 and t1 >= 30:
            t2 = 30
        if t1 == 31:
            t1 = 30
    return (y2 - y1) * 360 + (m2 - m1) * 30 + (t2 - t1)


def _end_of_feb(y: int, m: int, d: int) -> bool:
    return m == 2 and d == (29 if y == 1900 else calendar.monthrange(y, 2)[1])


def yearfrac(s: float, e: float, basis: int) -> float | ExcelError:
    if s > e:
        s, e = e, s
    for x in (s, e):
        if isinstance(from_serial(x), ExcelError):
            return ExcelError.NUM
    if basis in (0, 4):  # on Excel's own calendar: serial 0 is 1900-01-00, 60 is 02-29
        (y1, m1, t1), (y2, m2, t2) = from_serial(s), from_serial(e)
        return days_30_360((y1, m1, t1), _end_of_feb(y1, m1, t1),
                           (y2, m2, t2), _end_of_feb(y2, m2, t2), basis == 4) / 360.0
    d1, d2 = _ymd_date(from_serial(s)), _ymd_date(from_serial(e))
    days = e - s
    if basis == 2:
        return days / 360.0
    if basis == 3:
        return days / 365.0
    if d1.year == d2.year:
        return days / (366.0 if _is_leap(d1.year) else 365.0)
    if d2 <= dt.date(d1.year + 1, d1.month, min(d1.day, calendar.monthrange(d1.year + 1,
                                                                            d1.month)[1])):
        feb29 = ((_is_leap(d1.year) and d1 <= dt.date(d1.year, 2, 29))
                 or (_is_leap(d2.year) and d2 >= dt.date(d2.year, 2, 29)))
        return days / (366.0 if feb29 else 365.0)
    years = range(d1.year, d2.year + 1)
    average = sum(366 if _is_leap(y) else 365 for y in years) / len(years)
    return days / average


@register("YEARFRAC", 2, 3)
def _yearfrac(ctx, a, b, basis=0.0):
    # the basis is checked first, and booleans are #VALUE! (pycel's yearfrac.xlsx)
    k = ExcelError.VALUE if isinstance(basis, bool) else c.to_number(basis)
    if isinstance(k, ExcelError):
        return k
    if int(k) not in (0, 1, 2, 3, 4):
        return ExcelError.NUM
    if isinstance(a, bool) or isinstance(b, bool):
        return ExcelError.VALUE
    se = _two_dates(a, b)
    if isinstance(se, ExcelError):
        return se
    k = int(k)
    return c.result(yearfrac(se[0], se[1], k))


@register("DAYS", 2, 2)
def _days(ctx, end, start):
    se = _two_dates(start, end)
    return se if isinstance(se, ExcelError) else float(se[1] - se[0])


def _days360_ymd(x: float, lo: bool):
    """DAYS360's (year, month, day) of a serial: the time of day rounded to the second
    first (Excel: 46000.999999 is 46001), serial 0 the day 0 of January 1900 and 60 the
    29 February 1900 (the Excel-saved ironcalc DAYS_DAYS360.xlsx). LibreOffice (``lo``)
    truncates, and its serial n is 1899-12-30 plus n days."""
    if not lo:
        return from_serial(math.floor(round(x * 86400.0) / 86400.0))
    if isinstance(from_serial(x), ExcelError):
        return ExcelError.NUM
    d = null_date_plus(math.floor(x))
    return d.year, d.month, d.day


@register("DAYS360", 2, 3)
def _days360(ctx, a, b, european=False):
    x, y = serial_arg(a), serial_arg(b)
    eu = c.to_bool(european)
    for v in (x, y, eu):
        if isinstance(v, ExcelError):
            return v
    lo = ctx is not None and ctx.dialect == "libreoffice"
    d1, d2 = _days360_ymd(x, lo), _days360_ymd(y, lo)
    for d in (d1, d2):
        if isinstance(d, ExcelError):
            return d
    (y1, m1, t1), (y2, m2, t2) = d1, d2
    if eu:
        t1, t2 = min(t1, 30), min(t2, 30)
    else:
        feb_end = m1 == 2 and t1 == calendar.monthrange(y1, 2)[1]
        if _end_of_feb(y1, m1, t1) if not lo else feb_end:
            t1 = 30
        if t1 == 31:
            t1 = 30
        if t2 == 31 and t1 >= 30:
            t2 = 30
    return float((y2 - y1) * 360 + (m2 - m1) * 30 + t2 - t1)


@register("DATEDIF", 3, 3)
def _datedif(ctx, a, b, unit):
    se = _two_dates(a, b)
    u = c.to_text(unit)
    for x in (se, u):
        if isinstance(x, ExcelError):
            return x
    if se[0] > se[1]:
        return ExcelError.NUM
    d1, d2 = _ymd_date(from_serial(se[0])), _ymd_date(from_serial(se[1]))
    months = (d2.year - d1.year) * 12 + d2.month - d1.month - (d2.day < d1.day)
    u = u.upper()
    if u == "D":
        return float(se[1] - se[0])
    if u == "M":
        return float(months)
    if u == "Y":
        return float(months // 12)
    if u == "YM":
        return float(months % 12)
    if u == "MD":
        return float((d2 - d1).days if d2.day >= d1.day and months == 0 else
                     (d2.day - d1.day) % calendar.monthrange(
                         d2.year if d2.month > 1 else d2.year - 1, (d2.month - 2) % 12 + 1)[1])
    if u == "YD" and ctx.dialect != "libreoffice":
        # Excel moves the end date into the start date's year (then the next year if it
        # falls before the start) and subtracts serials: DATEDIF(8, 1987, "YD") is 153,
        # Jan 8 to Jun 9 of 1900 with its 29 February (formulas__test DATE & TIME!R4)
        def on(year):
            return dt.date(year, d2.month, min(d2.day, calendar.monthrange(year, d2.month)[1]))
        end = on(d1.year)
        if end < d1:
            end = on(d1.year + 1)
        return float(to_serial(end) - to_serial(d1))
    if u == "YD":
        start = dt.date(d2.year, d1.month, min(d1.day, calendar.monthrange(d2.year, d1.month)[1]))
        if start > d2:
            start = dt.date(d2.year - 1, d1.month,
                            min(d1.day, calendar.monthrange(d2.year - 1, d1.month)[1]))
        return float((d2 - start).days)
    return ExcelError.NUM


@register("WEEKDAY", 1, 2)
def _weekday(ctx, v, kind=1.0):
    ymd = _date(v)
    k = c.to_number(kind)
    for x in (ymd, k):
        if isinstance(x, ExcelError):
            return x
    wd = weekday(serial_arg(v))  # Monday 0, from the serial: 1900 has its 29 February
    k = int(k)
    if k == 1 or k == 17:
        return float((wd + 1) % 7 + 1)
    if k == 2 or k == 11:
        return float(wd + 1)
    if k == 3:
        return float(wd)
    if 12 <= k <= 16:
        return float((wd - (k - 11)) % 7 + 1)
    return ExcelError.NUM


def _from_text(name, part):
    """DATEVALUE (the day of a date read from text) and TIMEVALUE (its time of day)."""
    def scalar(ctx, v):
        t = c.to_text(v)
        if isinstance(t, ExcelError):
            return t
        x = parse_date_text(t)
        return x if isinstance(x, ExcelError) else part(x)
    register(name, 1, 1)(scalar)


_from_text("DATEVALUE", lambda x: float(math.floor(x)))
_from_text("TIMEVALUE", lambda x: x - math.floor(x))


def _holidays(h) -> set[int] | ExcelError:
    out = set()
    for v in (c.flat(h) if h is not None else []):
        if v is None:
            continue
        x = serial_arg(v)
        if isinstance(x, ExcelError):
            return x
        out.add(math.floor(x))
    return out


def _workday_ok(n: int, hol: set[int]) -> bool:
    ymd = from_serial(n)
    wd = _ymd_date(ymd).weekday() if ymd[2] != 0 else 5  # (1900-01-00: a Saturday)
    return wd < 5 and n not in hol


@register("NETWORKDAYS", 2, 3, ("scalar", "scalar", "range"))
def _networkdays(ctx, a, b, holidays=None):
    se = _two_dates(a, b)
    hol = _holidays(holidays)
    for x in (se, hol):
        if isinstance(x, ExcelError):
            return x
    lo, hi = sorted(se)
    n = sum(1 for d in range(lo, hi + 1) if _workday_ok(d, hol))
    return float(n if se[0] <= se[1] else -n)


@register("WORKDAY", 2, 3, ("scalar", "scalar", "range"))
def _workday(ctx, start, days, holidays=None):
    s = serial_arg(start)
    k = c.to_number(days)
    hol = _holidays(holidays)
    for x in (s, k, hol):
        if isinstance(x, ExcelError):
            return x
    d, k = math.floor(s), int(k)
    step = 1 if k > 0 else -1
    while k:
        d += step
        if d < 1 or d > max_serial():
            return ExcelError.NUM
        if _workday_ok(d, hol):
            k -= step
    return float(d)
