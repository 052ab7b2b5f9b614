"""TEXT's number formats: sections, and the number part laid placeholder by placeholder.

A format has up to four sections, ``positive;negative;zero;text``. A section holding ``@``
is the text section and must be the last (else #VALUE!); a fourth section is the text
section in any case. With one numeric section a negative number gets a leading ``-``;
with two, zero takes the first; with three, the third.

A numeric section is cut into tokens: digit placeholders (``0`` a digit or 0, ``#`` a
digit or nothing, ``?`` a digit or a space), the decimal point (the first ``.``; later
ones are literal dots), commas, ``%`` (the number times 100 for each, the sign shown in
place), an exponent (``E+``, ``E-``), and literals (quoted text, ``\\x``, other
characters; ``*x`` fill and ``_x`` padding as in a cell: nothing and a space; ``[...]``
colours and conditions are not printed, conditions not applied). Then:

* a comma between two integer placeholders turns thousands separators on; commas after
  the last integer placeholder (none after them) divide by 1000 each; another comma
  right after a placeholder is dropped; a comma after a literal is a literal;
* the integer digits go into the integer placeholders from the right, the extra ones
  all into the first placeholder (or just before the decimal point when there is none),
  literals staying where they are; separators follow the digits by place value;
* the decimals, rounded half away from zero to as many places as there are fraction
  placeholders, fill them from the left; a ``#`` (``?``) shows nothing (a space) where
  only zeros are left.

Measured on pycel's text.xlsx, saved by Excel (TextNumbers: '#,#"ZZ"#.0"YY"00',
'#.###.#.#.#', '%#%#%', '#x,0,#.00.0', 'w;x;z@' ...); date and time sections go to
:mod:`.datetext`; a section mixing date codes or ``@`` with digit placeholders is #VALUE!.
"""

from __future__ import annotations

import math
import re
from decimal import Decimal

from workbook_gen.formula.functions import coerce as c
from workbook_gen.xlerror import ExcelError

_TOKEN = re.compile(r'"[^"]*"?|\\.|[*_].|\[[^\]]*\]|[Ee][+-]|general|am/pm|a/p|.', re.I | re.S)
_DATE_CODE = re.compile(r"[dmyhse]|\[(h+|m+|s+)\]|am/pm|a/p", re.I)
_PLACEHOLDER = "0#?"


def split_sections(fmt: str) -> list[str]:
    """The sections of a format, split at ``;`` outside quotes and escapes."""
    sections, start = [], 0
    for m in _TOKEN.finditer(fmt):
        if m.group(0) == ";":
            sections.append(fmt[start:m.start()])
            start = m.end()
    sections.append(fmt[start:])
    return sections


def _tokens(section: str) -> list[str]:
    return _TOKEN.findall(section)


def _literal(tok: str) -> str:
    if tok.startswith('"'):
        return tok[1:-1] if tok.endswith('"') and len(tok) > 1 else tok[1:]
    if tok.startswith("\\"):
        return tok[1:]
    if tok.startswith("*"):
        return ""
    if tok.startswith("_"):
        return " "
    if tok.startswith("["):  # a colour, a condition or a locale: not printed
        return ""
    return tok


def _is_text_section(section: str) -> bool:
    return "@" in _tokens(section)


