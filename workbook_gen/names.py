"""Which names are legal defined names: Excel's rule, and the subset the generator writes.

Excel's rule, as Microsoft documents it (MS-XLSB 2.5.166 XLNameWideString; "Names in
formulas" on support.microsoft.com; KB 111393 "Some names are reserved"):
- 1 to 255 characters;
- first a letter (of any script), '_' or '\\'; then letters, digits, '_', '.', '\\', '?' and
  the Arabic question mark U+061F;
- not TRUE or FALSE, in any case;
- not an A1 cell reference (columns A to XFD, rows 1 to 1048576): ``A1``, ``AB2``, ``DF24``;
- not an R1C1 reference, nor beginning with one: ``R``, ``C``, ``RC``, ``R1C1``, ``C1_FOO``.

The auditor reports names in a file that break this rule; the generator writes only names
that keep it and are also plain ASCII identifiers (letters, digits, '_' and '.', starting
with a letter or '_'), so that every engine reads them the same way.
"""

from __future__ import annotations

import re

from .cellref import column_number
from .errors import IllegalNameError

_START = re.compile(r"[^\W\d]|\\")           # a letter of any script, '_' or '\'
_REST = re.compile(r"[\w.\\?\u061F]*")       # \w: letters, Unicode digits, '_'
_A1 = re.compile(r"([A-Za-z]{1,3})([0-9]+)")
_R1C1_WHOLE = re.compile(r"[Rr][0-9]*[Cc]?[0-9]*|[Cc][0-9]*")   # R, C, RC, R1C, RC1, R1C1
_R1C1_START = re.compile(r"[RrCc](\d+)")     # R1..., C1...: a row or column reference
_WRITER = re.compile(r"[A-Za-z_][A-Za-z0-9_.]*")
_MAX_COL = 16384  # XFD
_MAX_ROW = 1048576


def excel_name_problem(name: str) -> str | None:
    """Why Excel would refuse ``name`` as a defined name, or None if it is legal."""
    if not isinstance(name, str) or not name or len(name) > 255:
        return "a name has 1 to 255 characters"
    if not _START.match(name) or not _REST.fullmatch(name, 1):
        return ("a name starts with a letter, '_' or '\\' and holds only letters, digits, "
                "'_', '.', '\\' and '?'")
    a1 = _A1.fullmatch(name)
    if a1 and column_number(a1.group(1)) <= _MAX_COL and 1 <= int(a1.group(2)) <= _MAX_ROW:
        return "it is a cell reference"
    start = _R1C1_START.match(name)
    if _R1C1_WHOLE.fullmatch(name) or (start and int(start.group(1)) > 0):
        return "it reads as an R1C1 reference"
    if name.upper() in ("TRUE", "FALSE"):
        return "it is a boolean literal"
    return None


def name_problem(name: str) -> str | None:
    """Why the generator will not write ``name`` as a defined name, or None if it will."""
    if isinstance(name, str) and 0 < len(name) <= 255 and not _WRITER.fullmatch(name):
        return ("a name starts with a letter or underscore and holds only letters, digits, "
                "'_' and '.' (ASCII)")
    return excel_name_problem(name)


def check_name(name: str, where: str) -> None:
    """Raise IllegalNameError naming ``where`` (file and key) if ``name`` is illegal."""
    problem = name_problem(name)
    if problem:
        raise IllegalNameError(f"{where}: {name!r} is not a legal Excel name: {problem}")
