"""Securities with an odd last period: ODDLPRICE, ODDLYIELD, by the formulas of Microsoft's
pages. The odd period from the last interest date to maturity is cut into quasi-coupon
periods of 12/frequency months counted forward from the last interest date; for the i-th:
NL_i its normal length (actual days in basis 1, else 360/f or 365/f), DC_i its days up to
maturity, A_i its days up to settlement, DSC_i its days from settlement to maturity."""

from __future__ import annotations

import math

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions import daycount as dc
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError


def _odd_last(s, m, last, f, b):
    """(sum DC/NL, sum A/NL, sum DSC/NL) over the quasi-coupon periods of the odd period."""
    step, eom = 12 // f, dc._month_end(last)
    dc_sum = a_sum = dsc_sum = 0.0
    k = 0
    while True:
        q0, q1 = dc.add_months(last, k * step, eom), dc.add_months(last, (k + 1) * step, eom)
        if q0 >= m:
            break
        nl = (q1 - q0).days if b == 1 else (365.0 if b == 3 else 360.0) / f
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


@register("ODDLPRICE", "finance", 7, 8)
def _oddlprice(ctx, settle, maturity, last, rate, yld, redemption, freq, basis=None):
    got = _odd_args(settle, maturity, last, freq, basis, (rate, yld, redemption))
    if isinstance(got, ExcelError):
        return got
    s, m, li, f, b, (r, y, red) = got
    if r < 0 or y < 0 or red <= 0:
        return ExcelError.NUM
    dcs, acs, dscs = _odd_last(s, m, li, f, b)
    cpn = 100.0 * r / f
    return c.result((red + dcs * cpn) / (1.0 + dscs * y / f) - acs * cpn)


@register("ODDLYIELD", "finance", 7, 8)
def _oddlyield(ctx, settle, maturity, last, rate, pr, redemption, freq, basis=None):
    got = _odd_args(settle, maturity, last, freq, basis, (rate, pr, redemption))
    if isinstance(got, ExcelError):
        return got
    s, m, li, f, b, (r, p, red) = got
    if r < 0 or p <= 0 or red <= 0:
        return ExcelError.NUM
    dcs, acs, dscs = _odd_last(s, m, li, f, b)
    cpn = 100.0 * r / f
    paid = p + acs * cpn
    try:
        return c.result((red + dcs * cpn - paid) / paid * f / dscs)
    except ZeroDivisionError:
        return ExcelError.NUM
