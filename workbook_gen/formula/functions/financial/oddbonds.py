"""Securities with an odd first or last period: ODDFPRICE, ODDFYIELD, ODDLPRICE, ODDLYIELD,
by the formulas of Microsoft's pages. An odd period is cut into quasi-coupon periods of
12/frequency months (counted forward from the last interest date, or back from the first
coupon); for the i-th: NL_i its normal length (an odd last period's: its days in the
basis; an odd first period's: actual days in basis 1, else 360/f or 365/f), DC_i its days
within the odd period (a whole one before the first coupon counts one), A_i its days up to
settlement, DSC_i its days from settlement to maturity."""

from __future__ import annotations

import math

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.financial import daycount as dc
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError


def _odd_last(s, m, last, f, b, lo=False):
    """(sum DC/NL, sum A/NL, sum DSC/NL) over the quasi-coupon periods of the odd period.
    NL is the quasi-coupon period's days in the basis (Excel: the Excel-saved ironcalc
    PRICE_YIELD.xlsx, bases 2 and 3 counting actual days); LibreOffice (``lo``) 360/f or
    365/f in bases 2 and 3."""
    step, eom = 12 // f, dc._month_end(last)
    dc_sum = a_sum = dsc_sum = 0.0
    k = 0
    while True:
        q0, q1 = dc.add_months(last, k * step, eom), dc.add_months(last, (k + 1) * step, eom)
        if q0 >= m:
            break
        nl = float(dc.days(q0, q1, b)) if not lo or b == 1 else _normal(q0, q1, f, b)
        end = min(q1, m)
        dc_sum += dc.days(q0, end, b) / nl
        if s > q0:
            a_sum += dc.days(q0, min(s, end), b) / nl
        if s < end:
            dsc_sum += dc.days(max(s, q0), end, b) / nl
        k += 1
    return dc_sum, a_sum, dsc_sum


def _odd_args(settle, maturity, last, freq, basis, nums):
    got = dc.bond_args(settle, maturity, freq, basis, nums)
    li = dc.serial_arg(last)
    for v in (got, li):
        if isinstance(v, ExcelError):
            return v
    s, m, f, b, xs = got
    if isinstance(dc.from_serial(math.floor(li)), ExcelError):
        return ExcelError.NUM
    li = dc.date_of(math.floor(li))
    if not li < s:  # maturity > settlement > last_interest
        return ExcelError.NUM
    return s, m, li, f, b, xs


def _last_terms(ctx, settle, maturity, last, rate, x, redemption, freq, basis, x_bad):
    """ODDLPRICE's and ODDLYIELD's common part: (x, redemption, frequency, coupon, DCS, A,
    DSC) of an odd last period, or the error; #NUM! for a negative rate, ``x_bad(x)`` (the
    yield or the price) or a redemption <= 0."""
    got = _odd_args(settle, maturity, last, freq, basis, (rate, x, redemption))
    if isinstance(got, ExcelError):
        return got
    s, m, li, f, b, (r, x, red) = got
    if r < 0 or x_bad(x) or red <= 0:
        return ExcelError.NUM
    dcs, acs, dscs = _odd_last(s, m, li, f, b, ctx.dialect == "libreoffice")
    return x, red, f, 100.0 * r / f, dcs, acs, dscs


@register("ODDLPRICE", 7, 8)
def _oddlprice(ctx, settle, maturity, last, rate, yld, redemption, freq, basis=None):
    got = _last_terms(ctx, settle, maturity, last, rate, yld, redemption, freq, basis,
                      lambda y: y < 0)
    if isinstance(got, ExcelError):
        return got
    y, red, f, cpn, dcs, acs, dscs = got
    return c.result((red + dcs * cpn) / (1.0 + dscs * y / f) - acs * cpn)


@register("ODDLYIELD", 7, 8)
def _oddlyield(ctx, settle, maturity, last, rate, pr, redemption, freq, basis=None):
    got = _last_terms(ctx, settle, maturity, last, rate, pr, redemption, freq, basis,
                      lambda p: p <= 0)
    if isinstance(got, ExcelError):
        return got
    p, red, f, cpn, dcs, acs, dscs = got
    paid = p + acs * cpn
    try:
        return c.result((red + dcs * cpn - paid) / paid * f / dscs)
    except ZeroDivisionError:
        return ExcelError.NUM


# -- odd first period ---------------------------------------------------------------------

