"""Excel's supported worksheet functions (scalar), over the values of ``formula.values``.

A reference argument arrives as a :class:`Range`. Nothing here raises on bad data:
Excel errors are returned and propagate (overflow gives #NUM!). IF and IFERROR take thunks so that only
the branch taken is evaluated.

``dialect="libreoffice"`` applies LibreOffice 7.4's measured deviations
(:data:`LIBREOFFICE_DIFFERENCES`), so an auditor can accept a value cached by
LibreOffice where only such a deviation explains it.
"""

from __future__ import annotations

import math
import re
from typing import Callable, NamedTuple

from workbook_gen.formula.values import (
    Range, Value, checked, compare, rank, scalar_of, to_bool, to_number,
)
from workbook_gen.xlerror import ExcelError


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
    """MOD(n, d) = n - d*INT(n/d); the result takes the sign of d; #NUM! if n/d overflows."""
    if d == 0:
        return ExcelError.DIV0
    q = n / d
    return n - d * math.floor(q) if math.isfinite(q) else ExcelError.NUM


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
            numbers = a.numbers()
            if numbers is not None:
                out.extend(numbers)
                continue
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
            numbers = a.numbers()
            if numbers is not None:
                out.extend(numbers)
                continue
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


def _sum(xs: list[float]) -> float:
    """Correctly rounded sum; NaN (so #NUM!) where it overflows."""
    try:
        return math.fsum(xs)
    except (OverflowError, ValueError):  # fsum raises instead of returning inf
        return math.nan


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
    if kind == 0 and type(lookup) is float and area.numbers() is not None:
        try:  # a number among plain numbers: list.index compares exactly, as below
            return float(values.index(lookup) + 1)
        except ValueError:
            return ExcelError.NA
    if kind == 0:
        pattern = _wildcard(lookup) if isinstance(lookup, str) and any(
            c in lookup for c in "*?~") else None
        for i, v in enumerate(values):
            if rank(v) != rank(lookup) or v is None or isinstance(v, ExcelError):
                continue
            if (pattern.fullmatch(v) is not None) if pattern else compare(v, lookup) == 0:
                found = i
                break
    else:
        # Sorted data assumed, as Excel does: last position not past the lookup value.
        want = (0, -1) if kind > 0 else (0, 1)
        for i, v in enumerate(values):
            if v is None or isinstance(v, ExcelError) or rank(v) != rank(lookup):
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
    "SUM": _aggregate(_sum),
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
