"""Dates as text: reading (DATEVALUE, VALUE, date arguments given as text) and TEXT's
date and time formats. Serial numbers as in :mod:`.date`."""

from __future__ import annotations

import calendar
import datetime as dt
import math
import re

from workbook_gen.xlerror import ExcelError

_EPOCH = dt.date(1899, 12, 30)


def _to_serial(d: dt.date) -> float:
    n = (d - _EPOCH).days
    return float(n if n >= 61 else n - 1)


_MONTHS = {m.lower(): i for i, m in enumerate(calendar.month_abbr) if m}
_MONTHS.update({m.lower(): i for i, m in enumerate(calendar.month_name) if m})


_TIME = re.compile(r"(\d+):(\d+)(?::(\d+))?(\.\d*)?\s*([AaPp][Mm])?")
_LIMIT = 10_000  # a time field read from text is below this; the others within 23:59


def _time_part(text: str) -> float | None:
    """A time as text: h:m, h:m:s(.f) or m:s.f (two fields with decimals are minutes and
    seconds). The first or the last field may run over (up to 9999) when the others are
    within a clock's range: "23:9999", "0:0:9999", "59:9999.0" read, "24:99", "23:60:9999",
    "23:10000" do not (pycel's text.xlsx, saved by Excel); a lone trailing dot is ignored."""
    m = _TIME.fullmatch(text.strip())
    if m is None:
        return None
    a, b = int(m.group(1)), int(m.group(2))
    frac = m.group(4) or ""
    if m.group(3) is not None:
        h, mi, s = a, b, float(m.group(3) + frac.rstrip(".") if frac != "." else m.group(3))
        ok = mi <= 59 and ((s < 60 and h < _LIMIT) or (h <= 23 and s < _LIMIT))
    elif len(frac) > 1:  # m:s.f
        h, mi, s = 0, a, float(m.group(2) + frac)
        ok = (s < 60 and mi < _LIMIT) or (mi <= 59 and s < _LIMIT)
    else:
        h, mi, s = a, b, 0.0
        ok = (mi <= 59 and h < _LIMIT) or (h <= 23 and mi < _LIMIT)
    if not ok:
        return None
    if m.group(5):
        if h > 12:
            return None
        h = h % 12 + (12 if m.group(5).lower() == "pm" else 0)
    return (h * 3600 + mi * 60 + s) / 86400.0


def parse_date_text(text: str) -> float | ExcelError:
    """DATEVALUE-style reading: ISO ``2020-01-31``, US ``1/31/2020``, ``31-Jan-2020``,
    ``Jan 31, 2020``, optionally followed by a time; a time alone is a fraction."""
    t = text.strip()
    frac = _time_part(t)
    if frac is not None:
        return frac
    time = 0.0
    m = re.fullmatch(r"(.*?)\s+(\d{1,2}:\d{2}(?::\d{2}(?:\.\d*)?)?\s*(?:[AaPp][Mm])?)", t)
    if m:
        t, time = m.group(1), _time_part(m.group(2)) or 0.0
    parts = None
    for pattern, order in ((r"(\d{4})-(\d{1,2})-(\d{1,2})", "ymd"),
                           (r"(\d{4})/(\d{1,2})/(\d{1,2})", "ymd"),
                           (r"(\d{1,2})/(\d{1,2})/(\d{2,4})", "mdy"),
                           (r"(\d{1,2})[- ]([A-Za-z]+)[- ,]+(\d{2,4})", "dMy"),
                           (r"([A-Za-z]+)[- ](\d{1,2}),?[- ](\d{2,4})", "Mdy")):
        mm = re.fullmatch(pattern, t)
        if mm:
            parts = dict(zip(order, mm.groups()))
            break
    if parts is None:
        return ExcelError.VALUE
    month = parts.get("m") or _MONTHS.get(parts.get("M", "").lower())
    if not month:
        return ExcelError.VALUE
    year = int(parts["y"])
    if year < 100:
        year += 2000 if year < 30 else 1900
    day = int(parts["d"])
    if (year, int(month), day) == (1900, 2, 29):  # the day Excel counts, serial 60
        return 60.0 + time
    try:
        d = dt.date(year, int(month), day)
    except ValueError:
        if "m" not in parts or "d" not in parts or int(month) <= 12:
            return ExcelError.VALUE
        try:  # "29/02/1900": day first, as a European Excel reads it
            if (year, day, int(month)) == (1900, 2, 29):
                return 60.0 + time
            d = dt.date(year, day, int(month))
        except ValueError:
            return ExcelError.VALUE
    return _to_serial(d) + time


# -- TEXT's date formats ------------------------------------------------------------------

_DATE_TOKENS = re.compile(r"\[h+\]|\[m+\]|\[s+\]|(?<=s)\.0+|(?<=\])\.0+|y+|e+|m+|d+|"
                          r"h+|s+|am/pm|a/p|\"[^\"]*\"|.", re.IGNORECASE)
