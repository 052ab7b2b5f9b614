"""Fraction patterns: ``# ?/?``, ``# ??/16``, ``??/??``, ``#0#00??/??``.

The ``/`` splits the section: the denominator is the run of placeholders or digits after
it (digits starting with 1-9 are a fixed denominator, as ``16`` or ``100``; placeholders
allow any denominator up to 10^n - 1); the numerator is the last run of placeholders
before it; placeholders before the numerator's run, apart from it, take the integer part.

* Without an integer part the fraction is improper (``??/??`` of 12.3 is 123/10).
* A fixed denominator takes the numerator rounded half away from zero; otherwise the
  fraction is the last convergent of the continued fraction whose denominator fits
  (``# ??/??`` of 123.456 is 123 26/57, not the closer 31/68).
* The numerator fills its placeholders from the right, the denominator its own from the
  left (``?`` pads with spaces, ``#`` with nothing, ``0`` with zeros).
* A zero numerator with an integer part blanks the fraction, keeping its width
  (``# ?/?`` of 1 is "1    "); the integer then shows at least one digit.

Measured against SheetJS ssf's test/fraction.json and oddities.json (Excel's outputs);
[MS-OI29500] 2.1.713 d: ``/`` is a fraction only between number symbols.
"""

from __future__ import annotations

import functools
import math
from fractions import Fraction

from workbook_gen.formula.functions.numfmt.fixed import commas, lay_integer, round_half_up
from workbook_gen.formula.functions.numfmt.tokens import PLACEHOLDER, literal


def _digit(tok: str) -> bool:
    return len(tok) == 1 and tok.isdigit()


@functools.lru_cache(maxsize=512)
def layout(tokens: tuple[str, ...]):
    """(integer placeholders, numerator run, slash, denominator run) of a fraction
    section, as token indices, or None when it is not one."""
    slash = next((i for i, t in enumerate(tokens) if t == "/"), None)
    if slash is None:
        return None
    j = slash + 1
    while j < len(tokens) and not (tokens[j] in PLACEHOLDER or _digit(tokens[j])):
        j += 1
    den = []
    while j < len(tokens) and (tokens[j] in PLACEHOLDER or _digit(tokens[j])):
        den.append(j)
        j += 1
    i = slash - 1
    while i >= 0 and tokens[i] not in PLACEHOLDER:
        i -= 1
    num = []
    while i >= 0 and tokens[i] in PLACEHOLDER:
        num.insert(0, i)
        i -= 1
    if not den or not num:
        return None
    ints = [k for k in range(i + 1) if tokens[k] in PLACEHOLDER]
    return tuple(ints), tuple(num), slash, tuple(den)


def is_fraction(tokens: tuple[str, ...]) -> bool:
    return layout(tokens) is not None


def convergent(x: Fraction, max_den: int) -> tuple[int, int]:
    """The last convergent h/k of ``x``'s continued fraction with k <= ``max_den``, or the
    first within 1e-13 of ``x`` relatively (``# ??/?????????`` of 0.123251512342345 is
    480894/3901729, 3e-14 off, not a later convergent: ssf's fraction.json)."""
    h0, h1, k0, k1 = 0, 1, 1, 0
    rest = x
    while True:
        a = math.floor(rest)
        h2, k2 = a * h1 + h0, a * k1 + k0
        if k2 > max_den:
            break
        h0, h1, k0, k1 = h1, h2, k1, k2
        if rest == a or abs(x - Fraction(h1, k1)) <= x * _CLOSE:
            break
        rest = 1 / (rest - a)
    return h1, k1


_CLOSE = Fraction(1, 10 ** 13)


def value(x: float, tokens: tuple[str, ...]) -> tuple[int, int, int]:
    """(whole, numerator, denominator) that the fraction section shows for ``x`` >= 0."""
    ints, _, _, den = layout(tokens)
    den_text = "".join(tokens[k] for k in den)
    whole = math.floor(x) if ints else 0
    part = x - whole
    if _fixed(den_text):
        d = int(den_text)
        n = int(round_half_up(part * d, 0))
    else:
        n, d = convergent(Fraction(part), 10 ** len(den) - 1)
    if ints and n >= d:  # rounded up to a whole one
        whole, n = whole + n // d, n % d
    return whole, n, d


def _fixed(den_text: str) -> bool:
    return den_text[0] in "123456789" and den_text.isdigit()


def format_fraction(x: float, tokens: tuple[str, ...]) -> str:
    """The fraction section ``tokens`` applied to ``x`` >= 0."""
    ints, num, slash, den = layout(tokens)
    fixed = _fixed("".join(tokens[k] for k in den))
    whole, n, d = value(x, tokens)
    blank = bool(ints) and n == 0
    out: dict[int, str] = {}
    if ints:
        digits = str(whole) if whole or blank else ""
        grouping = commas(tokens, ints[-1] + 1, ints[-1] + 1, ints)[0]
        lay_integer(digits, ints, tokens, grouping, out)
    lay_integer(str(n), num, tokens, False, out)
    if not fixed:
        _lay_denominator(str(d), den, tokens, out)
    pieces = []
    for k, tok in enumerate(tokens):
        if blank and num[0] <= k <= den[-1]:
            pieces.append(" " * _blank_width(tok))
        else:
            pieces.append(out[k] if k in out else tok if k in den else literal(tok))
    return "".join(pieces)


def _blank_width(tok: str) -> int:
    """The spaces a blanked fraction's token keeps: one a placeholder (none a ``#``) or
    digit, its text's length a literal."""
    if tok in PLACEHOLDER or _digit(tok):
        return 0 if tok == "#" else 1
    return len(literal(tok))


def _lay_denominator(digits: str, places: list[int], tokens, out: dict) -> None:
    for k, i in enumerate(places):
        if k < len(digits):
            out[i] = digits[k]
        else:
            out[i] = {"0": "0", "#": "", "?": " "}[tokens[i]]
