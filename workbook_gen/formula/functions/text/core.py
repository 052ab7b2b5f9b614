"""Text: LEN, LEFT, RIGHT, MID, UPPER, LOWER, PROPER, TRIM, CONCATENATE, CONCAT, TEXTJOIN,
TEXT (common formats), VALUE, FIND, SEARCH, SUBSTITUTE, REPLACE, REPT, EXACT, CHAR, CODE,
FIXED, DOLLAR-free number formatting, T."""

from __future__ import annotations

import math
import re

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.numfmt import fixed_digits, format_value
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError


def _texts(*vs):
    out = [c.to_text(v) for v in vs]
    bad = next((t for t in out if isinstance(t, ExcelError)), None)
    return bad if bad is not None else out


_ABSENT = object()  # an argument not given at all (an empty cell given is 0)


def _count(v, default=0):
    """An integer argument (truncated); ``default`` when it is not given, 0 for an empty
    cell (formulas test.xlsx: LEFT("ciao",H21) with H21 empty is "", FIND(..,..,H17) #VALUE!)."""
    if v is _ABSENT:
        return default
    if v is None:
        return 0
    x = c.to_number(v)
    return x if isinstance(x, ExcelError) else int(x)


@register("LEN", 1, 1)
def _len(ctx, v):
    t = c.to_text(v)
    return t if isinstance(t, ExcelError) else float(len(t))


def _side(take_left: bool):
    def fn(ctx, v, n=_ABSENT):
        t, k = c.to_text(v), _count(n, 1)
        for x in (t, k):
            if isinstance(x, ExcelError):
                return x
        if k < 0 or (_libreoffice(ctx) and n not in (_ABSENT, None)
                     and c.to_number(n) < 0):  # LibreOffice: -0.5 too (measured)
            return ExcelError.VALUE
        return t[:k] if take_left else (t[max(len(t) - k, 0):] if k else "")
    return fn


register("LEFT", 1, 2)(_side(True))
register("RIGHT", 1, 2)(_side(False))


@register("MID", 3, 3)
def _mid(ctx, v, start, n):
    t, s, k = c.to_text(v), _count(start), _count(n)
    for x in (t, s, k):
        if isinstance(x, ExcelError):
            return x
    if s < 1 or k < 0:
        return ExcelError.VALUE
    return t[s - 1:s - 1 + k]


def _map(name, fn):
    def scalar(ctx, v):
        t = c.to_text(v)
        return t if isinstance(t, ExcelError) else fn(t)
    register(name, 1, 1)(scalar)


_map("UPPER", str.upper)
_map("LOWER", str.lower)
_map("PROPER", lambda t: re.sub(r"[A-Za-z]+", lambda m: m.group(0).capitalize(), t))
_map("TRIM", lambda t: re.sub(" +", " ", t).strip(" "))
_map("CLEAN", lambda t: "".join(ch for ch in t if ord(ch) >= 32))


@register("CONCATENATE", 1, -1)
def _concatenate(ctx, *args):
    ts = _texts(*args)
    return ts if isinstance(ts, ExcelError) else "".join(ts)


def _flat_texts(args, ctx):
    lo = ctx.dialect == "libreoffice"  # a boolean in a range is a number there
    out = []
    for a in args:
        for v in (c.flat(a) if isinstance(a, Range) else [a]):
            t = c.to_text(float(v) if lo and isinstance(v, bool) else v)
            if isinstance(t, ExcelError):
                return t
            out.append(t)
    return out


@register("CONCAT", 1, -1, "range")
def _concat(ctx, *args):
    ts = _flat_texts(args, ctx)
    return ts if isinstance(ts, ExcelError) else "".join(ts)


@register("TEXTJOIN", 3, -1, ("scalar", "scalar", "range"))
def _textjoin(ctx, delim, ignore_empty, *args):
    d = c.to_text(delim)
    skip = c.to_bool(ignore_empty)
    for x in (d, skip):
        if isinstance(x, ExcelError):
            return x
    ts = _flat_texts(args, ctx)
    if isinstance(ts, ExcelError):
        return ts
    return d.join(t for t in ts if t or not skip)


@register("REPT", 2, 2)
def _rept(ctx, v, n):
    t, k = c.to_text(v), _count(n)
    for x in (t, k):
        if isinstance(x, ExcelError):
            return x
    if k < 0 or len(t) * k > 32767:
        return ExcelError.VALUE
    return t * k


@register("EXACT", 2, 2)
def _exact(ctx, a, b):
    ts = _texts(a, b)
    return ts if isinstance(ts, ExcelError) else ts[0] == ts[1]


def _libreoffice(ctx) -> bool:
    return getattr(ctx, "dialect", ctx) == "libreoffice"


