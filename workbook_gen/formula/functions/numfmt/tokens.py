"""A number format cut into tokens and sections, and what a literal token prints.

Tokens: quoted text (``"..."``), an escaped character (``\\x``), a fill (``*x``: nothing in
TEXT) or a padding (``_x``: a space), a bracket (``[Red]``, ``[Color10]``, a condition
``[<=100]``, a locale or currency ``[$€-407]``, an elapsed count ``[h]``), an exponent
(``E+``, ``e-``), ``General``, ``AM/PM`` and ``A/P``, and any other single character.
Sections are split at ``;`` outside quotes, escapes and brackets.
"""

from __future__ import annotations

import functools
import re

TOKEN = re.compile(r'"[^"]*"?|\\.|[*_].|\[[^\]]*\]|[Ee][+-]|general|am/pm|a/p|.',
                   re.I | re.S)
PLACEHOLDER = "0#?"
CONDITION = re.compile(r"\[(<=|>=|<>|<|>|=)\s*([-+]?\d*\.?\d+(?:[eE][-+]?\d+)?)\]")
_CURRENCY = re.compile(r"\[\$([^\]]*?)(?:-[0-9A-Fa-f]*)?\]")


@functools.lru_cache(maxsize=1024)
def tokens(section: str) -> tuple[str, ...]:
    return tuple(TOKEN.findall(section))


@functools.lru_cache(maxsize=1024)
def split_sections(fmt: str) -> list[str]:
    """The sections of a format, split at ``;`` outside quotes, escapes and brackets."""
    sections, start = [], 0
    for m in TOKEN.finditer(fmt):
        if m.group(0) == ";":
            sections.append(fmt[start:m.start()])
            start = m.end()
    sections.append(fmt[start:])
    return tuple(sections)


@functools.lru_cache(maxsize=1024)
def unclosed_quote(fmt: str) -> bool:
    return any(t.startswith('"') and (len(t) == 1 or not t.endswith('"'))
               for t in tokens(fmt))


def literal(tok: str) -> str:
    """What a token that is not a placeholder prints: quoted text without its quotes, an
    escaped character, a space for ``_x``, nothing for ``*x``, a currency symbol for
    ``[$€-407]``, nothing for other brackets (colours, conditions, locales)."""
    if tok.startswith('"'):
        return tok[1:-1] if tok.endswith('"') and len(tok) > 1 else tok[1:]
    if tok.startswith("\\"):
        return tok[1:]
    if tok.startswith("*"):
        return ""
    if tok.startswith("_"):
        return " "
    if tok.startswith("["):
        m = _CURRENCY.fullmatch(tok)
        return m.group(1) if m else ""
    return tok


def is_literal(tok: str) -> bool:
    """A token printed as written or by :func:`literal` (quoted, escaped, fill, padding)."""
    return tok[:1] in ('"', "\\", "*", "_")


def is_exponent(tok: str) -> bool:
    return len(tok) == 2 and tok[0] in "Ee" and tok[1] in "+-"


@functools.lru_cache(maxsize=1024)
def condition(section: str):
    """The test of a section's ``[<=100]`` condition, or None."""
    for tok in tokens(section):
        m = CONDITION.fullmatch(tok)
        if m:
            op, bound = m.group(1), float(m.group(2))
            return _Condition(op, bound)
    return None


class _Condition:
    __slots__ = ("op", "bound")

    def __init__(self, op: str, bound: float):
        self.op, self.bound = op, bound

    def __call__(self, x: float) -> bool:
        b = self.bound
        return {"<": x < b, "<=": x <= b, ">": x > b, ">=": x >= b, "=": x == b,
                "<>": x != b}[self.op]

    @property
    def is_negative_default(self) -> bool:
        """``[<0]``: the second section's implicit condition (its numbers lose the sign)."""
        return self.op == "<" and self.bound == 0
