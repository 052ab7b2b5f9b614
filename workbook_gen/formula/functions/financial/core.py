"""Finance: PMT, PV, FV, NPER, RATE, IPMT, PPMT, NPV, IRR, XNPV, XIRR, SLN, DDB, EFFECT,
NOMINAL (Excel's sign convention: money paid out is negative)."""

from __future__ import annotations

import math

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.math.core import fsum
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError


def _nums(*vs):
    out = [c.to_number(v) if v is not None else 0.0 for v in vs]
    bad = next((x for x in out if isinstance(x, ExcelError)), None)
    return bad if bad is not None else out


def _growth(r: float, n: float) -> float:
    return (1.0 + r) ** n


def pmt(r, n, pv, fv=0.0, when=0.0):
    if n == 0:
        return ExcelError.NUM
    if r == 0:
        return -(pv + fv) / n
    g = _growth(r, n)
    return -(r * (pv * g + fv)) / ((1 + r * when) * (g - 1))


def fv(r, n, p, pv=0.0, when=0.0):
    if r == 0:
        return -(pv + p * n)
    g = _growth(r, n)
    # the annuity factor ((1+r)^n-1)/r first: Excel's rounding (POI FormulaEvalTestData.xlsx
    # FinanceLibTests H19:H20, where the two terms cancel to 1e-6 of their size)
    return -(pv * g + p * (1 + r * when) * ((g - 1) / r))


def pv(r, n, p, fv_=0.0, when=0.0):
    if r == 0:
        return -(fv_ + p * n)
    g = _growth(r, n)
    return -(fv_ + p * (1 + r * when) * (g - 1) / r) / g


def _safe(fn, *xs):
    try:
        y = fn(*xs)
        if isinstance(y, complex):  # a negative growth to a fractional power
            return ExcelError.NUM
        return y if isinstance(y, ExcelError) else c.result(float(y))
    except (OverflowError, ZeroDivisionError, ValueError):
        return ExcelError.NUM


def _tvm(name, fn, nmin, rate_over_minus_one=False):
    """``rate_over_minus_one``: a rate of -1 or less is #NUM! (LibreOffice: less only)."""
    def scalar(ctx, *args):
        xs = _nums(*args)
        if isinstance(xs, ExcelError):
            return xs
        if len(xs) == 5:
            xs[4] = 1.0 if xs[4] != 0 else 0.0
        if rate_over_minus_one and (xs[0] < -1 or xs[0] == -1 and _excel(ctx)):
            return ExcelError.NUM
        return _safe(fn, *xs)
    register(name, nmin, 5)(scalar)


# PMT's rate must exceed -1 (Excel, ironcalc PMT.xlsx: PMT(-3,...) and PMT(-1,...) #NUM!);
# LibreOffice 7.4 refuses below -1 only (PMT(-1,1,-100) is -0 there)
_tvm("PMT", pmt, 3, rate_over_minus_one=True)
_tvm("FV", fv, 3)
_tvm("PV", pv, 3)


def _nper(r, p, pv_, fv_=0.0, when=0.0):
    if r == 0:
        return ExcelError.NUM if p == 0 else -(pv_ + fv_) / p
    a = p * (1 + r * when)
    return math.log((a - fv_ * r) / (a + pv_ * r)) / math.log(1 + r)


_tvm("NPER", _nper, 3)


def ipmt(r, per, n, pv_, fv_=0.0, when=0.0):
    if not 1 <= per <= n:
        return ExcelError.NUM
    p = pmt(r, n, pv_, fv_, when)
    if when and per == 1:
        return 0.0
    interest = fv(r, per - 1, p, pv_, when) * r
    return interest / (1 + r) if when else interest


def ppmt(r, per, n, pv_, fv_=0.0, when=0.0, lo=False):
    """PMT - IPMT (LibreOffice's, ``lo``) without its cancellation: -r (pv + fv) (1+r)^(per-1) / ((1+r)^n - 1), over
    1+r for payments at the start (the first one all principal). Mac Excel 16's
    PPMT(1,3,33,10000,1) is -4.657078534906851E-06 (formulas__test.xlsx FINANCIAL!Y40),
    within an ulp of the exact value, where the difference keeps 9 digits."""
    i = ipmt(r, per, n, pv_, fv_, when)
    if isinstance(i, ExcelError):
        return i
    if lo or r == 0 or r <= -1 or (when and per == 1):
        return pmt(r, n, pv_, fv_, when) - i
    principal = -r * (pv_ + fv_) * _growth(r, per - 1) / (_growth(r, n) - 1)
    return principal / (1 + r) if when else principal


@register("IPMT", 4, 6)
def _ipmt(ctx, *args):
    xs = _nums(*args)
    return xs if isinstance(xs, ExcelError) else _safe(ipmt, *xs)