def _find(case: bool):
    def fn(ctx, needle, hay, start=_ABSENT):
        ts = _texts(needle, hay)
        s = _count(start, 1)
        if isinstance(ts, ExcelError):
            return ts
        if isinstance(s, ExcelError):
            return s
        n, h = ts
        # Microsoft: a start past the text's length is #VALUE! (SEARCH("*","") too; an
        # empty find_text matches at the start, even just past the end)
        if s < 1 or s > len(h) + 1 or (not n and _libreoffice(ctx)) or (n and s > len(h)):
            return ExcelError.VALUE
        if case:
            i = h.find(n, s - 1)
        else:
            m = (c.wildcard(n).pattern if c.has_wildcard(n) else re.escape(n))
            hit = re.compile(m, re.IGNORECASE | re.DOTALL).search(h, s - 1)
            i = -1 if hit is None else hit.start()
        return ExcelError.VALUE if i < 0 else float(i + 1)
    return fn


register("FIND", 2, 3)(_find(True))
register("SEARCH", 2, 3)(_find(False))


@register("SUBSTITUTE", 3, 4)
def _substitute(ctx, v, old, new, which=None):
    ts = _texts(v, old, new)
    if isinstance(ts, ExcelError):
        return ts
    t, o, n = ts
    if not o and (which is None or not _libreoffice(ctx)):
        return t
    if which is None:
        return t.replace(o, n)
    k = _count(which)
    if isinstance(k, ExcelError):
        return k
    if k < 1:
        return ExcelError.VALUE
    if not o:  # (LibreOffice checks the instance first)
        return t
    i = -1
    for _ in range(k):
        i = t.find(o, i + 1)
        if i < 0:
            return t
    return t[:i] + n + t[i + len(o):]


@register("REPLACE", 4, 4)
def _replace(ctx, v, start, n, new):
    ts = _texts(v, new)
    s, k = _count(start), _count(n)
    for x in (ts, s, k):
        if isinstance(x, ExcelError):
            return x
    if s < 1 or k < 0:
        return ExcelError.VALUE
    t, r = ts
    return t[:s - 1] + r + t[s - 1 + k:]


def _charset(ctx) -> str:
    """Microsoft's CHAR page: the character set of the operating environment, Windows' ANSI
    (cp1252) or the Macintosh character set (Excel for Mac: the Excel-saved sheetjs
    formula_stress_test.xlsx caches CHAR(240) as U+F8FF and CODE of it as 240)."""
    return "cp1252" if ctx is None else ctx.workbook.charset()


@register("CHAR", 1, 1)
def _char(ctx, v):
    k = _count(v)
    if isinstance(k, ExcelError):
        return k
    if not 1 <= k <= 255:
        return ExcelError.VALUE
    return bytes([k]).decode(_charset(ctx), errors="replace")


@register("CODE", 1, 1)
def _code(ctx, v):
    t = c.to_text(v)
    if isinstance(t, ExcelError):
        return t
    if not t:
        return 0.0 if _libreoffice(ctx) else ExcelError.VALUE
    try:
        return float(t[0].encode(_charset(ctx))[0])
    except UnicodeEncodeError:
        return 63.0


@register("VALUE", 1, 1)
def _value(ctx, v):
    if isinstance(v, ExcelError) or c.is_number(v):
        return v
    if v is None:
        return 0.0
    if isinstance(v, bool):
        return ExcelError.VALUE
    from workbook_gen.formula.functions.date.core import parse_date_text
    t = v.strip()
    if t[:1] == "$" or t[:2] in ("-$", "+$"):  # a currency sign, as Excel's VALUE("$1,000")
        t = t.replace("$", "", 1)
    x = c.text_to_number(t.replace(",", "") if re.fullmatch(
        r"[\s\-+]*\d{1,3}(,\d{3})+(\.\d*)?\s*", t) else t)
    if isinstance(x, ExcelError):
        x = parse_date_text(v)
    return x


# -- TEXT and FIXED ----------------------------------------------------------------------

def _round_half_up(x: float, d: int) -> float:
    from workbook_gen.formula.functions.math.core import round_digits
    from decimal import ROUND_HALF_UP
    return round_digits(x, d, ROUND_HALF_UP)


def _group(digits: str) -> str:
    out = []
    while len(digits) > 3:
        out.insert(0, digits[-3:])
        digits = digits[:-3]
    out.insert(0, digits)
    return ",".join(out)


def format_number(x: float, decimals: int, grouping: bool) -> str:
    """``x`` with ``decimals`` places (half away from zero) and optional thousands commas."""
    r = _round_half_up(x, decimals)
    text = fixed_digits(abs(r), max(decimals, 0))
    whole, _, frac = text.partition(".")
    if grouping:
        whole = _group(whole)
    body = whole + ("." + frac if frac else "")
    return ("-" if r < 0 else "") + body


