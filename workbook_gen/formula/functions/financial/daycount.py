"""Day-count bases 0-4 and coupon schedules, shared by the bond functions (bonds.py).

Bases (Microsoft's pages of PRICE, COUPDAYS, ...): 0 US (NASD) 30/360, 1 actual/actual,
2 actual/360, 3 actual/365, 4 European 30/360.  Coupon dates run back from maturity by
12/frequency months, each on maturity's day of the month (the month's last day when the
month is shorter, and every month's last day when maturity is one)."""

from __future__ import annotations

import calendar
import datetime as dt
import math

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.date.core import (days_30_360, from_serial, serial_arg,
                                                 to_serial, yearfrac)
from workbook_gen.xlerror import ExcelError

FREQUENCIES = (1, 2, 4)


def date_of(serial: float) -> dt.date:
    y, m, d = from_serial(serial)
    if d == 0:  # serial 0, 1900-01-00
        return dt.date(1899, 12, 31)
    if (y, m, d) == (1900, 2, 29):
        return dt.date(1900, 2, 28)
    return dt.date(y, m, d)


def _month_end(d: dt.date) -> bool:
    return d.day == calendar.monthrange(d.year, d.month)[1]


def add_months(d: dt.date, months: int, end_of_month: bool) -> dt.date:
    k = d.year * 12 + d.month - 1 + months
    y, m = divmod(k, 12)
    last = calendar.monthrange(y, m + 1)[1]
    return dt.date(y, m + 1, last if end_of_month else min(d.day, last))


def days(d1: dt.date, d2: dt.date, basis: int) -> int:
    """Days from d1 to d2 in the basis (30/360 for 0 and 4, actual days otherwise)."""
    if basis not in (0, 4):
        return (d2 - d1).days
    return days_30_360((d1.year, d1.month, d1.day), d1.month == 2 and _month_end(d1),
                       (d2.year, d2.month, d2.day), d2.month == 2 and _month_end(d2),
                       basis == 4)


def year_days(basis: int, d: dt.date | None = None) -> float:
    """The year's length in the basis (basis 1: the year of ``d``)."""
    if basis == 1:
        return 366.0 if d is not None and calendar.isleap(d.year) else 365.0
    return 365.0 if basis == 3 else 360.0


def year_fraction(s: float, e: float, basis: int) -> float:
    return yearfrac(s, e, basis)


class Schedule:
    """The coupon period holding ``settle``: its start (pcd), its end (ncd), and the number
    of coupons left (n)."""

    def __init__(self, settle: dt.date, maturity: dt.date, freq: int):
        self.step = 12 // freq
        self.maturity = maturity
        self.eom = _month_end(maturity)
        months = (maturity.year - settle.year) * 12 + maturity.month - settle.month
        k = max(months // self.step, 1)
        while self.coupon(k) > settle:  # coupon(k): k periods before maturity
            k += 1
        while k > 1 and self.coupon(k - 1) <= settle:
            k -= 1
        self.n, self.pcd, self.ncd, self.freq = k, self.coupon(k), self.coupon(k - 1), freq

    def coupon(self, k: int) -> dt.date:
        return add_months(self.maturity, -k * self.step, self.eom)


def coupon_days(s: Schedule, basis: int) -> float:
    """E: the length of the coupon period in days."""
    if basis == 1:
        return float((s.ncd - s.pcd).days)
    return (365.0 if basis == 3 else 360.0) / s.freq


def days_before(s: Schedule, settle: dt.date, basis: int) -> float:
    """A: days from the period's start to settlement."""
    return float(days(s.pcd, settle, basis))


def days_after(s: Schedule, settle: dt.date, basis: int) -> float:
    """DSC: days from settlement to the next coupon (30/360 bases: E - A)."""
    if basis in (0, 4):
        return coupon_days(s, basis) - days_before(s, settle, basis)
    return float((s.ncd - settle).days)


def bond_args(settle, maturity, freq, basis, nums=()):
    """Settlement and maturity as dates, the frequency and basis as whole numbers, the
    other numbers; Excel's checks: #VALUE! for what is not a number, #NUM! for a
    frequency not 1/2/4, a basis not 0-4 or settlement not before maturity."""
    s, m = serial_arg(settle), serial_arg(maturity)
    xs = [c.to_number(v) if v is not None else 0.0 for v in (freq, basis)]
    rest = [c.to_number(v) for v in nums]
    for v in (s, m, *xs, *rest):
        if isinstance(v, ExcelError):
            return v
    f, b = math.trunc(xs[0]), math.trunc(xs[1])
    s, m = math.floor(s), math.floor(m)
    if f not in FREQUENCIES or b not in range(5) or s >= m:
        return ExcelError.NUM
    for x in (s, m):
        if isinstance(from_serial(x), ExcelError):
            return ExcelError.NUM
    return date_of(s), date_of(m), f, b, rest


def serial(d: dt.date) -> float:
    return to_serial(d)
