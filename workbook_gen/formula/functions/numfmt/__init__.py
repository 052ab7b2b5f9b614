"""Excel's number formats applied to a value, as TEXT shows it: ``format_value(v, fmt)``.

Locale-free (the en-US separators ``,`` and ``.``), in modules by concept:

* :mod:`.tokens` cuts a format into tokens and sections; what literals print;
* :mod:`.sections` picks the section for a value (conditions, the sign) and the text one;
* :mod:`.fixed` lays fixed-point patterns (placeholders, commas, percent);
* :mod:`.scientific` the ``E+``/``E-`` patterns; :mod:`.fraction` the ``?/?`` ones;
* :mod:`.dates` the date, time and elapsed-time patterns (in the workbook's date system).

A section mixing date codes or ``@`` with digit placeholders is #VALUE!, as is an unclosed
quote (formulas test.xlsx EXTRA!A4).
"""

from __future__ import annotations

import functools
import re

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.numfmt import sections as sec
from workbook_gen.formula.functions.numfmt.dates import FRACTION, format_date
from workbook_gen.formula.functions.numfmt.fixed import fixed_digits, format_fixed, shows_zero
from workbook_gen.formula.functions.numfmt.fraction import format_fraction, is_fraction
from workbook_gen.formula.functions.numfmt.fraction import value as fraction_value
from workbook_gen.formula.functions.numfmt.scientific import format_scientific
from workbook_gen.formula.functions.numfmt.tokens import (
    PLACEHOLDER, is_exponent, is_literal, literal, tokens, unclosed_quote,
)
from workbook_gen.xlerror import ExcelError

__all__ = ["format_value", "format_date", "fixed_digits"]

_DATE_CODE = re.compile(r"[dmyhse]|\[(h+|m+|s+)\]|am/pm|a/p", re.I)


def format_value(v, fmt: str):
    """TEXT(v, fmt) for a number or a text ``v`` (booleans and errors are the caller's)."""
    split = sec.split(fmt)
    if split is None or unclosed_quote(fmt):
        return ExcelError.VALUE
    numeric, text_section = split
    if isinstance(v, str):
        if text_section is None:
            return v
        return "".join(v if t == "@" else literal(t) for t in tokens(text_section))
    x = float(v)
    if not numeric:  # "@" alone shows the number; with digit placeholders it is #VALUE!
        if any(t in PLACEHOLDER for t in tokens(text_section)):
            return ExcelError.VALUE
        return c.number_to_text(x)
    section, sign = sec.choose(numeric, x)
    return format_number(abs(x), section, sign)


def format_number(x: float, section: str, sign: bool):
    """A numeric section applied to ``x`` >= 0, with a leading minus if ``sign`` (and the
    number does not show as zero)."""
    toks, kind, bare = _kind(section)
    if kind == "general":
        body = "".join(c.number_to_text(x) if t.lower() == "general" else literal(t)
                       for t in toks)
        return ("-" if sign else "") + body
    if kind == "date":
        return _date(x, section, sign, bare)
    if kind == "invalid":
        return ExcelError.VALUE
    if kind == "scientific":
        body = format_scientific(x, toks)
        shown = x != 0
    elif kind == "fraction":
        body = format_fraction(x, toks)
        whole, numerator, _ = fraction_value(x, toks)
        shown = whole != 0 or numerator != 0
    else:
        body = format_fixed(x, toks)
        shown = not any(t in PLACEHOLDER for t in bare) or not shows_zero(x, toks)
    if isinstance(body, ExcelError):
        return body
    return ("-" if sign and shown else "") + body


@functools.lru_cache(maxsize=1024)
def _kind(section: str):
    """(tokens, kind, tokens that are no literal) of a numeric section; kind is general,
    date, invalid (date codes or ``@`` with digit placeholders), scientific, fraction or
    fixed."""
    toks = tokens(section)
    if any(t.lower() == "general" for t in toks):
        return toks, "general", ()
    bare = tuple(t for t in tokens(FRACTION.sub("", section)) if not is_literal(t))
    dates = any(_DATE_CODE.fullmatch(t) for t in bare)
    digits = any(t in PLACEHOLDER for t in bare)
    if dates and not digits:
        return toks, "date", bare
    if dates or "@" in bare:  # (an exponent E+ is one token, never a date code)
        return toks, "invalid", bare
    if any(is_exponent(t) for t in toks):
        return toks, "scientific", bare
    return toks, "fraction" if is_fraction(toks) else "fixed", bare


def _date(x: float, section: str, sign: bool, bare: list[str]):
    if not sign:
        return format_date(x, section)
    # a negative time: one elapsed count alone, as -24 for [h] of -1
    elapsed = [t for t in bare if t.startswith("[") and _DATE_CODE.fullmatch(t)]
    if len(elapsed) == 1 and all(not _DATE_CODE.fullmatch(t) or t.startswith("[")
                                 for t in bare) and not FRACTION.search(section):
        out = format_date(x, section)
        return out if isinstance(out, ExcelError) else "-" + out
    return ExcelError.VALUE
