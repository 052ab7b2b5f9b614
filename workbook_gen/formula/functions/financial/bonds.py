"""Securities: COUPDAYBS, COUPDAYS, COUPDAYSNC, COUPNCD, COUPNUM, COUPPCD, PRICE, YIELD,
DURATION, MDURATION, ACCRINT, ACCRINTM, DISC, PRICEDISC, YIELDDISC, INTRATE, RECEIVED,
PRICEMAT, YIELDMAT, TBILLEQ, with the formulas of Microsoft's function pages (A: days from
the coupon period's start to settlement, E: the period's days, DSC: days from settlement to
the next coupon, N: coupons left; day counts in daycount.py)."""

from __future__ import annotations

import math

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.financial import daycount as dc
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError


def _guarded(fn):
    def wrapped(*xs, **kw):
        try:
            y = fn(*xs, **kw)
        except (ZeroDivisionError, OverflowError, ValueError):
            return ExcelError.NUM
        if isinstance(y, ExcelError):
            return y
        return c.result(float(y))
    return wrapped


# -- coupon schedule ---------------------------------------------------------------------

def _coupon(name, fn):
    def scalar(ctx, settle, maturity, freq, basis=None):
        got = dc.bond_args(settle, maturity, freq, basis)
        if isinstance(got, ExcelError):
            return got
        s, m, f, b, _ = got
        return _guarded(fn)(dc.Schedule(s, m, f), s, b)
    register(name, 3, 4)(scalar)


_coupon("COUPDAYBS", lambda sch, s, b: dc.days_before(sch, s, b))
_coupon("COUPDAYS", lambda sch, s, b: dc.coupon_days(sch, b))
_coupon("COUPDAYSNC", lambda sch, s, b: dc.days_after(sch, s, b))
_coupon("COUPNCD", lambda sch, s, b: dc.serial(sch.ncd))
_coupon("COUPPCD", lambda sch, s, b: dc.serial(sch.pcd))
_coupon("COUPNUM", lambda sch, s, b: float(sch.n))


# -- coupon bonds -------------------------------------------------------------------------

def price(s, m, f, b, rate, yld, redemption, lo=False) -> float:
    """DSC is E - A in every basis (Excel: the Excel-saved ironcalc PRICE_YIELD.xlsx, bases
    2 and 3, where COUPDAYSNC's actual days differ); LibreOffice (``lo``) takes COUPDAYSNC."""
    sch = dc.Schedule(s, m, f)
    a, e = dc.days_before(sch, s, b), dc.coupon_days(sch, b)
    dsc, n = (dc.days_after(sch, s, b) if lo else e - a), sch.n
    cpn = 100.0 * rate / f
    if n == 1:
        return (redemption + cpn) / (1.0 + dsc / e * yld / f) - cpn * a / e
    v = 1.0 + yld / f
    total = redemption / v ** (n - 1 + dsc / e)
    total += sum(cpn / v ** (k - 1 + dsc / e) for k in range(1, n + 1))
    return total - cpn * a / e


def _bond(name, n_nums, fn, check):
    """fn(settle, maturity, freq, basis, *numbers) for NAME(settle, maturity, *numbers,
    frequency, [basis])."""
    def scalar(ctx, settle, maturity, *rest):
        nums, freq = rest[:n_nums], rest[n_nums]
        basis = rest[n_nums + 1] if len(rest) > n_nums + 1 else None
        got = dc.bond_args(settle, maturity, freq, basis, nums)
        if isinstance(got, ExcelError):
            return got
        s, m, f, b, xs = got
        if not check(*xs):
            return ExcelError.NUM
        if fn in (price, _yield):
            return _guarded(fn)(s, m, f, b, *xs, lo=ctx.dialect == "libreoffice")
        return _guarded(fn)(s, m, f, b, *xs)
    register(name, 3 + n_nums, 4 + n_nums)(scalar)


