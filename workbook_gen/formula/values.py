"""Excel's values and their coercions, shared by operators and functions.

A value is ``float | str | bool | None | ExcelError`` (None is an empty cell); a
reference arrives as a :class:`Range`. Nothing here raises on bad data: Excel
errors are returned.
"""

from __future__ import annotations

from itertools import chain

import math
import re
from dataclasses import dataclass, field
from typing import NamedTuple

from workbook_gen.xlerror import ExcelError

Value = float | str | bool | None | ExcelError


class Ref(NamedTuple):
    """Where a Range came from: a rectangle of a sheet (1-based, inclusive corners).

    ``sheet`` is None for the sheet of the formula being evaluated. Functions that
    need the reference itself (ROW, COLUMN, ROWS, COLUMNS, OFFSET, implicit
    intersection) read it from :attr:`Range.ref`.
    """

    sheet: str | None
    row1: int
    col1: int
    row2: int
    col2: int

    @property
    def shape(self) -> tuple[int, int]:
        return self.row2 - self.row1 + 1, self.col2 - self.col1 + 1


@dataclass(frozen=True, slots=True)
class Range:
    """The values of a reference, row by row (a single cell reference is 1x1), or of an
    array (``array=True``: a function's or an array constant's result, no ``ref``)."""

    rows: tuple[tuple[Value, ...], ...]
    _numbers: object = field(default=False, compare=False, repr=False)  # cache of numbers()
    ref: Ref | None = field(default=None, compare=False)
    array: bool = field(default=False, compare=False)
    # a union's areas, each a Ref (its values are theirs in one column); () for the rest
    areas: tuple = field(default=(), compare=False)

    @classmethod
    def of(cls, rows, ref: Ref | None = None) -> "Range":
        return cls(tuple(map(tuple, rows)), ref=ref)

    @classmethod
    def array_of(cls, rows) -> "Range":
        """An array value (not a reference): used as one value it gives its first item."""
        return cls(tuple(map(tuple, rows)), array=True)

    def with_ref(self, ref: Ref) -> "Range":
        """The same values, known to come from ``ref`` (the numbers cache is shared)."""
        return Range(self.rows, self._numbers, ref, False)

    @property
    def shape(self) -> tuple[int, int]:
        return len(self.rows), (len(self.rows[0]) if self.rows else 0)

    def flat(self):
        """The values row by row, one iterator (at C speed)."""
        return chain.from_iterable(self.rows)

    def numbers(self) -> list[float] | None:
        """All values as a flat list when every one is a plain number, else None
        (the fast path of MIN, MAX, SUM and MATCH over a column of results)."""
        if self._numbers is False:
            flat = list(self.flat())
            kinds = set(map(type, flat))  # (C loops: MAX of a 100,000-row column)
            numbers = flat if kinds == {float} or not flat else None
            object.__setattr__(self, "_numbers", numbers)
        return self._numbers


def checked(x: float) -> float | ExcelError:
    """``x``, or #NUM! if it overflowed to infinity or is NaN."""
    return x if math.isfinite(x) else ExcelError.NUM


def to_number(v: Value) -> float | ExcelError:
    """Arithmetic coercion: bool -> 1/0, empty -> 0, numeric text -> number."""
    if isinstance(v, ExcelError):
        return v
    if isinstance(v, bool):
        return 1.0 if v else 0.0
    if v is None:
        return 0.0
    if isinstance(v, (int, float)):
        return float(v)
    return text_to_number(v)


# Excel reads currency and thousands separators as numbers: VALUE("$1,000") is 1000
# (Microsoft's VALUE page), DOLLAR("$1.00") is "$1.00" (POI FormulaEvalTestData.xlsx L420)
_CURRENCY = re.compile(r"^([+-]?)\$\s*")
_GROUPED = re.compile(r"[+-]?\d{1,3}(,\d{3})+(\.\d*)?([eE][+-]?\d+)?")


