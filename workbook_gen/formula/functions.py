"""Excel's values, coercions and the supported worksheet functions (scalar).

A value is ``float | str | bool | None | ExcelError`` (None is an empty cell); a
reference argument arrives as a :class:`Range`. Nothing here raises on bad data:
Excel errors are returned and propagate. IF and IFERROR take thunks so that only
the branch taken is evaluated.

``dialect="libreoffice"`` applies LibreOffice 7.4's measured deviations
(:data:`LIBREOFFICE_DIFFERENCES`), so an auditor can accept a value cached by
LibreOffice where only such a deviation explains it.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Callable, NamedTuple

from workbook_gen.xlerror import ExcelError

Value = float | str | bool | None | ExcelError


@dataclass(frozen=True, slots=True)
class Range:
    """The values of a reference, row by row (a single cell reference is 1x1)."""

    rows: tuple[tuple[Value, ...], ...]

    @classmethod
    def of(cls, rows) -> "Range":
        return cls(tuple(tuple(r) for r in rows))

    @property
    def shape(self) -> tuple[int, int]:
        return len(self.rows), (len(self.rows[0]) if self.rows else 0)

    def flat(self):
        for row in self.rows:
            yield from row


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


def text_to_number(text: str) -> float | ExcelError:
    """``" 2 "`` -> 2.0, ``"50%"`` -> 0.5, ``"1e3"`` -> 1000.0, else #VALUE!."""
    s = text.strip()
    scale = 1.0
    if s.endswith("%"):
        s, scale = s[:-1].strip(), 0.01
    if not s or not all(c in "0123456789.eE+-" for c in s):  # rejects inf, nan, 0x..
        return ExcelError.VALUE
    try:
        return float(s) * scale
    except ValueError:
        return ExcelError.VALUE


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
    """Excel's General format as used by ``&``: 15 significant digits, no ``.0``."""
    if x == 0:
        return "0"
    if x == int(x) and abs(x) < 1e15:
        return str(int(x))
    text = f"{x:.15g}"
    if "e" in text:
        mantissa, exponent = text.split("e")
        sign = exponent[0]
        digits = exponent[1:].lstrip("0").rjust(2, "0")
        text = f"{mantissa}E{sign}{digits}"
    return text


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


def _rank(v: Value) -> int:
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
    ra, rb = _rank(a), _rank(b)
    if ra != rb:
        return -1 if ra < rb else 1
    if ra == 1:
        a, b = a.lower(), b.lower()
    elif ra == 0:
        a, b = float(a), float(b)
    return (a > b) - (a < b)


# -- arithmetic shared by operators and functions ------------------------------------

def power(x: float, y: float) -> float | ExcelError:
    """Excel's ``x^y`` and POWER: 0^0 #NUM!, 0^-n #DIV/0!, (-x)^fraction #NUM!."""
    if x == 0:
        if y == 0:
            return ExcelError.NUM
        return ExcelError.DIV0 if y < 0 else 0.0
    if x < 0 and y != math.floor(y):
        return ExcelError.NUM
    try:
        return checked(math.pow(x, y))
    except OverflowError:
        return ExcelError.NUM


def scalar_of(v) -> Value:
    """A Range used where one value is expected: its single cell, else #VALUE!."""
    if isinstance(v, Range):
        return v.rows[0][0] if v.shape == (1, 1) else ExcelError.VALUE
    return v


def _numbers(args, n: int):
    """Coerce ``args`` to ``n`` floats, or return the first error met."""
    if len(args) != n:
        return ExcelError.VALUE
    out = []
    for a in args:
        x = to_number(scalar_of(a))
        if isinstance(x, ExcelError):
            return x
        out.append(x)
    return out


def _math1(fn: Callable[[float], float | ExcelError]):
    def call(args):
        xs = _numbers(args, 1)
        return xs if isinstance(xs, ExcelError) else _result(fn(xs[0]))
    return call


def _math2(fn: Callable[[float, float], float | ExcelError]):
    def call(args):
        xs = _numbers(args, 2)
        return xs if isinstance(xs, ExcelError) else _result(fn(*xs))
    return call


def _result(x):
    return x if isinstance(x, ExcelError) else checked(x)


_TRIG_LIMIT = 2.0 ** 27  # Excel's SIN, COS, TAN give #NUM! from here on


def _trig(fn):
    return lambda x: ExcelError.NUM if abs(x) >= _TRIG_LIMIT else fn(x)


def _domain(fn, lo, hi):
    return lambda x: fn(x) if lo <= x <= hi else ExcelError.NUM