def _yield(s, m, f, b, rate, pr, redemption, lo=False):
    sch = dc.Schedule(s, m, f)
    if sch.n == 1:  # Microsoft's closed form for one coupon left
        a, e = dc.days_before(sch, s, b), dc.coupon_days(sch, b)
        dsr = e - a
        paid = pr / 100.0 + a / e * rate / f
        return (redemption / 100.0 + rate / f - paid) / paid * f * e / dsr
    return _solve(lambda y: price(s, m, f, b, rate, y, redemption, lo) - pr)


def _solve(g, guess=0.05):
    """The root of a decreasing price function: Newton from ``guess``, bisection when a
    step leaves the bracket."""
    lo, hi = -0.999999, 1.0
    while g(hi) > 0:
        hi *= 2
        if hi > 1e6:
            return ExcelError.NUM
    if g(lo) < 0:
        return ExcelError.NUM
    y = guess
    for _ in range(200):
        gy = g(y)
        if gy == 0:
            return y
        lo, hi = (y, hi) if gy > 0 else (lo, y)
        h = 1e-7 * max(abs(y), 1e-3)
        slope = (g(y + h) - gy) / h
        step = y - gy / slope if slope else (lo + hi) / 2
        if not lo < step < hi:
            step = (lo + hi) / 2
        if abs(step - y) <= 1e-15 * max(abs(y), 1.0):
            return step
        y = step
    return y


def _duration(s, m, f, b, cpn, yld):
    """Macaulay duration, the k-th coupon (k-1+DSC/E) periods away: Microsoft's examples
    (10.9191453, 5.73567) and the Excel-saved sheetjs formula_stress_test.xlsx Finance!B38 to
    the last bit (LibreOffice and Gnumeric count from YEARFRAC instead and differ)."""
    sch = dc.Schedule(s, m, f)
    frac = dc.days_after(sch, s, b) / dc.coupon_days(sch, b)
    v = 1.0 + yld / f
    flows = [(k - 1 + frac, 100.0 * cpn / f + (100.0 if k == sch.n else 0.0))
             for k in range(1, sch.n + 1)]
    pv = sum(x / v ** t for t, x in flows)
    return sum(t * x / v ** t for t, x in flows) / pv / f


_bond("PRICE", 3, price, lambda rate, yld, red: rate >= 0 and yld >= 0 and red > 0)
_bond("YIELD", 3, _yield, lambda rate, pr, red: rate >= 0 and pr > 0 and red > 0)
_bond("DURATION", 2, _duration, lambda cpn, yld: cpn >= 0 and yld >= 0)
_bond("MDURATION", 2, lambda s, m, f, b, cpn, yld: _duration(s, m, f, b, cpn, yld) / (1 + yld / f),
      lambda cpn, yld: cpn >= 0 and yld >= 0)


# -- accrued interest ---------------------------------------------------------------------

@register("ACCRINT", 6, 8)
def _accrint(ctx, issue, first, settle, rate, par, freq, basis=None, method=True):
    """par * rate/frequency * sum of A_i/NL_i over the quasi-coupon periods (anchored on
    first_interest) from issue (calc_method TRUE, or settlement before first_interest)
    or first_interest to settlement."""
    got = dc.bond_args(issue, settle, freq, basis, (rate, par))
    first_serial = dc.serial_arg(first)
    whole = c.to_bool(method) if method is not None else True
    for v in (got, first_serial, whole):
        if isinstance(v, ExcelError):
            return v
    i, s, f, b, (r, p) = got
    if r <= 0 or p <= 0 or isinstance(dc.from_serial(first_serial), ExcelError):
        return ExcelError.NUM
    fi = dc.date_of(math.floor(first_serial))
    start = i if whole or s <= fi else fi
    step, eom = 12 // f, dc._month_end(fi)
    k = 0
    while dc.add_months(fi, k * step, eom) > start:
        k -= 1
    while dc.add_months(fi, (k + 1) * step, eom) <= start:
        k += 1
    total = 0.0
    while True:
        q0, q1 = dc.add_months(fi, k * step, eom), dc.add_months(fi, (k + 1) * step, eom)
        if q0 >= s:
            break
        a = dc.days(max(q0, start), min(q1, s), b)
        nl = (q1 - q0).days if b == 1 else (365.0 if b == 3 else 360.0) / f
        total += a / nl
        k += 1
    return c.result(p * r / f * total)


