"""Which section of a format shows a value, and with which sign.

A format has up to four sections, ``positive;negative;zero;text``. A section holding
``@`` is the text section and must be the last (else #VALUE!); a fourth section is the
text section in any case; more than four is #VALUE!. Without conditions: with one
numeric section a negative number gets a leading ``-``; with two, zero takes the first;
with three, the third.

Conditions (``[<10]``, ``[>=100]``, ``[<>0]`` ...) stand in the first two sections
(Microsoft's KB 67469: the first two clauses are the condition clauses, the third the
"else" clause):

* the first section shows the numbers its condition holds for (without one: the positive
  numbers), the second those of its own condition, or without one the negative numbers
  (every other number when there is no third section: ssf's oddities.json,
  ``[<=9999999]###-####;(###) ###-####`` of 2813308004 is (281) 330-8004); the third
  section every other number (KB 67469: ``[>1000]0.00E+00;General;0.00`` shows 999 as
  999.00);
* a number no section takes is shown in General (``[<10]#" Wow"`` of 10 is "10":
  NPOI's FormatChoiceTests.xlsx, saved by Excel);
* a negative number keeps its minus sign, except in a second section without a condition
  or with ``[<0]``, the negative section's own condition (KB 67469:
  ``[>100]General;[<100](General)`` shows -5 as -(5), ``...;[<0](General)`` as (5)).
"""

from __future__ import annotations

import functools

from workbook_gen.formula.functions.numfmt.tokens import condition, split_sections, tokens

GENERAL = "General"


def is_text_section(section: str) -> bool:
    return "@" in tokens(section)


@functools.lru_cache(maxsize=1024)
def split(fmt: str):
    """(numeric sections, text section or None), or None when the sections are invalid."""
    sections = split_sections(fmt)
    if len(sections) > 4 or any(is_text_section(s) for s in sections[:-1]):
        return None
    text = sections[-1] if len(sections) == 4 or is_text_section(sections[-1]) else None
    return (sections[:-1] if text is not None else sections), text


def choose(numeric: list[str], x: float) -> tuple[str, bool]:
    """(section, whether a minus sign goes before it) for the number ``x``."""
    conds = [condition(s) for s in numeric[:2]]
    if not any(conds):
        if len(numeric) == 1 or x > 0 or (x == 0 and len(numeric) == 2):
            return numeric[0], len(numeric) == 1 and x < 0
        if x < 0:
            return numeric[1], False
        return numeric[2], False
    first = conds[0]
    if first is None or first(x):
        if first is not None or x > 0 or len(numeric) == 1:
            return numeric[0], x < 0
    if len(numeric) >= 2:
        second = conds[1]
        if second is None and (len(numeric) == 2 or x < 0):
            return numeric[1], False
        if second is not None and second(x):
            return numeric[1], x < 0 and not second.is_negative_default
    if len(numeric) >= 3:
        return numeric[2], x < 0
    return GENERAL, x < 0
