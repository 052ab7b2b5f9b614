"""Depreciation and more finance: VDB, DB, SYD, CUMIPMT, CUMPRINC, FVSCHEDULE, MIRR,
ISPMT, DOLLARDE, DOLLARFR, TBILLPRICE, TBILLYIELD, AMORLINC, AMORDEGRC.

VDB follows the spreadsheet algorithm (Excel's, also LibreOffice's): declining balance
at ``factor / life`` per period, switching to straight line over the remaining life in
the first period where that gives more (unless ``no_switch``); a fractional start or end
period takes its fraction of that period's depreciation."""

from __future__ import annotations

import math

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.numeric import args_of
from workbook_gen.formula.functions.math.core import fsum
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError


def _safe(fn, booleans=True):
    """``booleans=False``: an Analysis ToolPak function, which takes no boolean (#VALUE!;
    formulas__test.xlsx FINANCIAL!Y13, CUMIPMT(TRUE,...))."""
    def wrapped(ctx, *vs):
        xs = args_of(*vs, booleans=booleans)
        if isinstance(xs, ExcelError):
            return xs
        try:
            r = fn(*xs)
        except (ZeroDivisionError, ValueError, OverflowError):
            return ExcelError.NUM
        return r if isinstance(r, ExcelError) else c.result(float(r))
    return wrapped


def vdb(cost, salvage, life, start, end, factor=2.0, no_switch=False):
    """Depreciation over [start, end] on Excel's schedule: periods of length 1 on a grid
    through ``start`` (0, f, f+1, f+2, ... with f the fraction of ``start``), each at the
    declining rate ``factor/life`` of the book value or, from the first period where it
    is more (unless ``no_switch``), at the straight line over the remaining life; a
    period cut by the grid or by ``end`` takes its fraction (xlcalculator VDB.xlsx, saved
    by Excel: half periods)."""
    if (cost < 0 or salvage < 0 or life <= 0 or start < 0 or end < start or end > life
            or factor <= 0 or salvage > cost):
        return ExcelError.NUM
    rate = min(factor / life, 1.0)
    f = start - math.floor(start)
    book, a, total, line = cost, 0.0, 0.0, None
    while a < end - 1e-12:
        b = f if 0 < f and a == 0 else a + 1
        if line is None:
            ddb = min(book * rate, max(book - salvage, 0.0))
            sln = (book - salvage) / (life - a)
            if not no_switch and sln > ddb:
                line = sln
            unit = ddb if line is None else line
        else:
            unit = line
        if a >= start - 1e-12:
            total += unit * (min(b, end) - a)
        book -= unit * (b - a)
        a = b
    return total


@register("VDB", 5, 7)
def _vdb(ctx, cost, salvage, life, start, end, factor=None, no_switch=None):
    xs = args_of(cost, salvage, life, start, end, 2.0 if factor is None else factor)
    ns = False if no_switch is None else c.to_bool(no_switch)
    for v in (xs, ns):
        if isinstance(v, ExcelError):
            return v
    try:
        r = vdb(*xs, no_switch=ns)
    except (ZeroDivisionError, ValueError, OverflowError):
        return ExcelError.NUM
    return r if isinstance(r, ExcelError) else c.result(float(r))


def db(cost, salvage, life, period, month=12.0):
    month = math.trunc(month)
    period = math.trunc(period)
    if (cost < 0 or salvage < 0 or life <= 0 or period <= 0 or not 1 <= month <= 12
            or period > life + (0 if month == 12 else 1)):
        return ExcelError.NUM
    if cost == 0:
        return 0.0
    rate = round(1 - (salvage / cost) ** (1 / life), 3)
    total = cost * rate * month / 12
    if period == 1:
        return total
    for p in range(2, period + 1):
        if p == life + 1:
            d = (cost - total) * rate * (12 - month) / 12
        else:
            d = (cost - total) * rate
        if p == period:
            return d
        total += d
    return ExcelError.NUM


register("DB", 4, 5)(_safe(db))


def syd(cost, salvage, life, per):
    if life <= 0 or per <= 0 or per > life or salvage < 0:
        return ExcelError.NUM
    return (cost - salvage) * (life - per + 1) * 2 / (life * (life + 1))


