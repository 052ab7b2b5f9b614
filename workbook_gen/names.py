"""Which names are legal defined names in both Excel and LibreOffice."""

from __future__ import annotations

import re

from .cellref import column_number
from .errors import IllegalNameError

_SHAPE = re.compile(r"^[A-Za-z_][A-Za-z0-9_.]*$")
_A1 = re.compile(r"^\$?([A-Za-z]{1,3})\$?([0-9]+)$")
_R1C1 = re.compile(r"^[Rr]([0-9]*)[Cc]?([0-9]*)$|^[Cc][0-9]*$")
_MAX_COL = 16384  # XFD
_MAX_ROW = 1048576


def name_problem(name: str) -> str | None:
    """Why ``name`` is not a legal defined name, or None if it is legal."""
    if not isinstance(name, str) or not name:
        return "a name must be a non-empty string"
    if len(name) > 255:
        return "a name is at most 255 characters"
    if not _SHAPE.match(name):
        return ("a name starts with a letter or underscore and holds only letters, digits, "
                "'_' and '.'")
    a1 = _A1.match(name)
    if a1 and column_number(a1.group(1)) <= _MAX_COL and 1 <= int(a1.group(2)) <= _MAX_ROW:
        return "it is a cell reference"
    if _R1C1.match(name):
        return "it reads as an R1C1 reference"
    if name.upper() in ("TRUE", "FALSE"):
        return "it is a boolean literal"
    return None


def check_name(name: str, where: str) -> None:
    """Raise IllegalNameError naming ``where`` (file and key) if ``name`` is illegal."""
    problem = name_problem(name)
    if problem:
        raise IllegalNameError(f"{where}: {name!r} is not a legal Excel name: {problem}")