@register("PPMT", 4, 6)
def _ppmt(ctx, *args):
    xs = _nums(*args)
    if isinstance(xs, ExcelError):
        return xs
    return _safe(lambda *v: ppmt(*v, lo=not _excel(ctx)), *(xs + [0.0, 0.0][len(xs) - 4:]))


def _solve(f, guess: float, lo: float = -0.999999999, hi: float = 1e10):
    """A root of ``f`` near ``guess``: Newton's method, then bisection; None if none."""
    x = guess
    for _ in range(100):
        try:
            y = f(x)
            h = 1e-7 * max(1.0, abs(x))
            d = (f(x + h) - y) / h
        except (OverflowError, ZeroDivisionError, ValueError):
            break
        if not math.isfinite(y) or d == 0 or not math.isfinite(d):
            break
        step = y / d
        x -= step
        if x <= -1:
            x = (x + step - 1) / 2
        if abs(step) <= 1e-12 * max(1.0, abs(x)):
            return x
    grid = [lo] + [(-0.99 + 0.01 * i) for i in range(100)] + [1.0, 10.0, 100.0, 1000.0, hi]
    try:
        values = [(g, f(g)) for g in grid]
    except (OverflowError, ZeroDivisionError, ValueError):
        return None
    for (a, fa), (b, fb) in zip(values, values[1:]):
        if math.isfinite(fa) and math.isfinite(fb) and fa * fb <= 0:
            for _ in range(200):
                m = (a + b) / 2
                fm = f(m)
                if fa * fm <= 0:
                    b = m
                else:
                    a, fa = m, fm
            return (a + b) / 2
    return None


@register("RATE", 3, 6)
def _rate(ctx, n, p, pv_, fv_=0.0, when=0.0, guess=0.1):
    xs = _nums(n, p, pv_, fv_, when, guess)
    if isinstance(xs, ExcelError):
        return xs
    n, p, pv_, fv_, when, g = xs
    when = 1.0 if when else 0.0

    def f(r):
        if abs(r) < 1e-12:
            return pv_ + p * n + fv_
        gr = _growth(r, n)
        return pv_ * gr + p * (1 + r * when) * (gr - 1) / r + fv_
    r = _solve(f, g)
    return ExcelError.NUM if r is None else c.result(r)


@register("NPV", 2, -1, ("scalar", "range"))
def _npv(ctx, rate, *args):
    r = c.to_number(rate)
    if isinstance(r, ExcelError):
        return r
    xs = c.numbers(args, ctx)
    if isinstance(xs, ExcelError):
        return xs
    if r == -1:
        return ExcelError.DIV0
    return _safe(lambda: fsum([v / (1 + r) ** (i + 1) for i, v in enumerate(xs)]))


@register("IRR", 1, 2, ("range", "scalar"))
def _irr(ctx, values, guess=0.1):
    xs = c.numbers([c.as_area(values)], ctx)
    g = c.to_number(guess)
    if isinstance(xs, ExcelError) and _excel(ctx):
        return ExcelError.VALUE  # Excel: an error among the cash flows (Mac Excel's Z26:AF27)
    for x in (xs, g):
        if isinstance(x, ExcelError):
            return x
    if not (any(v > 0 for v in xs) and any(v < 0 for v in xs)):
        return ExcelError.NUM
    r = _solve(lambda r: sum(v / (1 + r) ** i for i, v in enumerate(xs)), g)
    return ExcelError.NUM if r is None else c.result(r)


def _excel(ctx) -> bool:
    return ctx is None or ctx.dialect != "libreoffice"


def _flows(values, dates, excel: bool = True):
    """(cash flows, their dates) of XNPV and XIRR, or the error.

    Pairs of empty cells and pairs holding text are left out. Excel (Mac Excel's
    formulas__test.xlsx, FINANCIAL row 54) checks the dates' errors before the values' and
    refuses a boolean with #VALUE!; LibreOffice (measured, 7.4) checks the values first and
    takes a boolean as its number."""
    vs = [v for v in c.flat(values)]
    ds = [d for d in c.flat(dates)]
    for v in (ds + vs if excel else vs + ds):
        if isinstance(v, ExcelError):
            return v
    if len(vs) != len(ds) or not vs:
        return ExcelError.NUM
    pairs = [(v, d) for v, d in zip(vs, ds) if (v is not None or d is not None)
             and not isinstance(v, str) and not isinstance(d, str)]
    if excel and any(isinstance(x, bool) for pair in pairs for x in pair):
        return ExcelError.VALUE
    if not pairs:
        return ExcelError.NUM
    try:
        vs = [float(c.to_number(v)) for v, _ in pairs]
        ds = [math.floor(float(c.to_number(d))) for _, d in pairs]
    except TypeError:
        return ExcelError.VALUE
    if any(d < ds[0] for d in ds):
        return ExcelError.NUM
    return vs, ds


