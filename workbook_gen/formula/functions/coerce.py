"""Excel's coercion rules, in the one place every function calls.

* A **direct argument** (a literal or a computed value) converts: TRUE is 1, numeric
  text is a number, an empty cell is 0 or "".
* A **range** (a reference, or an array) keeps only what its function wants: SUM, AVERAGE,
  COUNT and the like skip text, booleans and empty cells; COUNTA counts all but empties.
* **Errors** propagate: the first error met (left to right, row by row) is the result.
* **LibreOffice** (``ctx.dialect == "libreoffice"``) has no boolean type: a TRUE in a
  range is the number 1 there, and a text argument of an aggregate is #VALUE!.

Nothing here raises on bad data: Excel errors are returned.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache

from workbook_gen.formula.values import (
    Range, Value, checked, compare, number_to_text, rank, scalar_of, text_to_number, to_bool,
    to_number, to_text,
)
from workbook_gen.xlerror import ExcelError

__all__ = [
    "Range", "Value", "checked", "compare", "number_to_text", "rank", "scalar_of", "text_to_number",
    "to_bool", "to_number", "to_text", "is_error", "is_number", "flat", "number",
    "integer", "text", "numbers", "logicals", "result", "wildcard", "criterion",
    "as_area", "first_error", "values_a",
]


def is_error(v) -> bool:
    return isinstance(v, ExcelError)


def is_number(v) -> bool:
    """A plain number (booleans are not numbers to Excel's functions)."""
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def flat(v) -> list:
    """The values of an argument as a flat list (a scalar is one value)."""
    if isinstance(v, Range):
        return [x for row in v.rows for x in row]
    return [v]


def first_error(values) -> ExcelError | None:
    for v in values:
        if isinstance(v, ExcelError):
            return v
    return None


def first_pair_error(a: list, b: list, dialect: str = "excel") -> ExcelError | None:
    """The first error of two equal-length lists taken pair by pair (``a``'s, then
    ``b``'s). Excel passes over a pair whose first value is #NULL! when another error
    follows (as ``past_null``): the fits, a paired T.TEST."""
    skip = dialect == "excel"
    error = first_error(u for x, y in zip(a, b) if not (skip and x is ExcelError.NULL)
                        for u in (x, y))
    return error or (first_error(a) if skip else None)


def past_null(error, values):
    """Excel's tests and fits of two arrays (CHISQ.TEST, T.TEST, F.TEST, SLOPE, PEARSON
    ...) pass over a #NULL! when another error follows it in ``values`` (Mac Excel 16,
    formulas__test.xlsx STATISTICAL!AD17, AD26, AD107): that one, else ``error``."""
    if error is not ExcelError.NULL:
        return error
    return next((v for v in values if isinstance(v, ExcelError) and v is not ExcelError.NULL),
                error)


def number(v) -> float | ExcelError:
    """A direct argument as a number (a reference to one cell is that cell)."""
    return to_number(scalar_of(v))


def integer(v) -> int | ExcelError:
    """A direct argument truncated toward zero, as Excel's integer arguments are."""
    x = number(v)
    if isinstance(x, ExcelError):
        return x
    if abs(x) >= 2 ** 53:
        return ExcelError.NUM
    return int(x)


def text(v) -> str | ExcelError:
    """A direct argument as text (numbers in General format, TRUE as "TRUE")."""
    return to_text(scalar_of(v))


def numbers(args, ctx=None, *, strict_text: bool | None = None) -> list[float] | ExcelError:
    """The numbers of SUM-like arguments: ranges keep only numbers, direct arguments
    convert (booleans, numeric text); the first error wins.

    Under LibreOffice a boolean in a range counts as 1/0 and a direct text argument is
    #VALUE! (``strict_text`` overrides the latter).
    """
    lo = ctx is not None and ctx.dialect == "libreoffice"
    strict = lo if strict_text is None else strict_text
    out: list[float] = []
    for a in args:
        if isinstance(a, Range):
            fast = a.numbers()
            if fast is not None:
                out.extend(fast)
                continue
            for v in a.flat():
                if isinstance(v, ExcelError):
                    return v
                if is_number(v):
                    out.append(float(v))
                elif lo and isinstance(v, bool):
                    out.append(float(v))
            continue
        if strict and isinstance(a, str):
            return ExcelError.VALUE
        x = to_number(a)
        if isinstance(x, ExcelError):
            return x
        out.append(x)
    return out


def values_a(args) -> list[float] | ExcelError:
    """AVERAGEA/VARA-style numbers: in ranges text is 0, booleans 1/0, empty cells skipped;
    a direct argument converts (an omitted one is 0: LibreOffice gives AVERAGEA(1,,3) = 4/3,
    VARA(1,,3) = 7/3, MAXA(-1,,-3) = 0, tests/formula/functions/test_registry_more.py)."""
    out: list[float] = []
    for a in args:
        if isinstance(a, Range):
            for v in a.flat():
                if isinstance(v, ExcelError):
                    return v
                if v is not None:
                    out.append(0.0 if isinstance(v, str) else float(v))
            continue
        x = to_number(a)
        if isinstance(x, ExcelError):
            return x
        out.append(x)
    return out


def logicals(args, errors_first: bool = False) -> list[bool] | ExcelError:
    """Booleans for AND/OR/XOR: ranges skip text and empties, a direct text argument must
    be TRUE or FALSE; no logical value at all is #VALUE!. ``errors_first`` (Excel): a
    text argument's #VALUE! gives way to an error value among the later arguments (Mac
    Excel 16, formulas__test.xlsx LOGICAL!AS3: AND(TRUE,"ciao",#REF!,"0") is #REF!)."""
    out: list[bool] = []
    bad_text = None
    for a in args:
        if isinstance(a, Range):
            fast = a.numbers()
            if fast is not None:
                out.extend(x != 0 for x in fast)
                continue
            for v in a.flat():
                if isinstance(v, ExcelError):
                    return v
                if isinstance(v, (bool, int, float)):
                    out.append(bool(v))
            continue
        b = to_bool(a)
        if isinstance(b, ExcelError):
            if not (errors_first and isinstance(a, str)):
                return b
            bad_text = bad_text or b
            continue
        out.append(b)
    if bad_text is not None:
        return bad_text
    return out if out else ExcelError.VALUE


def result(x):
    """A float result made safe: #NUM! for inf/NaN, no negative zero; others unchanged."""
    if isinstance(x, float):
        if not math.isfinite(x):
            return ExcelError.NUM
        return 0.0 if x == 0 else x
    return x


def as_area(v) -> Range:
    """An argument as a Range (a single value is a 1x1 array)."""
    return v if isinstance(v, Range) else Range.array_of([[v]])


@lru_cache(maxsize=512)
def wildcard(pattern: str) -> re.Pattern:
    """Excel's wildcards: ``*`` any run, ``?`` one character, ``~`` escapes; whole text,
    case-insensitive."""
    out, i = [], 0
    while i < len(pattern):
        c = pattern[i]
        if c == "~" and i + 1 < len(pattern):
            out.append(re.escape(pattern[i + 1]))
            i += 1
        else:
            out.append(".*" if c == "*" else "." if c == "?" else re.escape(c))
        i += 1
    return re.compile("".join(out), re.IGNORECASE | re.DOTALL)


def has_wildcard(text: str) -> bool:
    return any(c in text for c in "*?~")


#: the comparison operators a criterion may open with, longest first
CRITERION_OPERATORS = ("<=", ">=", "<>", "=", "<", ">")


@lru_cache(maxsize=512)
def _criterion(kind: type, crit) -> "callable":
    from_text = kind is str  # "=5" (text) also matches the text "5"; the number 5 doesn't
    if kind is str:
        op = next((o for o in CRITERION_OPERATORS if crit.startswith(o)), "")
        body = crit[len(op):]
        target: Value = body
        # "" matches empty cells and empty text, "=" empty cells only, "<>" all but empty
        # cells: a formula's "" is not empty (LibreOffice 7.4 as Excel: COUNTIF of
        # {="",<empty>,"1",1} is 2 for "", 1 for "=" and 3 for "<>")
        if body == "" and op == "=":
            return lambda v: v is None
        if body == "" and op == "":
            return None
        if body == "" and op == "<>":
            return lambda v: v is not None
        x = text_to_number(body)
        if not isinstance(x, ExcelError):
            target = x
        elif body.upper() in ("TRUE", "FALSE"):
            target = body.upper() == "TRUE"
        elif ExcelError.from_text(body) is not None:
            target = ExcelError.from_text(body)
        op = op or "="
    else:
        op, target = "=", crit
    if isinstance(target, ExcelError):
        if op == "=":
            return lambda v: v is target
        if op == "<>":
            return lambda v: v is not target
        return lambda v: False
    if isinstance(target, str) and op in ("=", "<>") and has_wildcard(target):
        rx = wildcard(target)
        if op == "=":
            return lambda v: isinstance(v, str) and rx.fullmatch(v) is not None
        return lambda v: not (isinstance(v, str) and rx.fullmatch(v) is not None)
    tr = rank(target)
    tests = {"=": lambda c: c == 0, "<>": lambda c: c != 0, "<": lambda c: c < 0,
             ">": lambda c: c > 0, "<=": lambda c: c <= 0, ">=": lambda c: c >= 0}[op]

    def match(v):
        if v is None or isinstance(v, ExcelError):
            return op == "<>"
        if isinstance(v, str) and from_text and tr == 0 and op in ("=", "<>"):
            num = text_to_number(v)  # "=5" matches the text "5" as well as the number
            if not isinstance(num, ExcelError):
                return tests(compare(num, target))
        if rank(v) != tr:
            return op == "<>"
        return tests(compare(v, target))
    return match


def criterion(crit: Value):
    """A predicate for COUNTIF-style criteria: ``5``, ``">=5"``, ``"a*"``, ``"<>pear"``,
    ``""`` (empty cells and empty text), ``"="`` (empty cells), ``"<>"`` (all but empty
    cells), an error value (cells holding it)."""
    if isinstance(crit, ExcelError):  # counts the cells holding that error
        return lambda v: v is crit
    if crit is None:
        crit = 0.0
    if isinstance(crit, int) and not isinstance(crit, bool):
        crit = float(crit)
    pred = _criterion(type(crit), crit)
    if pred is None:  # "" : empty cells and empty text
        return lambda v: v is None or v == ""
    return pred
