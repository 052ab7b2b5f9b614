"""REGEXTEST, REGEXEXTRACT, REGEXREPLACE (Excel 365, PCRE2 patterns).

Python's ``re`` reads the patterns these functions are used with (classes, groups,
quantifiers, anchors, lookaround); a pattern it cannot read is #VALUE!, as Excel's is.
Replacement strings use ``$1`` / ``${name}`` for groups (Excel's syntax), turned into
Python's. ``case_sensitivity`` 0 (default) is case-sensitive, 1 ignores case.
"""

from __future__ import annotations

import re

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.arrayargs import OMITTED, whole_arg
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError


def _compile(pattern, case):
    p = c.to_text(pattern)
    if isinstance(p, ExcelError):
        return p
    flag = whole_arg(case, 0)
    if isinstance(flag, ExcelError):
        return flag
    if flag not in (0, 1):
        return ExcelError.VALUE
    try:
        return re.compile(p, re.IGNORECASE if flag else 0)
    except (re.error, OverflowError):
        return ExcelError.VALUE


def _text(v):
    return c.to_text(v)


@register("REGEXTEST", 2, 3)
def _regextest(ctx, text, pattern, case=OMITTED):
    t, rx = _text(text), _compile(pattern, case)
    for v in (t, rx):
        if isinstance(v, ExcelError):
            return v
    return rx.search(t) is not None


@register("REGEXEXTRACT", 2, 4)
def _regexextract(ctx, text, pattern, mode=OMITTED, case=OMITTED):
    t, rx, m = _text(text), _compile(pattern, case), whole_arg(mode, 0)
    for v in (t, rx, m):
        if isinstance(v, ExcelError):
            return v
    if m not in (0, 1, 2):
        return ExcelError.VALUE
    if m == 1:
        found = [x.group(0) for x in rx.finditer(t)]
        return Range.array_of([found]) if found else ExcelError.NA  # (spilled as a row)
    first = rx.search(t)
    if first is None:
        return ExcelError.NA
    if m == 0:
        return first.group(0)
    if not first.groups():  # capture groups asked of a pattern without any
        return ExcelError.VALUE
    return Range.array_of([[ExcelError.NA if g is None else g for g in first.groups()]])


_GROUP = re.compile(r"\$(\d+|\{\w+\})|\$\$")


def _replacement(text: str) -> str:
    """Excel's ``$1``, ``${name}`` and ``$$`` as Python's template (backslashes literal)."""
    out, last = [], 0
    for m in _GROUP.finditer(text):
        out.append(text[last:m.start()].replace("\\", "\\\\"))
        g = m.group(1)
        out.append("$" if g is None else f"\\g<{g.strip('{}')}>")
        last = m.end()
    out.append(text[last:].replace("\\", "\\\\"))
    return "".join(out)


@register("REGEXREPLACE", 3, 5)
def _regexreplace(ctx, text, pattern, replacement, occurrence=OMITTED, case=OMITTED):
    t, rx, r = _text(text), _compile(pattern, case), _text(replacement)
    n = whole_arg(occurrence, 0)
    for v in (t, rx, r, n):
        if isinstance(v, ExcelError):
            return v
    template = _replacement(r)
    matches = list(rx.finditer(t))
    if n != 0:
        if abs(n) > len(matches):
            return t
        matches = [matches[n - 1] if n > 0 else matches[n]]
    out, last = [], 0
    try:
        for m in matches:
            out.append(t[last:m.start()])
            out.append(m.expand(template))
            last = m.end()
    except (re.error, IndexError):
        return ExcelError.VALUE
    out.append(t[last:])
    return "".join(out)