def text_to_number(text: str) -> float | ExcelError:
    """``" 2 "`` -> 2.0, ``"50%"`` -> 0.5, ``"1e3"`` -> 1000.0, ``"$1,000"`` -> 1000.0,
    else #VALUE!."""
    s = _CURRENCY.sub(r"\1", text.strip())
    scale = 1.0
    if s.endswith("%"):
        s, scale = s[:-1].strip(), 0.01
    if "," in s and _GROUPED.fullmatch(s):
        s = s.replace(",", "")
    if not s or not all(c in "0123456789.eE+-" for c in s):  # rejects inf, nan, 0x..
        return _date_text(text)
    try:
        x = float(s) * scale
    except ValueError:
        return _date_text(text)
    return x if math.isfinite(x) else ExcelError.VALUE  # "1E999" is text to Excel


def _date_text(text: str) -> float | ExcelError:
    """Text that reads as a date or a time is its serial number ("2020-03-01" + 0)."""
    if not any(ch.isdigit() for ch in text):
        return ExcelError.VALUE
    from workbook_gen.formula.functions.datetext import parse_date_text
    return parse_date_text(text)


def to_bool(v: Value) -> bool | ExcelError:
    """Logical coercion (IF, NOT): number != 0, "TRUE"/"FALSE" text, empty is FALSE."""
    if isinstance(v, ExcelError) or isinstance(v, bool):
        return v
    if v is None:
        return False
    if isinstance(v, (int, float)):
        return v != 0
    upper = v.strip().upper()
    if upper in ("TRUE", "FALSE"):
        return upper == "TRUE"
    return ExcelError.VALUE


def number_to_text(x: float) -> str:
    """Excel's number-to-text rule (``&``, text functions): 15 significant digits, no
    ``.0``; a number below 1 in full ("0.00001") while that takes at most 20 characters,
    else in E notation ("5.67890123456E-08"); from 1 in full up to 20 digits before the
    point ("12345678901234600000"), else E notation ("1.23456789012346E+20"). Measured in
    Excel by Apache POI (NumberToTextConverter's table); POI FormulaEvalTestData.xlsx:
    SEARCH(1, 0.00001) is 7."""
    if x == 0 or abs(x) < 2.2250738585072014e-308:  # denormals show as 0
        return "0"
    sign = "-" if x < 0 else ""
    mantissa, exponent = f"{abs(x):.14e}".split("e")
    exp = int(exponent)
    digits = mantissa.replace(".", "").rstrip("0")
    if exp < 0:
        text = "0." + "0" * (-exp - 1) + digits
        if len(text) <= 20:
            return sign + text
    elif exp <= 19:
        if len(digits) > exp + 1:
            return sign + digits[:exp + 1] + "." + digits[exp + 1:]
        return sign + digits + "0" * (exp + 1 - len(digits))
    head = digits[0] + ("." + digits[1:] if len(digits) > 1 else "")
    return f"{sign}{head}E{'-' if exp < 0 else '+'}{abs(exp):02d}"


def to_text(v: Value) -> str | ExcelError:
    if isinstance(v, ExcelError):
        return v
    if v is None:
        return ""
    if isinstance(v, bool):
        return "TRUE" if v else "FALSE"
    if isinstance(v, str):
        return v
    return number_to_text(float(v))


def rank(v: Value) -> int:
    """Type order for comparisons: number 0, text 1, boolean 2."""
    if isinstance(v, bool):
        return 2
    if isinstance(v, str):
        return 1
    return 0


def compare(a: Value, b: Value) -> int | ExcelError:
    """-1, 0 or 1 in Excel's order: numbers < text < booleans, text case-insensitive.

    An empty operand takes the type of the other (0, "" or FALSE).
    """
    for v in (a, b):
        if isinstance(v, ExcelError):
            return v
    if a is None:
        a = b.__class__() if b is not None else 0.0
    if b is None:
        b = a.__class__()
    ra, rb = rank(a), rank(b)
    if ra != rb:
        return -1 if ra < rb else 1
    if ra == 1:
        a, b = a.lower(), b.lower()
    elif ra == 0:
        a, b = float(a), float(b)
    return (a > b) - (a < b)


def scalar_of(v) -> Value:
    """A Range used where one value is expected: its single cell (an array: its first
    item), else #VALUE!."""
    if isinstance(v, Range):
        if v.shape == (1, 1) or (v.array and v.rows and v.rows[0]):
            return v.rows[0][0]
        return ExcelError.VALUE
    return v