def _normal(q0, q1, f, b) -> float:
    return float((q1 - q0).days) if b == 1 else (365.0 if b == 3 else 360.0) / f


def oddf_price(s, m, issue, first, f, b, r, y, red) -> float:
    """Microsoft's ODDFPRICE (the long-first-period form, which is the short one when the odd
    period is one quasi-coupon period): quasi-coupon dates run back from first_coupon."""
    step, eom = 12 // f, dc._month_end(first)

    def q(k):  # k periods before the first coupon
        return dc.add_months(first, -k * step, eom)
    nc = 1
    while q(nc) > issue:
        nc += 1
    dc_sum = a_sum = 0.0
    for k in range(nc, 0, -1):
        q0, q1 = q(k), q(k - 1)
        nl = _normal(q0, q1, f, b)
        start = max(issue, q0)
        dc_sum += dc.days(start, q1, b) / nl if k == nc else 1.0  # a whole period counts 1
        if s > start:
            a_sum += dc.days(start, min(s, q1), b) / nl
    k = 0
    while q(k + 1) > s:  # the quasi-coupon period holding settlement: (q(k+1), q(k)]
        k += 1
    nq = k  # whole quasi-coupon periods from its end to the first coupon
    e = _normal(q(k + 1), q(k), f, b)
    if b in (2, 3):  # actual days to the next quasi-coupon date; else E - A
        dsc = dc.days(s, q(k), b) / e
    else:
        dsc = (e - dc.days(q(k + 1), s, b)) / e
    n = dc.Schedule(first, m, f).n if first < m else 0  # coupons after the first one
    v = 1.0 + y / f
    cpn = 100.0 * r / f
    price = red / v ** (n + nq + dsc) + cpn * dc_sum / v ** (nq + dsc)
    price += sum(cpn / v ** (j + nq + dsc) for j in range(1, n + 1))
    return price - cpn * a_sum


def _oddf_args(settle, maturity, issue, first, freq, basis, nums, x_bad):
    """ODDFPRICE's and ODDFYIELD's arguments (settlement, maturity, issue, first coupon,
    frequency, basis, (rate, x, redemption)), or the error; #NUM! for dates out of order, a
    negative rate, ``x_bad(x)`` (the yield or the price) or a redemption <= 0."""
    got = dc.bond_args(settle, maturity, freq, basis, nums)
    dates = [dc.serial_arg(d) for d in (issue, first)]
    for v in (got, *dates):
        if isinstance(v, ExcelError):
            return v
    s, m, f, b, xs = got
    if any(isinstance(dc.from_serial(math.floor(d)), ExcelError) for d in dates):
        return ExcelError.NUM
    i, fc = (dc.date_of(math.floor(d)) for d in dates)
    if not i < s < fc <= m:  # maturity >= first_coupon > settlement > issue
        return ExcelError.NUM
    r, x, red = xs
    if r < 0 or x_bad(x) or red <= 0:
        return ExcelError.NUM
    return s, m, i, fc, f, b, xs


@register("ODDFPRICE", 8, 9)
def _oddfprice(ctx, settle, maturity, issue, first, rate, yld, redemption, freq, basis=None):
    got = _oddf_args(settle, maturity, issue, first, freq, basis, (rate, yld, redemption),
                     lambda y: y < 0)
    if isinstance(got, ExcelError):
        return got
    s, m, i, fc, f, b, (r, y, red) = got
    try:
        return c.result(oddf_price(s, m, i, fc, f, b, r, y, red))
    except (ZeroDivisionError, OverflowError):
        return ExcelError.NUM


@register("ODDFYIELD", 8, 9)
def _oddfyield(ctx, settle, maturity, issue, first, rate, pr, redemption, freq, basis=None):
    """The yield at which ODDFPRICE is the price (Newton's method, bisection as a guard)."""
    from workbook_gen.formula.functions.financial.bonds import _solve
    got = _oddf_args(settle, maturity, issue, first, freq, basis, (rate, pr, redemption),
                     lambda p: p <= 0)
    if isinstance(got, ExcelError):
        return got
    s, m, i, fc, f, b, (r, p, red) = got
    try:
        y = _solve(lambda y: oddf_price(s, m, i, fc, f, b, r, y, red) - p)
    except (ZeroDivisionError, OverflowError):
        return ExcelError.NUM
    return y if isinstance(y, ExcelError) else c.result(y)