def _span(name, n_nums, fn, check):
    """NAME(settlement, maturity, *numbers, [basis]): fn(year fraction, *numbers)."""
    def scalar(ctx, settle, maturity, *rest):
        nums = rest[:n_nums]
        basis = rest[n_nums] if len(rest) > n_nums else None
        got = dc.bond_args(settle, maturity, 1, basis, nums)
        if isinstance(got, ExcelError):
            return got
        s, m, _, b, xs = got
        if not check(*xs):
            return ExcelError.NUM
        return _guarded(fn)(dc.year_fraction(dc.serial(s), dc.serial(m), b), *xs)
    register(name, 2 + n_nums, 3 + n_nums)(scalar)


_span("ACCRINTM", 2, lambda t, rate, par: par * rate * t,
      lambda rate, par: rate > 0 and par > 0)
_span("DISC", 2, lambda t, pr, red: (red - pr) / red / t, lambda pr, red: pr > 0 and red > 0)
_span("PRICEDISC", 2, lambda t, d, red: red - d * red * t, lambda d, red: d > 0 and red > 0)
_span("YIELDDISC", 2, lambda t, pr, red: (red / pr - 1) / t, lambda pr, red: pr > 0 and red > 0)
_span("INTRATE", 2, lambda t, inv, red: (red - inv) / inv / t,
      lambda inv, red: inv > 0 and red > 0)
_span("RECEIVED", 2, lambda t, inv, d: inv / (1 - d * t), lambda inv, d: inv > 0 and d > 0)


def _at_maturity(name, fn):
    """PRICEMAT/YIELDMAT(settlement, maturity, issue, rate, x, [basis]): interest paid at
    maturity, accrued from issue (year fractions: issue-maturity, issue-settlement,
    settlement-maturity)."""
    def scalar(ctx, settle, maturity, issue, rate, x, basis=None):
        got = dc.bond_args(settle, maturity, 1, basis, (rate, x))
        iss = dc.serial_arg(issue)
        for v in (got, iss):
            if isinstance(v, ExcelError):
                return v
        s, m, _, b, (r, y) = got
        iss = math.floor(iss)
        if r < 0 or y < 0 or isinstance(dc.from_serial(iss), ExcelError):
            return ExcelError.NUM
        ss, ms = dc.serial(s), dc.serial(m)
        yf = dc.year_fraction
        return _guarded(fn)(yf(iss, ms, b), yf(iss, ss, b), yf(ss, ms, b), r, y)
    register(name, 5, 6)(scalar)


_at_maturity("PRICEMAT", lambda dim, a, dsm, r, y:
             (100 + dim * r * 100) / (1 + dsm * y) - a * r * 100)
_at_maturity("YIELDMAT", lambda dim, a, dsm, r, pr:
             ((1 + dim * r) - (pr / 100 + a * r)) / (pr / 100 + a * r) / dsm)


@register("TBILLEQ", 3, 3)
def _tbilleq(ctx, settle, maturity, discount):
    """Bond-equivalent yield 365*rate/(360-rate*DSM), DSM the days to maturity (Microsoft's
    TBILLEQ page; its example 0.094151 counts 62 days from 31-Mar to 1-Jun); at most a
    year."""
    got = dc.bond_args(settle, maturity, 1, 0, (discount,))
    if isinstance(got, ExcelError):
        return got
    s, m, _, _, (d,) = got
    if d <= 0 or m > dc.add_months(s, 12, False):  # more than a calendar year
        return ExcelError.NUM
    return _guarded(lambda: 365 * d / (360 - d * (m - s).days))()