def format_value(v, fmt: str):
    """TEXT(v, fmt) for a number or a text ``v`` (booleans and errors are the caller's)."""
    from workbook_gen.formula.functions.datetext import FRACTION, format_date
    sections = split_sections(fmt)
    if len(sections) > 4 or any(_is_text_section(s) for s in sections[:-1]) or any(
            t.startswith('"') and (len(t) == 1 or not t.endswith('"')) for t in _tokens(fmt)):
        return ExcelError.VALUE  # (an unclosed quote: formulas test.xlsx EXTRA!A4)
    text_section = sections[-1] if len(sections) == 4 or _is_text_section(sections[-1]) \
        else None
    numeric = sections[:-1] if text_section is not None else sections
    if isinstance(v, str):
        if text_section is None:
            return v
        return "".join(v if t == "@" else _literal(t) for t in _tokens(text_section))
    x = float(v)
    if not numeric:  # "@" alone shows the number; with digit placeholders it is #VALUE!
        if any(t in _PLACEHOLDER for t in _tokens(text_section)):
            return ExcelError.VALUE
        return c.number_to_text(x)
    conditions = [_condition(s) for s in numeric]
    if any(conditions):  # [<=1]a;[=2]b;c: the first section whose condition holds
        chosen = next((s for s, cond in zip(numeric, conditions)
                       if cond is None or cond(x)), None)
        if chosen is None:
            return ExcelError.VALUE
        section, sign = chosen, x < 0
    elif len(numeric) == 1 or x > 0 or (x == 0 and len(numeric) == 2):
        section, sign = numeric[0], len(numeric) == 1 and x < 0
    elif x < 0:
        section, sign = numeric[1], False
    else:
        section, sign = numeric[2], False
    x = abs(x)
    tokens = _tokens(section)
    low = [t.lower() for t in tokens]
    if "general" in low:
        body = "".join(c.number_to_text(x) if t == "general" else _literal(tok)
                       for t, tok in zip(low, tokens))
        return ("-" if sign else "") + body
    bare = [t for t in _tokens(FRACTION.sub("", section)) if not t.startswith(('"', "\\"))]
    dates = any(_DATE_CODE.fullmatch(t) for t in bare)
    digits = any(t in _PLACEHOLDER for t in bare)
    if dates and not digits:
        if sign:  # a negative time: one elapsed count alone, as -24 for [h] of -1
            elapsed = [t for t in bare if t.startswith("[")]
            if len(elapsed) == 1 and all(not _DATE_CODE.fullmatch(t) or t.startswith("[")
                                         for t in bare) and not FRACTION.search(section):
                out = format_date(x, section)
                return out if isinstance(out, ExcelError) else "-" + out
            return ExcelError.VALUE
        return format_date(x, section)
    if dates or "@" in bare:  # (an exponent E+ is one token, never a date code)
        return ExcelError.VALUE
    body = _number(x, tokens)
    shown = not digits or float(_digits_of(x, tokens)) != 0 or (
        x != 0 and any(t[:1] in "Ee" and t[1:] in ("+", "-") for t in tokens))
    return ("-" if sign and shown else "") + body


_CONDITION = re.compile(r"\[(<=|>=|<>|<|>|=)\s*([-+]?\d*\.?\d+(?:[eE][-+]?\d+)?)\]")
_COMPARE = {"<": float.__lt__, "<=": float.__le__, ">": float.__gt__, ">=": float.__ge__,
            "=": float.__eq__, "<>": float.__ne__}


def _condition(section: str):
    """The test of a section's ``[<=100]`` condition, or None (formulas test.xlsx EXTRA!A35:
    TEXT(2,"[<=1]a;[=2]xx;xcx") is xx)."""
    for tok in _tokens(section):
        m = _CONDITION.fullmatch(tok)
        if m:
            op, bound = m.group(1), float(m.group(2))
            return lambda x: _COMPARE[op](float(x), bound)
    return None


def _digits_of(x: float, tokens: list[str]) -> str:
    """The rounded digits a section shows of ``x`` (for the sign of a value shown as 0)."""
    dot = next((i for i, t in enumerate(tokens) if t == "."), len(tokens))
    decimals = sum(1 for t in tokens[dot:] if t in _PLACEHOLDER)
    pct = sum(1 for t in tokens if t == "%")
    places = [i for i, t in enumerate(tokens) if t in _PLACEHOLDER]
    scale = _commas(tokens, len(tokens), dot, places)[1]
    return f"{_round(x * 100 ** pct / 1000 ** scale, decimals):.{decimals}f}"


def fixed_digits(x: float, decimals: int) -> str:
    """``x`` >= 0 in fixed point with ``decimals`` places as Excel shows numbers: 15
    significant digits, then zeros (FIXED of 1.2345678907675434e20 is
    123,456,789,076,754,000,000: formulas test.xlsx TEXT!R18)."""
    if x == 0 or not math.isfinite(x):
        return f"{x:.{decimals}f}"
    return f"{Decimal(f'{x:.14e}'):.{decimals}f}"


def _round(x: float, d: int) -> float:
    from decimal import ROUND_HALF_UP

    from workbook_gen.formula.functions.math import _round as round_to
    return round_to(x, d, ROUND_HALF_UP)