def _rate_argument(x, excel: bool):
    """XNPV's rate, XIRR's guess: Excel refuses a boolean (#VALUE!, FINANCIAL!Y54, Z56)."""
    if excel and isinstance(x, bool):
        return ExcelError.VALUE
    return c.to_number(x)


def _xnpv(r, vs, ds):
    """Summed in order, as Excel does: at Excel's own XIRR rate the sheetjs
    formula_stress_test.xlsx's XNPV (Finance!B12, -6.211546860868111E-06) to the last bit."""
    total = 0.0
    for v, d in zip(vs, ds):
        total += v / (1 + r) ** ((d - ds[0]) / 365.0)
    return total


@register("XNPV", 3, 3, ("scalar", "range", "range"))
def _xnpv_fn(ctx, rate, values, dates):
    """A rate of 0 or less is #NUM! (Mac Excel 16, formulas__test.xlsx FINANCIAL!S56, U56,
    X56: -0.1, 0 and an empty cell); LibreOffice 7.4 (measured) refuses -1 or less only,
    with #VALUE!."""
    r = _rate_argument(rate, _excel(ctx))
    flows = _flows(values, dates, _excel(ctx))
    for x in (r, flows):
        if isinstance(x, ExcelError):
            return x
    if r <= (0 if _excel(ctx) else -1):
        return ExcelError.NUM if _excel(ctx) else ExcelError.VALUE
    return _safe(_xnpv, r, *flows)


@register("XIRR", 2, 3, ("range", "range", "scalar"))
def _xirr(ctx, values, dates, guess=0.1):
    excel = _excel(ctx)
    flows = _flows(values, dates, excel)
    g = _rate_argument(guess, excel)
    for x in ((g, flows) if excel else (flows, g)):  # Excel: the guess's error first
        if isinstance(x, ExcelError):
            return x
    r = _solve(lambda r: _xnpv(r, *flows), g)
    return ExcelError.NUM if r is None else c.result(r)


@register("SLN", 3, 3)
def _sln(ctx, cost, salvage, life):
    xs = _nums(cost, salvage, life)
    if isinstance(xs, ExcelError):
        return xs
    return ExcelError.DIV0 if xs[2] == 0 else c.result((xs[0] - xs[1]) / xs[2])


@register("DDB", 4, 5)
def _ddb(ctx, cost, salvage, life, period, factor=2.0):
    xs = _nums(cost, salvage, life, period, factor)
    if isinstance(xs, ExcelError):
        return xs
    cost, salvage, life, period, factor = xs
    if life <= 0 or period <= 0 or period > life or factor <= 0 or cost < 0 or salvage < 0:
        return ExcelError.NUM
    book, dep = cost, 0.0
    for _ in range(int(math.ceil(period))):
        dep = min(book * factor / life, max(book - salvage, 0.0))
        book -= dep
    return c.result(dep)


def _compounding(name, convert):
    """EFFECT and NOMINAL: ``convert(r, k)`` of a rate r > 0 compounded k >= 1 times a year."""
    def scalar(ctx, rate, n):
        xs = _nums(rate, n)
        if isinstance(xs, ExcelError):
            return xs
        r, k = xs[0], int(xs[1])
        return ExcelError.NUM if r <= 0 or k < 1 else _safe(lambda: convert(r, k))
    register(name, 2, 2)(scalar)


_compounding("EFFECT", lambda r, k: (1 + r / k) ** k - 1)
_compounding("NOMINAL", lambda r, k: k * ((1 + r) ** (1 / k) - 1))


@register("RRI", 3, 3)
def _rri(ctx, nper, pv, fv):
    """The equivalent interest rate for the growth of ``pv`` to ``fv`` in ``nper``
    periods: ``(fv/pv)^(1/nper) - 1``, computed as Excel does through exp and log (RRI(0.5,
    3, 4) is 0.7777777777777775 in Excel, one ulp under the power's); #NUM! for
    ``nper <= 0`` or ``pv = 0`` (ironcalc RRI.xlsx)."""
    xs = _nums(nper, pv, fv)
    if isinstance(xs, ExcelError):
        return xs
    n, p, f = xs
    if n <= 0 or p == 0:
        return ExcelError.NUM
    ratio = f / p
    if ratio == 0:
        return -1.0
    if ratio < 0:
        from workbook_gen.formula.functions.math.core import power
        root = power(ratio, 1 / n)
        return root if isinstance(root, ExcelError) else c.result(root - 1)
    return _safe(lambda: math.exp(math.log(ratio) / n) - 1)