FRACTION = re.compile(r"(?<=[sS\]])\.0+")  # fractional seconds: "ss.000", "[ss].00"


def _code(tok: str) -> str:
    """Runs of a code longer than its forms read as the longest (yyy, ddddd, hhh, sss) or
    shortest (y) form; mmmmm is the month's initial (formulas test.xlsx EXTRA!A37:A42)."""
    low = tok.lower()
    if not low or low[0] not in "ydhsm" or low.strip(low[0]):
        return tok
    n, k = len(low), low[0]
    if k == "y":
        return "yy" if n <= 2 else "yyyy"
    if k == "d":
        return tok if n <= 4 else "dddd"
    if k in "hs":
        return tok if n <= 2 else k * 2
    return tok if n <= 5 else "mmmm"


def format_date(x: float, fmt: str) -> str | ExcelError:
    """TEXT's date and time formats. The value is first rounded to the format's smallest
    unit (a second, or 1/10^k s with "ss.000"), carrying into the day as Excel does
    (0.999999 as "dd hh:mm:ss" is 01 00:00:00); elapsed [h], [m], [s]; weekdays counted
    from serial 1, a Sunday (serial 0 is "Saturday, 0 January 1900"); sheetjs
    issue2717.xlsx, saved by Excel."""
    from workbook_gen.formula.functions.date import from_serial
    if x < 0:
        return ExcelError.VALUE
    tokens = [_code(t) for t in _DATE_TOKENS.findall(fmt)]
    digits = max((len(t) - 1 for t in tokens if t.startswith(".")), default=0)
    scale = 10 ** digits
    units = math.floor(x * 86400 * scale + 0.5)
    day, rest = divmod(units, 86400 * scale)
    secs, part = divmod(rest, scale)
    ymd = from_serial(day)
    if isinstance(ymd, ExcelError):  # past 9999-12-31: elapsed counts only ([h] of 2958466)
        if any(t[:1].lower() in "ymdhe" or t.lower() in ("am/pm", "a/p") for t in tokens
               if not t.startswith(("[", '"', ".")) and len(t) > 0 and t[0].isalpha()
               and t.lower() not in ("m", "mm", "s", "ss")):
            return ExcelError.VALUE
        ymd = (9999, 12, 31)  # not shown
    y, m, d = ymd
    wd = (day + 5) % 7  # Monday 0 ... Sunday 6
    hh, mi, ss = secs // 3600, secs // 60 % 60, secs % 60
    ampm = any(t.lower() in ("am/pm", "a/p") for t in tokens)
    elapsed = next((t.lower()[1] for t in tokens if t.startswith("[")), None)
    out = []
    for i, tok in enumerate(tokens):
        low = tok.lower()
        prev = next((t.lower().strip("[]") for t in reversed(tokens[:i]) if t[-1:].isalpha() or
                     t.endswith("]")), "")
        nxt = next((t.lower().strip("[]") for t in tokens[i + 1:] if t[:1].isalpha() or
                    t.startswith("[")), "")
        minute = low in ("m", "mm") and (prev.startswith("h") or nxt.startswith("s"))
        if low.startswith("["):
            total = {"h": units // (3600 * scale), "m": units // (60 * scale),
                     "s": units // scale}[low[1]]
            out.append(str(total).zfill(len(low) - 2))
        elif low.startswith("."):
            out.append("." + str(part).zfill(digits)[:len(low) - 1])
        elif low == "yyyy":
            out.append(f"{y:04d}")
        elif low == "yy":
            out.append(f"{y % 100:02d}")
        elif low.startswith("e"):  # the era's year: the year in the Gregorian calendar
            out.append(str(y))  # (sheetjs formula_stress_test.xlsx Text!B15, "ee-mm-dd")
        elif minute:
            mm = mi if elapsed != "h" else mi
            out.append(f"{mm:02d}" if low == "mm" else str(mm))
        elif low == "mmmmm":
            out.append(calendar.month_name[m][:1])
        elif low == "mmmm":
            out.append(calendar.month_name[m])
        elif low == "mmm":
            out.append(calendar.month_abbr[m])
        elif low == "mm":
            out.append(f"{m:02d}")
        elif low == "m":
            out.append(str(m))
        elif low == "dddd":
            out.append(calendar.day_name[wd])
        elif low == "ddd":
            out.append(calendar.day_abbr[wd])
        elif low == "dd":
            out.append(f"{d:02d}")
        elif low == "d":
            out.append(str(d))
        elif low in ("hh", "h"):
            h = (hh % 12 or 12) if ampm else hh
            out.append(f"{h:02d}" if low == "hh" else str(h))
        elif low in ("ss", "s"):
            out.append(f"{ss:02d}" if low == "ss" else str(ss))
        elif low == "am/pm":
            out.append("AM" if hh < 12 else "PM")
        elif low == "a/p":
            out.append("A" if hh < 12 else "P")
        elif tok.startswith('"'):
            out.append(tok[1:-1])
        elif tok == "\\":
            continue
        else:
            out.append(tok)
    return "".join(out)
