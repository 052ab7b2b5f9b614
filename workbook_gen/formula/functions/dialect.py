"""LibreOffice 7.4's measured deviations from Excel (xlsx recalculated and saved).

The evaluator follows Excel unless the workbook was saved by LibreOffice; then
``Context(dialect="libreoffice")`` applies these, and the coercion rules of
:mod:`coerce` that differ (a boolean in a range is a number; a text argument of an
aggregate is #VALUE!), and the operators' (``TRUE>1`` is FALSE, ``"x"&TRUE`` is "x1").
"""

from __future__ import annotations

import math
import re
from typing import NamedTuple

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.values import Value
from workbook_gen.xlerror import ExcelError


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
    Difference("LN of zero", "LN(0)", ExcelError.NUM, ExcelError.VALUE),
    Difference("a boolean in a range is a number", "SUM(A1:A2) with A1=TRUE, A2=2", 2.0, 3.0),
    Difference("text argument of an aggregate", 'SUM("3",4)', 7.0, ExcelError.VALUE),
    Difference("a boolean compared with a number", "TRUE>1", True, False),
    Difference("a boolean joined to text", '"x"&TRUE', "xTRUE", "x1"),
    Difference("zero to a negative power (^ and POWER)", "0^-1", ExcelError.DIV0,
               ExcelError.NUM),
    Difference("FIND and SEARCH of an empty text", 'FIND("","abc")', 1.0, ExcelError.VALUE),
    Difference("ROUND's digits beyond a 16-bit integer (ROUNDUP, ROUNDDOWN, TRUNC too)",
               "ROUND(10,32768)", 10.0, ExcelError.VALUE),
    Difference("ISEVEN and ISODD of a numeric text", 'ISEVEN("4")', True, ExcelError.VALUE),
    Difference("a numeric text or a boolean in an exact lookup", 'MATCH("10",{10},0)',
               ExcelError.NA, 1.0),
    Difference("ISNUMBER of a TRUE cell", "ISNUMBER(A1) with A1=TRUE", False, True),
    Difference("LEFT and RIGHT of a negative count above -1", 'LEFT("ab",-0.5)', "",
               ExcelError.VALUE),
    Difference("CODE of an empty text", 'CODE("")', ExcelError.VALUE, 0.0),
    Difference("an error as the criterion of COUNTIF, SUMIF, ...", "COUNTIF(A1:A3,NA())",
               0.0, ExcelError.NA),
    Difference("SUBSTITUTE of an empty text at instance 0", 'SUBSTITUTE("abc","","X",0)',
               "abc", ExcelError.VALUE),
)


def _odd_root(x: float, y: float) -> float | None:
    """LibreOffice's real odd root of a negative base, or None."""
    n = 1.0 / y
    k = round(n)
    if k % 2 == 1 and abs(n - k) <= 1e-12 * abs(n):
        return -math.pow(-x, y)
    return None


def dialect_of(application: str | None) -> str:
    """The semantics to recompute with, from docProps/app.xml's Application: "libreoffice"
    for LibreOffice / OpenOffice, else "excel" (Microsoft Excel, and unknown writers)."""
    text = (application or "").lower()
    return "libreoffice" if "libreoffice" in text or "openoffice" in text else "excel"


