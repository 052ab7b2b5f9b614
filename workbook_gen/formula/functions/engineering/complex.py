"""Complex numbers as Excel writes them, text like "3+4i" or "-2.5j": COMPLEX and the IM*
family. A complex argument is such text (suffix i or j, "i" alone is 1i) or a real
number; unreadable text is #NUM!, a boolean #VALUE!, suffixes i and j mixed #NUM! (#VALUE!
in IMSUM and IMPRODUCT); an empty cell is 0.
Results are written with 15 significant digits (Excel's number-to-text); powers, roots
and logarithms go through the polar form as Excel does."""

from __future__ import annotations

import math
import re

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

_NUM = r"(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"
_FORM = re.compile(rf"^(?P<re>[+-]?{_NUM})?(?:(?P<im>[+-]?(?:{_NUM})?)(?P<sfx>[ij]))?$")


def parse(v) -> tuple[complex, str | None] | ExcelError:
    """(value, suffix) of a complex argument (suffix None for a real)."""
    if isinstance(v, ExcelError):
        return v
    if isinstance(v, bool):
        return ExcelError.VALUE
    if v is None or v == "":
        return complex(0), None
    if isinstance(v, (int, float)):
        return complex(float(v)), None
    m = _FORM.match(v)
    if m is None or (m.group("re") is None and m.group("sfx") is None):
        return ExcelError.NUM
    real = float(m.group("re")) if m.group("re") else 0.0
    if m.group("sfx") is None:
        return complex(real), None
    im = m.group("im")
    if m.group("re") is not None and im == "":
        return complex(0, real), m.group("sfx")  # "3i": the number is the imaginary part
    imag = {"": 1.0, "+": 1.0, "-": -1.0}.get(im)
    imag = float(im) if imag is None else imag
    return complex(real, imag), m.group("sfx")


def _part(x: float) -> str:
    """15 significant digits; from 1E-05 to 1 written out in full as Excel writes the
    parts (formulas test.xlsx: "0.0000692442674613868-1.00005873951153j"), smaller in
    E notation ("3.82126757337684E-22-j")."""
    if 1e-5 <= abs(x) < 1:
        digits = 15 - 1 - math.floor(math.log10(abs(x)))
        return f"{x:.{digits}f}".rstrip("0").rstrip(".")
    return c.number_to_text(x)


def write(z: complex, sfx: str = "i") -> str | ExcelError:
    re_, im = z.real, z.imag
    if not (math.isfinite(re_) and math.isfinite(im)):
        return ExcelError.NUM
    re_, im = float(f"{re_:.15g}"), float(f"{im:.15g}")
    if im == 0:
        return _part(re_)
    coef = "" if im == 1 else "-" if im == -1 else _part(im)
    if re_ == 0:
        return coef + sfx
    return _part(re_) + ("+" if im > 0 else "") + coef + sfx


def _suffix(*sfxs, mixed=ExcelError.NUM):
    """The suffix of a result; ``mixed`` if "i" and "j" are mixed: #NUM! for the
    two-argument functions (formulas test.xlsx ENGINEERING!T51, IMSUB), #VALUE! for
    IMSUM and IMPRODUCT (S52, T44)."""
    got = {s for s in sfxs if s is not None}
    if len(got) > 1:
        return mixed
    return got.pop() if got else "i"


@register("COMPLEX", 2, 3)
def _complex(ctx, real, imag, suffix="i"):
    if isinstance(real, bool) or isinstance(imag, bool):
        return ExcelError.VALUE  # an Analysis ToolPak function: no booleans
    a, b = c.to_number(real), c.to_number(imag)
    s = "i" if suffix is None else c.to_text(suffix)
    for x in (a, b, s):
        if isinstance(x, ExcelError):
            return x
    s = s or "i"
    if s not in ("i", "j"):
        return ExcelError.VALUE
    return write(complex(a, b), s)


def _unary(name, fn, out="complex"):
    def scalar(ctx, v):
        got = parse(v)
        if isinstance(got, ExcelError):
            return got
        z, sfx = got
        try:
            r = fn(z)
        except (ZeroDivisionError, ValueError, OverflowError):
            return ExcelError.NUM
        if isinstance(r, ExcelError):
            return r
        if out == "number":
            return c.result(float(r))
        return write(r, sfx or "i")
    register(name, 1, 1)(scalar)


def _polar_pow(z: complex, n: float) -> complex:
    r, t = abs(z), math.atan2(z.imag, z.real)
    if r == 0:
        if n <= 0:
            raise ValueError
        return complex(0)
    rn = r ** n
    return complex(rn * math.cos(n * t), rn * math.sin(n * t))


def _ln(z: complex) -> complex:
    if z == 0:
        raise ValueError
    return complex(math.log(abs(z)), math.atan2(z.imag, z.real))


def _arg(z: complex):
    return ExcelError.DIV0 if z == 0 else math.atan2(z.imag, z.real)