def _number(x: float, tokens: list[str]):
    """The numeric section ``tokens`` applied to ``x`` >= 0."""
    exp = next((i for i, t in enumerate(tokens) if t[:1] in "Ee" and t[1:] in ("+", "-")), None)
    end = len(tokens) if exp is None else exp
    dot = next((i for i in range(end) if tokens[i] == "."), None)
    int_end = end if dot is None else dot
    int_places = [i for i in range(int_end) if tokens[i] in _PLACEHOLDER]
    frac_places = [] if dot is None else [i for i in range(dot + 1, end)
                                           if tokens[i] in _PLACEHOLDER]
    x *= 100 ** sum(1 for t in tokens if t == "%")
    grouping, scale, dropped = _commas(tokens, end, int_end, int_places + frac_places)
    x /= 1000 ** scale
    exponent = 0
    if exp is not None:
        exponent, x = _scientific(x, len(int_places), tokens[:int_end], len(frac_places))
    r = _round(x, len(frac_places))
    whole, _, frac = fixed_digits(r, len(frac_places)).partition(".")
    whole = "" if whole == "0" else whole
    out: dict[int, str] = {}
    _lay_integer(whole, int_places, tokens, grouping, out)
    _lay_fraction(frac, frac_places, tokens, out)
    parts = []
    for i, tok in enumerate(tokens[:end]):
        if i in out:
            parts.append(out[i])
        elif i == dot:
            parts.append(("" if int_places else whole) + ".")
        elif i not in dropped:
            parts.append(_literal(tok))
    if exp is not None:
        parts.append(_exponent_text(exponent, tokens[exp], tokens[exp + 1:]))
    return "".join(parts)


def _after_placeholder(tokens: list[str], i: int) -> bool:
    j = i - 1
    while j >= 0 and tokens[j] == ",":
        j -= 1
    return j >= 0 and tokens[j] in _PLACEHOLDER


def _commas(tokens: list[str], end: int, int_end: int, places: list[int]):
    """(thousands separators on, scaling commas, commas dropped) of a number part: a comma
    right after a placeholder separates thousands when an integer placeholder follows it,
    scales when no placeholder follows at all (``0.0,,``), else is dropped."""
    grouping, scale, dropped = False, 0, set()
    last = places[-1] if places else -1
    for i in range(end):
        if tokens[i] != "," or not _after_placeholder(tokens, i):
            continue
        j = i + 1
        while j < int_end and tokens[j] == ",":
            j += 1
        if j < int_end and tokens[j] in _PLACEHOLDER:
            grouping = True
        elif i > last:
            scale += 1
        dropped.add(i)
    return grouping, scale, dropped


def _lay_integer(whole: str, places: list[int], tokens, grouping: bool, out: dict) -> None:
    n = len(places)
    for k, i in enumerate(places):
        p = n - k  # place value of this placeholder (1: units)
        if k == 0 and len(whole) > n:  # the extra digits all go to the first placeholder
            digits = whole[:len(whole) - n + 1]
            text = "".join(d + ("," if grouping and (len(whole) - j - 1) % 3 == 0
                                and len(whole) - j - 1 > 0 else "")
                           for j, d in enumerate(digits))
            out[i] = text
            continue
        idx = len(whole) - p
        if idx >= 0:
            d = whole[idx]
        else:
            d = {"0": "0", "#": "", "?": " "}[tokens[i]]
        if d not in ("", " ") and grouping and p > 1 and (p - 1) % 3 == 0:
            d += ","
        out[i] = d


def _lay_fraction(frac: str, places: list[int], tokens, out: dict) -> None:
    last = len(frac.rstrip("0"))  # digits from here on are trailing zeros
    for k, i in enumerate(places):
        if k < last or tokens[i] == "0":
            out[i] = frac[k]
        else:
            out[i] = "" if tokens[i] == "#" else " "


def _scientific(x: float, int_count: int, int_tokens: list[str], decimals: int):
    """(exponent, mantissa): one integer digit, or engineering steps of ``int_count``
    digits when the integer placeholders start with #."""
    if x == 0:
        return 0, 0.0
    e = math.floor(math.log10(x))
    step = int_count if int_count > 1 and "#" in int_tokens else 1
    e = e - (e % step) if step > 1 else e - max(int_count - 1, 0)
    m = _round(x / 10.0 ** e, decimals)
    if m >= 10 ** max(step, int_count if step == 1 else step):  # rounding carried a digit
        e += step
        m = _round(x / 10.0 ** e, decimals)
    return e, m


def _exponent_text(e: int, marker: str, rest: list[str]) -> str:
    width = sum(1 for t in rest if t == "0")
    sign = "-" if e < 0 else ("+" if marker[1] == "+" else "")
    tail = "".join(_literal(t) for t in rest if t not in _PLACEHOLDER)
    return marker[0] + sign + str(abs(e)).zfill(max(width, 1)) + tail