# Errors LibreOffice 7.4 gives where Excel gives another (measured: its "invalid argument"
# is saved as #VALUE!): function -> {Excel's error: LibreOffice's}.
_INVALID = {ExcelError.NUM: ExcelError.VALUE}
LIBREOFFICE_ERRORS: dict[str, dict[ExcelError, ExcelError]] = {
    **{name: _INVALID for name in (
        "LOG", "LOG10", "LN", "FACT", "ATANH", "ACOSH", "LARGE", "SMALL", "DEC2BIN", "DEC2OCT",
        "DEC2HEX", "HEX2BIN", "HEX2OCT", "OCT2BIN", "BIN2DEC", "HEX2DEC", "OCT2DEC",
        "BIN2HEX", "BIN2OCT", "OCT2HEX", "SQRT", "COMBIN", "PERMUT", "PERCENTILE",
        "PERCENTILE.INC", "PERCENTILE.EXC", "QUARTILE", "QUARTILE.INC", "QUARTILE.EXC")},
    "QUOTIENT": {ExcelError.DIV0: ExcelError.VALUE},
    # measured by the differential test (tests/differential.py): CEILING(5,-2)
    "CEILING": _INVALID, "MEDIAN": _INVALID,
    "FLOOR": {ExcelError.NUM: ExcelError.VALUE, ExcelError.DIV0: ExcelError.VALUE},
    "MODE": {ExcelError.NA: ExcelError.VALUE},
    "MODE.SNGL": {ExcelError.NA: ExcelError.VALUE},
    "CONVERT": {ExcelError.NA: ExcelError.VALUE},
    "VLOOKUP": {ExcelError.REF: ExcelError.VALUE},
    "HLOOKUP": {ExcelError.REF: ExcelError.VALUE},
    "INDEX": {ExcelError.REF: ExcelError.VALUE},
    # measured on tests/formula/functions/test_registry_more.py's cases (a name and its
    # aliases share the code)
    **{name: _INVALID for name in (
        "BETA.DIST", "BETADIST", "BINOM.DIST", "BINOMDIST", "POISSON", "POISSON.DIST",
        "CHISQ.DIST", "EXPONDIST", "EXPON.DIST", "GAMMALN", "GAMMALN.PRECISE", "GAMMA",
        "GEOMEAN", "HARMEAN", "T.TEST", "TTEST", "IMABS", "IMLN", "IMDIV", "BITAND", "BITOR",
        "BITXOR", "ACOTH", "VDB", "CUMPRINC", "CUMIPMT")},
    **{name: {ExcelError.DIV0: ExcelError.VALUE} for name in ("MIRR", "DOLLARFR", "DOLLARDE")},
    **{name: {ExcelError.NA: ExcelError.VALUE} for name in (
        "SUMXMY2", "SUMX2MY2", "SUMX2PY2", "PERCENTRANK", "PERCENTRANK.INC", "PERCENTRANK.EXC")},
    "DGET": {ExcelError.NUM: ExcelError.VALUE},
    # two areas of different sizes: Microsoft's #N/A ("a different number of data points",
    # support.microsoft.com SLOPE, CORREL, ...), LibreOffice 7.4's #VALUE! (measured)
    **{name: {ExcelError.NA: ExcelError.VALUE} for name in (
        "SLOPE", "INTERCEPT", "FORECAST", "FORECAST.LINEAR", "CORREL", "PEARSON", "RSQ",
        "STEYX", "COVAR", "COVARIANCE.P", "COVARIANCE.S")},
    **{name: {**_INVALID, ExcelError.NA: ExcelError.VALUE} for name in ("T.TEST", "TTEST")},
}


def libreoffice_error(name: str, result, args=()):
    """LibreOffice's error for the error ``result`` that ``name`` raised itself (an error
    passed on from an argument stays as it is); any other result unchanged."""
    if not isinstance(result, ExcelError) or result not in LIBREOFFICE_ERRORS.get(name, {}):
        return result
    for a in args:
        if not callable(a) and any(v is result for v in c.flat(a)):
            return result  # propagated, not raised here
    return LIBREOFFICE_ERRORS[name][result]


_DIGITS = frozenset({"ROUND", "ROUNDUP", "ROUNDDOWN", "TRUNC"})
NUMERIC_DEVIATIONS = frozenset({"SQRT", "ATAN2", "POWER", "LN"}) | _DIGITS


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
    if name in _DIGITS and len(args) == 2 and not -32768 <= math.trunc(args[1]) <= 32767:
        return ExcelError.VALUE  # its digits are a 16-bit integer (ROUND(10,32768))
    if name == "POWER" and len(args) == 2:
        x, y = args
        if x == 0 and y == 0:
            return 1.0
        if x == 0 and y < 0:
            return ExcelError.NUM
        if x < 0 and y != math.floor(y):
            return _odd_root(x, y)
    return None


def numeric_deviation(name: str, args: list) -> Value | None:
    """The deviation for a call of ``name`` on (not yet coerced) arguments, or None."""
    if name not in NUMERIC_DEVIATIONS:
        return None
    xs = [c.number(a) for a in args]
    if any(isinstance(x, ExcelError) for x in xs):
        return None
    return libreoffice_result(name, xs)


_PLAIN_NUMBER = re.compile(r"-?(0|[1-9][0-9]*)(\.[0-9]+)?")


def lookup_plain(v):
    """A value as LibreOffice's exact lookups compare it: a boolean is its number and a
    plain numeric text the number (MATCH("10",{10},0) is 1 there; not "007", " 3 " or
    "1e2"; measured by tests/differential.py)."""
    if isinstance(v, bool):
        return float(v)
    if isinstance(v, str) and _PLAIN_NUMBER.fullmatch(v):
        return float(v)
    return v


def exact_lookup(ctx, lookup, values: list, first: bool = False):
    """(lookup, values) as an exact MATCH (``first``: VLOOKUP's rows, by their first
    cell) compares them in ``ctx``'s dialect: unchanged but in LibreOffice's."""
    if getattr(ctx, "dialect", ctx) != "libreoffice":
        return lookup, values
    if first:
        return lookup_plain(lookup), [(lookup_plain(r[0]), *r[1:]) for r in values]
    return lookup_plain(lookup), [lookup_plain(v) for v in values]
