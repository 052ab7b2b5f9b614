"""Scientific patterns: a mantissa, ``E+``/``E-`` (or ``e+``/``e-``), an exponent.

* The mantissa has as many integer digits as its integer placeholders (``0``, ``#`` or
  ``?``): with n of them the exponent is a multiple of n (engineering steps, ``##0.0E+0``
  of 12345 is 12.3E+3, ``0000.0000E+0`` of 123456.789 is 0012.3457E+4); with one it is
  the usual d.ddd. The decimals are rounded half away from zero; a carry moves the
  exponent a step. Zero shows every integer placeholder as 0 (``####.####E+0`` of 0 is
  0000.E+0).
* Commas between integer placeholders separate thousands in the mantissa; every other
  comma right after a placeholder is dropped (nothing scales); ``%`` is printed, not
  applied.
* ``E`` or ``e`` prints as written; the sign (``-`` for E-, ``+``/``-`` for E+) goes right
  before the exponent's first digit placeholder, after any literal between (``#.#e+|#``
  of 1.2e5 is 1.2e|+5); the exponent's digits fill its placeholders from the right
  (``?`` pads with spaces, ``0`` with zeros, ``#`` with nothing) and at least one digit
  shows.
* A decimal point after the exponent, or an exponent without a digit placeholder, makes
  the format invalid (#VALUE!).

Measured on NPOI's NumberFormatApproxTests.xlsx and formulas' test.xlsx (EXTRA!A27:A33),
both saved by Excel, and SheetJS ssf's test/exp.tsv (Excel's outputs). ([MS-OI29500]
2.1.713 says Office takes only E+ and E- as scientific; Excel's TEXT, as cached in the
NPOI workbook, takes e+ and e- alike.)
"""

from __future__ import annotations

import math

from workbook_gen.formula.functions.numfmt.fixed import (
    commas, fixed_digits, join, lay_fraction, lay_integer, parts, round_half_up,
)
from workbook_gen.formula.functions.numfmt.tokens import PLACEHOLDER, is_exponent, literal
from workbook_gen.xlerror import ExcelError


def valid(tokens: list[str]) -> bool:
    exp = next(i for i, t in enumerate(tokens) if is_exponent(t))
    rest = tokens[exp + 1:]
    return "." not in rest and any(t in PLACEHOLDER for t in rest) and not any(
        is_exponent(t) for t in rest)


def _mantissa(x: float, int_count: int, decimals: int) -> tuple[int, float]:
    """(exponent, mantissa rounded to ``decimals``) of ``x`` > 0."""
    step = max(int_count, 1)
    e = math.floor(math.log10(x))
    e = e - (e % step) if int_count > 1 else (e + 1 if int_count == 0 else e)
    top = 10.0 ** step if int_count else 1.0
    m = round_half_up(x / 10.0 ** e, decimals)
    if m >= top:  # rounding carried a digit
        e += step
        m = round_half_up(x / 10.0 ** e, decimals)
    return e, m


def format_scientific(x: float, tokens: list[str]) -> str | ExcelError:
    """The scientific section ``tokens`` applied to ``x`` >= 0."""
    if not valid(tokens):
        return ExcelError.VALUE
    exp = next(i for i, t in enumerate(tokens) if is_exponent(t))
    dot, int_places, frac_places = parts(tokens, exp)
    grouping, _, dropped = commas(tokens, exp, exp if dot is None else dot,
                                  int_places + frac_places)
    if x == 0:
        e, whole, frac = 0, "0" * len(int_places), "0" * len(frac_places)
    else:
        e, m = _mantissa(x, len(int_places), len(frac_places))
        whole, _, frac = fixed_digits(m, len(frac_places)).partition(".")
        whole = "" if whole == "0" else whole
    out: dict[int, str] = {}
    lay_integer(whole, int_places, tokens, grouping, out)
    lay_fraction(frac, frac_places, tokens, out)
    pieces = join(tokens, exp, out, dot, whole, dropped)
    pieces.append(tokens[exp][0])
    pieces.append(_exponent(e, tokens[exp][1], tokens[exp + 1:]))
    return "".join(pieces)


def _exponent(e: int, marker: str, rest: list[str]) -> str:
    """The exponent part after ``E+``/``E-``: literals, the sign, the digits."""
    places = [i for i, t in enumerate(rest) if t in PLACEHOLDER]
    out: dict[int, str] = {}
    lay_integer(str(abs(e)), places, rest, False, out)
    sign = "-" if e < 0 else ("+" if marker == "+" else "")
    pieces = []
    for i, tok in enumerate(rest):
        if i == places[0]:
            pieces.append(sign)
        if i in out:
            pieces.append(out[i])
        elif tok != "," or i == 0 or rest[i - 1] not in PLACEHOLDER:
            pieces.append(literal(tok))
    return "".join(pieces)