def _atan2(x: float, y: float):
    """Excel's ATAN2(x, y): x first; (0, 0) is #DIV/0!."""
    return ExcelError.DIV0 if x == 0 and y == 0 else math.atan2(y, x)


def _mod(n: float, d: float):
    """MOD(n, d) = n - d*INT(n/d); the result takes the sign of d."""
    return ExcelError.DIV0 if d == 0 else n - d * math.floor(n / d)


def _sign(x: float) -> float:
    return float((x > 0) - (x < 0))


def _pi(args):
    return math.pi if not args else ExcelError.VALUE


# -- logical and aggregate functions ------------------------------------------------

def _logicals(args):
    """Booleans for AND/OR: ranges skip text and empties, literal text must be TRUE/FALSE."""
    out = []
    for a in args:
        if isinstance(a, Range):
            for v in a.flat():
                if isinstance(v, ExcelError):
                    return v
                if isinstance(v, (bool, int, float)) and v is not None:
                    out.append(bool(v))
            continue
        b = to_bool(a)
        if isinstance(b, ExcelError):
            return b
        out.append(b)
    return out if out else ExcelError.VALUE


def _and(args):
    bs = _logicals(args)
    return bs if isinstance(bs, ExcelError) else all(bs)


def _or(args):
    bs = _logicals(args)
    return bs if isinstance(bs, ExcelError) else any(bs)


def _not(args):
    if len(args) != 1:
        return ExcelError.VALUE
    b = to_bool(scalar_of(args[0]))
    return b if isinstance(b, ExcelError) else not b


def _aggregate_numbers(args):
    """Numbers for MIN/MAX/SUM: ranges keep only numbers, literals are coerced."""
    out = []
    for a in args:
        if isinstance(a, Range):
            for v in a.flat():
                if isinstance(v, ExcelError):
                    return v
                if isinstance(v, (int, float)) and not isinstance(v, bool):
                    out.append(float(v))
            continue
        x = to_number(a)
        if isinstance(x, ExcelError):
            return x
        out.append(x)
    return out


def _aggregate(fn):
    def call(args):
        if not args:
            return ExcelError.VALUE
        xs = _aggregate_numbers(args)
        if isinstance(xs, ExcelError):
            return xs
        return checked(fn(xs)) if xs else 0.0
    return call


def _iserror(args):
    return ExcelError.VALUE if len(args) != 1 else isinstance(scalar_of(args[0]), ExcelError)


# -- lookup ---------------------------------------------------------------------------

def _index(args):
    if not 2 <= len(args) <= 3:
        return ExcelError.VALUE
    area = args[0] if isinstance(args[0], Range) else Range.of([[args[0]]])
    idx = _numbers(args[1:], len(args) - 1)
    if isinstance(idx, ExcelError):
        return idx
    nrows, ncols = area.shape
    row, col = (int(i) for i in idx) if len(idx) == 2 else (int(idx[0]), 0)
    if len(idx) == 1 and nrows == 1:
        row, col = 1, row  # one index into a single row selects a column
    if row < 0 or col < 0:
        return ExcelError.VALUE
    if row > nrows or col > ncols:
        return ExcelError.REF
    rows = range(nrows) if row == 0 else [row - 1]
    cols = range(ncols) if col == 0 else [col - 1]
    if len(rows) != 1 or len(cols) != 1:
        return ExcelError.VALUE  # a whole row or column: an array, not a scalar
    return area.rows[rows[0]][cols[0]]


def _wildcard(pattern: str) -> re.Pattern:
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


def _match(args):
    if not 2 <= len(args) <= 3:
        return ExcelError.VALUE
    lookup = scalar_of(args[0])
    if isinstance(lookup, ExcelError):
        return lookup
    if lookup is None:
        return ExcelError.NA
    kind = 1.0
    if len(args) == 3:
        kind = to_number(scalar_of(args[2]))
        if isinstance(kind, ExcelError):
            return kind
    area = args[1] if isinstance(args[1], Range) else Range.of([[args[1]]])
    if 1 not in area.shape:
        return ExcelError.NA
    values = list(area.flat())
    found = None
    if kind == 0:
        pattern = _wildcard(lookup) if isinstance(lookup, str) and any(
            c in lookup for c in "*?~") else None
        for i, v in enumerate(values):
            if _rank(v) != _rank(lookup) or v is None or isinstance(v, ExcelError):
                continue
            if (pattern.fullmatch(v) is not None) if pattern else compare(v, lookup) == 0:
                found = i
                break
    else:
        # Sorted data assumed, as Excel does: last position not past the lookup value.
        want = (0, -1) if kind > 0 else (0, 1)
        for i, v in enumerate(values):
            if v is None or isinstance(v, ExcelError) or _rank(v) != _rank(lookup):
                continue
            if compare(v, lookup) in want:
                found = i
            else:
                break
    return ExcelError.NA if found is None else float(found + 1)