def _exp(z: complex) -> complex:
    e = math.exp(z.real)
    return complex(e * math.cos(z.imag), e * math.sin(z.imag))


def _sin(z):
    return complex(math.sin(z.real) * math.cosh(z.imag), math.cos(z.real) * math.sinh(z.imag))


def _cos(z):
    return complex(math.cos(z.real) * math.cosh(z.imag), -math.sin(z.real) * math.sinh(z.imag))


def _sinh(z):
    return complex(math.sinh(z.real) * math.cos(z.imag), math.cosh(z.real) * math.sin(z.imag))


def _cosh(z):
    return complex(math.cosh(z.real) * math.cos(z.imag), math.sinh(z.real) * math.sin(z.imag))


_unary("IMABS", abs, "number")
_unary("IMREAL", lambda z: z.real, "number")
_unary("IMAGINARY", lambda z: z.imag, "number")
_unary("IMARGUMENT", _arg, "number")
_unary("IMCONJUGATE", lambda z: z.conjugate())
_unary("IMSQRT", lambda z: _polar_pow(z, 0.5))
_unary("IMLN", _ln)
_unary("IMLOG10", lambda z: _ln(z) / math.log(10))
_unary("IMLOG2", lambda z: _ln(z) / math.log(2))
_unary("IMEXP", _exp)
_unary("IMSIN", _sin)
_unary("IMCOS", _cos)
# tan, cot, sec, csc by the double-angle forms, whose digits are Excel's (formulas
# test.xlsx: IMTAN("3.1+2j"), IMCOT("7+25j") = "3.82126757337684E-22-j")
def _tan(z):
    a, b = z.real, z.imag
    den = math.cos(2 * a) + math.cosh(2 * b)
    return complex(math.sin(2 * a) / den, math.sinh(2 * b) / den)


def _cot(z):
    a, b = z.real, z.imag
    if b == 0:  # a real argument: cos/sin, whole for a tiny one (IMCOT(1e-16) is 1e+16
        return complex(math.cos(a) / math.sin(a), 0.0)  # in the Excel-saved ironcalc COMPLEXs)
    den = math.cosh(2 * b) - math.cos(2 * a)
    return complex(math.sin(2 * a) / den, -math.sinh(2 * b) / den)


def _sec(z):
    a, b = z.real, z.imag
    den = math.cosh(2 * b) + math.cos(2 * a)
    return complex(2 * math.cos(a) * math.cosh(b) / den, 2 * math.sin(a) * math.sinh(b) / den)


def _csc(z):
    a, b = z.real, z.imag
    if b == 0:  # as _cot
        return complex(1.0 / math.sin(a), 0.0)
    den = math.cosh(2 * b) - math.cos(2 * a)
    return complex(2 * math.sin(a) * math.cosh(b) / den, -2 * math.cos(a) * math.sinh(b) / den)


_unary("IMTAN", _tan)
_unary("IMCOT", _cot)
_unary("IMSEC", _sec)
_unary("IMCSC", _csc)
_unary("IMSINH", _sinh)
_unary("IMCOSH", _cosh)
_unary("IMSECH", lambda z: 1 / _cosh(z))
_unary("IMCSCH", lambda z: 1 / _sinh(z))


@register("IMPOWER", 2, 2)
def _impower(ctx, v, n):
    got, k = parse(v), c.to_number(n)
    for x in (got, k):
        if isinstance(x, ExcelError):
            return x
    z, sfx = got
    try:
        return write(_polar_pow(z, k), sfx or "i")
    except (ValueError, OverflowError, ZeroDivisionError):
        return ExcelError.NUM


def _two(fn):
    def scalar(ctx, a, b):
        x, y = parse(a), parse(b)
        for v in (x, y):
            if isinstance(v, ExcelError):
                return v
        s = _suffix(x[1], y[1])
        if isinstance(s, ExcelError):
            return s
        try:
            return write(fn(x[0], y[0]), s)
        except (ZeroDivisionError, ValueError, OverflowError):
            return ExcelError.NUM
    return scalar


register("IMSUB", 2, 2)(_two(lambda a, b: a - b))
register("IMDIV", 2, 2)(_two(lambda a, b: a / b))


def _many(fn, start):
    def scalar(ctx, *args):
        acc, sfxs = start, []
        for a in args:
            for v in (c.flat(a) if isinstance(a, Range) else [a]):
                got = parse(v)
                if isinstance(got, ExcelError):
                    return got
                acc = fn(acc, got[0])
                sfxs.append(got[1])
        s = _suffix(*sfxs, mixed=ExcelError.VALUE)
        return s if isinstance(s, ExcelError) else write(acc, s)
    return scalar


register("IMSUM", 1, -1, "range")(_many(lambda a, b: a + b, complex(0)))
register("IMPRODUCT", 1, -1, "range")(_many(lambda a, b: a * b, complex(1)))