register("SYD", 4, 4)(_safe(syd))


def _fv(r, n, pmt, pv, typ):
    if r == 0:
        return -(pv + pmt * n)
    g = (1 + r) ** n
    return -(pv * g + pmt * (1 + r * typ) * (g - 1) / r)


def _pmt(r, n, pv, fv, typ):
    if r == 0:
        return -(pv + fv) / n
    g = (1 + r) ** n
    return -(pv * g + fv) * r / ((1 + r * typ) * (g - 1))


def _cum_args(rate, nper, pv, start, end, typ):
    start, end, typ = math.trunc(start), math.trunc(end), typ
    if (rate <= 0 or nper <= 0 or pv <= 0 or start < 1 or end < start or end > nper
            or typ not in (0, 1)):
        return None
    return start, end, int(typ)


def _cumulative(rate, nper, pv, start, end, typ, first, later):
    """CUMIPMT's and CUMPRINC's sum: ``first(pmt, typ)`` for period 1 if the range holds it,
    then ``later(pmt, balance)`` for each later period, ``balance`` the amount the period's
    interest is charged on; #NUM! for arguments out of range."""
    got = _cum_args(rate, nper, pv, start, end, typ)
    if got is None:
        return ExcelError.NUM
    start, end, typ = got
    pmt = _pmt(rate, nper, pv, 0.0, typ)
    total = 0.0
    if start == 1:
        total = first(pmt, typ)
        start += 1
    for i in range(start, end + 1):
        total += later(pmt, _fv(rate, i - 2, pmt, pv, 1) - pmt if typ
                       else _fv(rate, i - 1, pmt, pv, 0))
    return total


def cumipmt(rate, nper, pv, start, end, typ):
    total = _cumulative(rate, nper, pv, start, end, typ,
                        lambda pmt, typ: 0.0 if typ else -pv, lambda pmt, balance: balance)
    return total if isinstance(total, ExcelError) else total * rate


def cumprinc(rate, nper, pv, start, end, typ):
    return _cumulative(rate, nper, pv, start, end, typ,
                       lambda pmt, typ: pmt if typ else pmt + pv * rate,
                       lambda pmt, balance: pmt - balance * rate)


register("CUMIPMT", 6, 6)(_safe(cumipmt, booleans=False))
register("CUMPRINC", 6, 6)(_safe(cumprinc, booleans=False))
register("ISPMT", 4, 4)(_safe(lambda r, per, n, pv: pv * r * (per / n - 1)))


@register("FVSCHEDULE", 2, 2, ("scalar", "range"))
def _fvschedule(ctx, principal, schedule):
    p = c.to_number(principal)
    if isinstance(p, ExcelError):
        return p
    for v in c.flat(schedule):
        if v is None:
            continue
        r = v if c.is_number(v) else c.to_number(v) if isinstance(v, str) else ExcelError.VALUE
        if isinstance(r, ExcelError):
            return r
        p *= 1 + r
    return c.result(p)


@register("MIRR", 3, 3, ("range", "scalar", "scalar"))
def _mirr(ctx, values, finance_rate, reinvest_rate):
    xs = c.numbers([c.as_area(values)], ctx)
    rates = args_of(finance_rate, reinvest_rate)
    for v in (xs, rates):
        if isinstance(v, ExcelError):
            return v
    fr, rr = rates
    n = len(xs)
    pos = fsum(x / (1 + rr) ** i for i, x in enumerate(xs) if x > 0)
    neg = fsum(x / (1 + fr) ** i for i, x in enumerate(xs) if x < 0)
    if pos == 0 or neg == 0 or n < 2:
        return ExcelError.DIV0
    return c.result((-pos * (1 + rr) ** (n - 1) / neg) ** (1 / (n - 1)) - 1)


def _dollar(de):
    def fn(x, fraction):
        f = math.trunc(fraction)
        if f < 0:
            return ExcelError.NUM
        if f == 0:
            return ExcelError.DIV0
        whole = math.trunc(x)
        frac = x - whole
        scale = 10 ** math.ceil(math.log10(f))
        return whole + (frac * scale / f if de else frac * f / scale)
    return _safe(fn)