# -- lazy functions: arguments are thunks ------------------------------------------------

def _if(thunks):
    if not 1 <= len(thunks) <= 3:
        return ExcelError.VALUE
    cond = to_bool(scalar_of(thunks[0]()))
    if isinstance(cond, ExcelError):
        return cond
    if cond:
        return thunks[1]() if len(thunks) > 1 else True
    return thunks[2]() if len(thunks) > 2 else False


def _iferror(thunks):
    if len(thunks) != 2:
        return ExcelError.VALUE
    v = scalar_of(thunks[0]())
    return thunks[1]() if isinstance(v, ExcelError) else v


EAGER: dict[str, Callable] = {
    "SIN": _math1(_trig(math.sin)),
    "COS": _math1(_trig(math.cos)),
    "TAN": _math1(_trig(math.tan)),
    "ASIN": _math1(_domain(math.asin, -1.0, 1.0)),
    "ACOS": _math1(_domain(math.acos, -1.0, 1.0)),
    "ATAN": _math1(math.atan),
    "ATAN2": _math2(_atan2),
    "SQRT": _math1(_domain(math.sqrt, 0.0, math.inf)),
    "ABS": _math1(abs),
    "SIGN": _math1(_sign),
    "PI": _pi,
    "RADIANS": _math1(math.radians),
    "DEGREES": _math1(math.degrees),
    "MOD": _math2(_mod),
    "POWER": _math2(power),
    "AND": _and,
    "OR": _or,
    "NOT": _not,
    "MIN": _aggregate(min),
    "MAX": _aggregate(max),
    "SUM": _aggregate(math.fsum),
    "INDEX": _index,
    "MATCH": _match,
    "ISERROR": _iserror,
}
LAZY: dict[str, Callable] = {"IF": _if, "IFERROR": _iferror}
SUPPORTED = frozenset(EAGER) | frozenset(LAZY)


# -- LibreOffice 7.4 deviations (measured: xlsx recalculated and saved) -------------------

class Difference(NamedTuple):
    situation: str
    example: str
    excel: Value
    libreoffice: Value


LIBREOFFICE_DIFFERENCES: tuple[Difference, ...] = (
    Difference("SQRT of a negative number", "SQRT(-1)", ExcelError.NUM, ExcelError.VALUE),
    Difference("ATAN2 of two zeros", "ATAN2(0,0)", ExcelError.DIV0, 0.0),
    Difference("zero to the power zero (^ and POWER)", "0^0", ExcelError.NUM, 1.0),
    Difference("negative base, exponent 1/odd integer", "(-8)^(1/3)", ExcelError.NUM, -2.0),
    Difference("LN of zero (not a supported function)", "LN(0)", ExcelError.NUM, ExcelError.VALUE),
)


def _odd_root(x: float, y: float) -> float | None:
    """LibreOffice's real odd root of a negative base, or None."""
    n = 1.0 / y
    k = round(n)
    if k % 2 == 1 and abs(n - k) <= 1e-12 * abs(n):
        return -math.pow(-x, y)
    return None


def libreoffice_result(func: str, args) -> Value | None:
    """LibreOffice's result of ``func`` (a function name, or ``"^"``) on numeric
    ``args`` where it differs from Excel's; None where the two agree."""
    name = "POWER" if func == "^" else func.upper()
    if name == "SQRT" and len(args) == 1 and args[0] < 0:
        return ExcelError.VALUE
    if name == "ATAN2" and len(args) == 2 and args[0] == 0 and args[1] == 0:
        return 0.0
    if name == "LN" and len(args) == 1 and args[0] == 0:
        return ExcelError.VALUE
    if name == "POWER" and len(args) == 2:
        x, y = args
        if x == 0 and y == 0:
            return 1.0
        if x < 0 and y != math.floor(y):
            return _odd_root(x, y)
    return None


def call(name: str, args: list, dialect: str = "excel") -> Value:
    """Apply the eager function ``name`` (upper-case, supported) to evaluated args."""
    if dialect == "libreoffice" and name in ("SQRT", "ATAN2", "POWER"):
        xs = _numbers(args, len(args))
        if not isinstance(xs, ExcelError):
            deviation = libreoffice_result(name, xs)
            if deviation is not None:
                return deviation
    return EAGER[name](args)
