"""TEXT's date and time patterns.

The value is first rounded to the pattern's smallest unit (a second, or 1/10^k s with
``ss.000``), carrying into the day as Excel does (0.999999 as ``dd hh:mm:ss`` is 01
00:00:00). Codes are read case-insensitively (``D-M-Y``, ``H:M:S``); ``m`` is minutes
right after an hour or before a second, else the month; runs longer than a code's forms
read as the longest (``yyy``, ``ddddd``, ``hhh``) or shortest (``y``) form; ``mmmmm`` is
the month's initial. Elapsed counts ``[h]``, ``[mm]``, ``[ss]``; ``AM/PM`` prints AM or PM,
``A/P`` prints A or P and ``a/p`` a or p, as written; the hours then count 1 to 12.
Weekdays and dates come from :mod:`..serials` (the workbook's 1900 or 1904 system; in
the 1900 one serial 0 is "Saturday, 0 January 1900"). Literals as in numbers: quoted
text, ``\\x``, ``_x`` (a space), ``*x`` (nothing), colours and locales (nothing) or
currencies (their symbol).

Measured on sheetjs issue2717.xlsx, NPOI's DateFormatTests.xlsx (a 1904 workbook) and
formulas' test.xlsx (EXTRA!A37:A43), saved by Excel.
"""

from __future__ import annotations

import calendar
import functools
import math
import re

from workbook_gen.formula.functions.numfmt.tokens import literal
from workbook_gen.formula.functions.serials import from_serial, weekday
from workbook_gen.xlerror import ExcelError

_TOKENS = re.compile(r'\[h+\]|\[m+\]|\[s+\]|\[[^\]]*\]|"[^"]*"?|\\.|[*_].|(?<=s)\.0+|'
                     r"(?<=\])\.0+|y+|e+|m+|d+|h+|s+|am/pm|a/p|.", re.I | re.S)
FRACTION = re.compile(r"(?<=[sS\]])\.0+")  # fractional seconds: "ss.000", "[ss].00"
_ELAPSED = re.compile(r"\[(h+|m+|s+)\]", re.I)


class _Literal(str):
    """A token printed as it is (quoted text, an escape, a bracket that is no count)."""


def _code(tok: str) -> str:
    """Runs of a code longer than its forms read as the longest (yyy, ddddd, hhh, sss) or
    shortest (y) form; mmmmm is the month's initial (formulas test.xlsx EXTRA!A37:A42)."""
    if tok[:1] in ('"', "\\", "*", "_") or (tok.startswith("[")
                                            and not _ELAPSED.fullmatch(tok)):
        return _Literal(literal(tok))
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


def _is_code(t: str) -> bool:
    return not isinstance(t, _Literal) and (t[-1:].isalpha() or t.endswith("]"))


def _minute(tokens: list[str], i: int) -> bool:
    """``m``/``mm`` at ``i`` is minutes: after an hour or before a second."""
    prev = next((t.lower().strip("[]") for t in reversed(tokens[:i]) if _is_code(t)), "")
    nxt = next((t.lower().strip("[]") for t in tokens[i + 1:] if _is_code(t)), "")
    return prev.startswith("h") or nxt.startswith("s")


def _needs_date(tokens: list[str]) -> bool:
    """A calendar code (past 9999-12-31 only elapsed counts and clock codes can show)."""
    return any(t[:1].lower() in "ymdhe" or t.lower() in ("am/pm", "a/p") for t in tokens
               if not isinstance(t, _Literal) and not t.startswith(("[", "."))
               and t[:1].isalpha() and t.lower() not in ("m", "mm", "s", "ss"))


def format_date(x: float, fmt: str) -> str | ExcelError:
    """TEXT(x, fmt) for a date or time pattern ``fmt`` and ``x`` >= 0."""
    if x < 0:
        return ExcelError.VALUE
    tokens, minutes, digits, needs_date, ampm = _parse(fmt)
    scale = 10 ** digits
    units = math.floor(x * 86400 * scale + 0.5)
    day, rest = divmod(units, 86400 * scale)
    secs, part = divmod(rest, scale)
    ymd = from_serial(day)
    if isinstance(ymd, ExcelError):  # past 9999-12-31: elapsed counts only ([h] of 2958466)
        if needs_date:
            return ExcelError.VALUE
        ymd = (9999, 12, 31)  # not shown
    clock = {"y": ymd[0], "m": ymd[1], "d": ymd[2], "wd": weekday(day), "hh": secs // 3600,
             "mi": secs // 60 % 60, "ss": secs % 60, "part": part, "digits": digits,
             "units": units, "scale": scale, "ampm": ampm}
    return "".join(_show(tok, i in minutes, clock) for i, tok in enumerate(tokens))


@functools.lru_cache(maxsize=512)
def _parse(fmt: str):
    """(tokens, indices of the m/mm that are minutes, fractional-second digits, whether
    a calendar code shows, whether AM/PM or A/P shows) of a date pattern."""
    tokens = tuple(_code(t) for t in _TOKENS.findall(fmt))
    minutes = frozenset(i for i, t in enumerate(tokens) if not isinstance(t, _Literal)
                        and t.lower() in ("m", "mm") and _minute(tokens, i))
    digits = max((len(t) - 1 for t in tokens
                  if t.startswith(".") and not isinstance(t, _Literal)), default=0)
    ampm = any(not isinstance(t, _Literal) and t.lower() in ("am/pm", "a/p") for t in tokens)
    return tokens, minutes, digits, _needs_date(tokens), ampm


def _show(tok: str, minute: bool, c: dict) -> str:
    if isinstance(tok, _Literal):
        return str(tok)
    low = tok.lower()
    if low.startswith("["):
        total = c["units"] // ({"h": 3600, "m": 60, "s": 1}[low[1]] * c["scale"])
        return str(total).zfill(len(low) - 2)
    if low.startswith(".") and len(low) > 1:
        return "." + str(c["part"]).zfill(c["digits"])[:len(low) - 1]
    if minute:
        return f"{c['mi']:02d}" if low == "mm" else str(c["mi"])
    if low in ("h", "hh"):
        h = (c["hh"] % 12 or 12) if c["ampm"] else c["hh"]
        return f"{h:02d}" if low == "hh" else str(h)
    if low == "am/pm":
        return "AM" if c["hh"] < 12 else "PM"
    if low == "a/p":  # as written: a/p gives a or p, A/P gives A or P
        return tok[0] if c["hh"] < 12 else tok[2]
    y, m, d, wd = c["y"], c["m"], c["d"], c["wd"]
    shown = {"yyyy": f"{y:04d}", "yy": f"{y % 100:02d}", "mmmmm": calendar.month_name[m][:1],
             "mmmm": calendar.month_name[m], "mmm": calendar.month_abbr[m],
             "mm": f"{m:02d}", "m": str(m), "dddd": calendar.day_name[wd],
             "ddd": calendar.day_abbr[wd], "dd": f"{d:02d}", "d": str(d),
             "ss": f"{c['ss']:02d}", "s": str(c["ss"])}.get(low)
    if shown is not None:
        return shown
    if low.startswith("e"):  # the era's year: the year in the Gregorian calendar
        return str(y)  # (sheetjs formula_stress_test.xlsx Text!B15, "ee-mm-dd")
    return tok
