"""Fixed-point number patterns, laid placeholder by placeholder.

A numeric section is a run of tokens: digit placeholders (``0`` a digit or 0, ``#`` a
digit or nothing, ``?`` a digit or a space), the decimal point (the first ``.``; later
ones are literal dots), commas, ``%`` (the number times 100 for each, the sign shown in
place) and literals. Then:

* a comma between two integer placeholders turns thousands separators on; commas after
  the last placeholder (none after them) divide by 1000 each; another comma right after
  a placeholder is dropped; a comma after a literal is a literal;
* the integer digits go into the integer placeholders from the right, the extra ones all
  into the first placeholder (or just before the decimal point when there is none),
  literals staying where they are; separators follow the digits by place value, a space
  where a ``?`` shows a space (``?,???`` of 12 is "    12"), nothing where a ``#`` shows
  nothing;
* the decimals, rounded half away from zero to as many places as there are fraction
  placeholders, fill them from the left; a ``#`` (``?``) shows nothing (a space) where
  only zeros are left.

Measured on pycel's text.xlsx, saved by Excel (TextNumbers: '#,#"ZZ"#.0"YY"00',
'#.###.#.#.#', '%#%#%', '#x,0,#.00.0' ...) and NPOI's NumberFormatApproxTests.xlsx
('?,??????.????').
"""

from __future__ import annotations

import math
from decimal import ROUND_HALF_UP, Decimal

from workbook_gen.formula.functions.numfmt.tokens import PLACEHOLDER, literal


def fixed_digits(x: float, decimals: int) -> str:
    """``x`` >= 0 in fixed point with ``decimals`` places as Excel shows numbers: 15
    significant digits, then zeros (FIXED of 1.2345678907675434e20 is
    123,456,789,076,754,000,000: formulas test.xlsx TEXT!R18)."""
    if x == 0 or not math.isfinite(x):
        return f"{x:.{decimals}f}"
    return f"{Decimal(f'{x:.14e}'):.{decimals}f}"


def round_half_up(x: float, d: int) -> float:
    from workbook_gen.formula.functions.math.core import round_digits as round_to
    return round_to(x, d, ROUND_HALF_UP)


def _after_placeholder(tokens: list[str], i: int) -> bool:
    j = i - 1
    while j >= 0 and tokens[j] == ",":
        j -= 1
    return j >= 0 and tokens[j] in PLACEHOLDER


def commas(tokens: list[str], end: int, int_end: int, places: list[int]):
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
        if j < int_end and tokens[j] in PLACEHOLDER:
            grouping = True
        elif i > last:
            scale += 1
        dropped.add(i)
    return grouping, scale, dropped


def _separator(digit: str) -> str:
    return "" if digit == "" else " " if digit == " " else ","


def lay_integer(whole: str, places: list[int], tokens, grouping: bool, out: dict) -> None:
    """The digits ``whole`` into the placeholders at ``places`` (indices into ``tokens``),
    from the right; ``out[i]`` is what placeholder ``i`` prints."""
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
        d = whole[idx] if idx >= 0 else {"0": "0", "#": "", "?": " "}[tokens[i]]
        if grouping and p > 1 and (p - 1) % 3 == 0:
            d += _separator(d)
        out[i] = d


def lay_fraction(frac: str, places: list[int], tokens, out: dict) -> None:
    """The decimals ``frac`` into the fraction placeholders, from the left."""
    last = len(frac.rstrip("0"))  # digits from here on are trailing zeros
    for k, i in enumerate(places):
        if k < last or tokens[i] == "0":
            out[i] = frac[k]
        else:
            out[i] = "" if tokens[i] == "#" else " "


def parts(tokens: list[str], end: int):
    """(decimal point index or None, integer placeholders, fraction placeholders) of
    ``tokens[:end]``."""
    dot = next((i for i in range(end) if tokens[i] == "."), None)
    int_end = end if dot is None else dot
    int_places = [i for i in range(int_end) if tokens[i] in PLACEHOLDER]
    frac_places = [] if dot is None else [i for i in range(dot + 1, end)
                                           if tokens[i] in PLACEHOLDER]
    return dot, int_places, frac_places


def join(tokens: list[str], end: int, out: dict, dot, whole: str, dropped) -> list[str]:
    """The printed pieces of ``tokens[:end]``: placeholders from ``out``, the decimal
    point (with the integer digits before it when there is no integer placeholder),
    literals; ``dropped`` commas print nothing."""
    pieces = []
    has_int = any(i in out for i in range(end) if dot is None or i < dot)
    for i, tok in enumerate(tokens[:end]):
        if i in out:
            pieces.append(out[i])
        elif i == dot:
            pieces.append(("" if has_int else whole) + ".")
        elif i not in dropped:
            pieces.append(literal(tok))
    return pieces


def format_fixed(x: float, tokens: list[str]) -> str:
    """The fixed-point section ``tokens`` applied to ``x`` >= 0."""
    end = len(tokens)
    dot, int_places, frac_places = parts(tokens, end)
    x *= 100 ** sum(1 for t in tokens if t == "%")
    grouping, scale, dropped = commas(tokens, end, end if dot is None else dot,
                                      int_places + frac_places)
    x /= 1000 ** scale
    r = round_half_up(x, len(frac_places))
    whole, _, frac = fixed_digits(r, len(frac_places)).partition(".")
    whole = "" if whole == "0" else whole
    out: dict[int, str] = {}
    lay_integer(whole, int_places, tokens, grouping, out)
    lay_fraction(frac, frac_places, tokens, out)
    return "".join(join(tokens, end, out, dot, whole, dropped))


def shows_zero(x: float, tokens: list[str]) -> bool:
    """Whether ``x`` >= 0 rounds to zero in the fixed-point section (no minus sign then)."""
    end = len(tokens)
    dot, int_places, frac_places = parts(tokens, end)
    pct = sum(1 for t in tokens if t == "%")
    scale = commas(tokens, end, end if dot is None else dot, int_places + frac_places)[1]
    return round_half_up(x * 100 ** pct / 1000 ** scale, len(frac_places)) == 0
