"""Dates read from text (DATEVALUE, VALUE, date arguments given as text), as serial
numbers in the workbook's date system (:mod:`.serials`); TEXT's date formats are in
:mod:`.numfmt.dates`."""

from __future__ import annotations

import calendar
import datetime as dt
import re

from workbook_gen.formula.functions.serials import is_1904, to_serial
from workbook_gen.xlerror import ExcelError


def _to_serial(d: dt.date) -> float | ExcelError:
    """The day's serial in the workbook's date system; #VALUE! before its first day."""
    x = to_serial(d)
    return x if x >= 0 else ExcelError.VALUE


def _feb29_1900(time: float) -> float | ExcelError:
    """1900-02-29, the day Excel counts (serial 60), in the 1900 system only."""
    return ExcelError.VALUE if is_1904() else 60.0 + time


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
        return _feb29_1900(time)
    try:
        d = dt.date(year, int(month), day)
    except ValueError:
        if "m" not in parts or "d" not in parts or int(month) <= 12:
            return ExcelError.VALUE
        try:  # "29/02/1900": day first, as a European Excel reads it
            if (year, day, int(month)) == (1900, 2, 29):
                return _feb29_1900(time)
            d = dt.date(year, day, int(month))
        except ValueError:
            return ExcelError.VALUE
    serial = _to_serial(d)
    return serial if isinstance(serial, ExcelError) else serial + time