register("DOLLARDE", 2, 2)(_dollar(True))
register("DOLLARFR", 2, 2)(_dollar(False))


def _dsm(settlement, maturity):
    s, m = math.trunc(settlement), math.trunc(maturity)
    if s >= m or m - s > 365:
        return None
    return m - s


def tbillprice(settlement, maturity, discount):
    d = _dsm(settlement, maturity)
    if d is None or discount <= 0:
        return ExcelError.NUM
    price = 100 * (1 - discount * d / 360)
    return ExcelError.NUM if price <= 0 else price


def tbillyield(settlement, maturity, price):
    d = _dsm(settlement, maturity)
    if d is None or price <= 0:
        return ExcelError.NUM
    return (100 - price) / price * 360 / d


register("TBILLPRICE", 3, 3)(_safe(tbillprice))
register("TBILLYIELD", 3, 3)(_safe(tbillyield))


# -- French accounting depreciation (AMORLINC, AMORDEGRC) ---------------------------------

def _amor_args(cost, purchased, first, salvage, period, rate, basis):
    from workbook_gen.formula.functions.date.core import serial_arg, yearfrac
    xs = args_of(cost, salvage, period, rate, 0.0 if basis is None else basis)
    dates = [serial_arg(d) for d in (purchased, first)]
    for v in (xs, *dates):
        if isinstance(v, ExcelError):
            return v
    cost, salvage, period, rate, b = xs
    b = math.trunc(b)
    if b not in (0, 1, 3, 4) or rate <= 0 or cost < 0 or salvage < 0 or salvage > cost or period < 0:
        return ExcelError.NUM  # basis 2 is #NUM! on Microsoft's pages
    d0, d1 = (math.floor(d) for d in dates)
    if d0 > d1:
        return ExcelError.NUM
    return cost, salvage, math.trunc(period), rate, yearfrac(d0, d1, b)


def _half_up(x: float) -> float:
    return float(math.floor(x + 0.5))


@register("AMORLINC", 6, 7)
def _amorlinc(ctx, cost, purchased, first, salvage, period, rate, basis=None):
    """Straight line at cost*rate a period, the first period prorated by YEARFRAC(purchase,
    end of the first period, basis), the last what is left down to salvage (Microsoft's
    AMORLINC example: 360)."""
    got = _amor_args(cost, purchased, first, salvage, period, rate, basis)
    if isinstance(got, ExcelError):
        return got
    cost, salvage, period, rate, first_fraction = got
    full = cost * rate
    first_amount = first_fraction * rate * cost
    if period == 0:
        return c.result(first_amount)
    periods = int((cost - salvage - first_amount) / full) if full else 0
    if period <= periods:
        return c.result(full)
    if period == periods + 1:
        return c.result(cost - salvage - full * periods - first_amount)
    return 0.0


@register("AMORDEGRC", 6, 7)
def _amordegrc(ctx, cost, purchased, first, salvage, period, rate, basis=None):
    """Declining balance at rate times the life's coefficient (1 up to 3 years, 1.5 to 5,
    2 to 6, 2.5 beyond), whole amounts; the first period prorated; half the rest in the
    period before the balance would go under salvage and nothing after (Microsoft's
    AMORDEGRC example: 776)."""
    got = _amor_args(cost, purchased, first, salvage, period, rate, basis)
    if isinstance(got, ExcelError):
        return got
    cost, salvage, period, rate, first_fraction = got
    life = 1.0 / rate
    if any(lo < life < hi for lo, hi in ((0, 1), (1, 2), (2, 3), (4, 5))):
        return ExcelError.NUM  # Microsoft's AMORDEGRC page
    coeff = 1.0 if life < 3 else 1.5 if life < 5 else 2.0 if life <= 6 else 2.5
    rate *= coeff
    amount = _half_up(first_fraction * rate * cost)
    cost -= amount
    rest = cost - salvage
    for n in range(period):
        amount = _half_up(rate * cost)
        rest -= amount
        if rest < 0:
            return _half_up(cost * 0.5) if period - n in (0, 1) else 0.0
        cost -= amount
    return amount