@register("TEXT", 2, 2)
def _text(ctx, v, fmt):
    f = c.to_text(fmt)
    if isinstance(f, ExcelError):
        return f
    if isinstance(v, (ExcelError, bool)):  # TEXT(TRUE,...) is "TRUE" (pycel's text.xlsx)
        return c.to_text(v)
    if isinstance(v, str):
        x = c.text_to_number(v)
        if isinstance(x, ExcelError):  # text: the format's text section, if any
            return format_value(v, f)
        v = x
    return format_value(c.to_number(v), f)


@register("FIXED", 1, 3)
def _fixed(ctx, v, decimals=2.0, no_commas=False):
    x, d, nc = c.to_number(v), _count(decimals, 2), c.to_bool(no_commas)
    for y in (x, d, nc):
        if isinstance(y, ExcelError):
            return y
    if d > 127:
        return ExcelError.VALUE
    return format_number(x, d, not nc) if d >= 0 else format_number(
        _round_half_up(x, d), 0, not nc)


@register("NUMBERVALUE", 1, 3)
def _numbervalue(ctx, v, dec=".", group=_ABSENT):
    """Spaces ignored; the separators' first characters; a separator given as an empty
    cell is #VALUE!; the group separator after the decimal one, the decimal one twice, or
    the two the same, is #VALUE! (Microsoft); without a group separator, "," unless the
    decimal one is "," ("." then); a number in parentheses is negative, with percent signs
    inside and after them (Mac Excel 16, formulas__test.xlsx TEXT!R27:W28: "(2.500,27)"
    with "," and "." is -2500.27, "(2,500.27%)%" -0.250027, "(2500,27E+6%)%" with ","
    -250027)."""
    excel = ctx.dialect == "excel"
    if excel and (dec is None or group is None):
        return ExcelError.VALUE
    if group is _ABSENT:
        group = "." if excel and isinstance(dec, str) and dec[:1] == "," else ","
    ts = _texts(v, dec, group)
    if isinstance(ts, ExcelError):
        return ts
    t, d, g = ts
    t = "".join(t.split())
    if excel and d and g:
        if d[0] == g[0]:
            return ExcelError.VALUE  # formulas__test.xlsx TEXT!T27
        first = t.find(d[0])
        if first >= 0 and (t.find(d[0], first + 1) >= 0 or g[0] in t[first + 1:]):
            return ExcelError.VALUE
    if g:
        t = t.replace(g[0], "")
    if d and d[0] != ".":
        t = t.replace(d[0], ".")
    if excel and t.rstrip("%").startswith("(") and t.rstrip("%").endswith(")"):
        outer = len(t) - len(t.rstrip("%"))
        inner = t.rstrip("%")[1:-1]
        percent = outer + len(inner) - len(inner.rstrip("%"))
        inner = inner.rstrip("%")
        if not _PLAIN_NUMBER.fullmatch(inner):
            return ExcelError.VALUE
        return c.result(-float(inner) / 100.0 ** percent)
    return c.text_to_number(t) if t else 0.0


_PLAIN_NUMBER = re.compile(r"(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")


@register("UNICHAR", 1, 1)
def _unichar(ctx, v):
    k = _count(v)
    if isinstance(k, ExcelError):
        return k
    return chr(k) if 1 <= k <= 0x10FFFF else ExcelError.VALUE


@register("UNICODE", 1, 1)
def _unicode(ctx, v):
    t = c.to_text(v)
    if isinstance(t, ExcelError):
        return t
    return float(ord(t[0])) if t else ExcelError.VALUE


@register("DOLLAR", 1, 2)
def _dollar(ctx, v, decimals=2.0):
    x, d = c.to_number(v), _count(decimals, 2)
    for y in (x, d):
        if isinstance(y, ExcelError):
            return y
    body = format_number(abs(x), max(d, 0), True)
    return f"(${body})" if x < 0 and not math.isclose(x, 0) else f"${body}"


@register("T", 1, 1, "range")
def _t(ctx, v):
    """A reference gives its first cell, not the implicit intersection (POI
    FormulaEvalTestData: T(J1351:J1353) in row 1352 is "" from the empty J1351)."""
    if isinstance(v, Range) and ctx.dialect == "libreoffice":
        v = ctx.scalar(v)  # LibreOffice 7.4 intersects (#VALUE! outside the range)
    elif isinstance(v, Range):
        v = v.rows[0][0] if v.rows and v.rows[0] else None
    return v if isinstance(v, (str, ExcelError)) else ""
