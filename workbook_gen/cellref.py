"""Cell references in A1 form: column letters and numbers, a cell's name with its sheet.

The one place these conversions live: the reader, the parser, the evaluator, the auditor,
the names rule and the writers (the workbook, the batch summary) use them, not XlsxWriter's
utilities (tests/test_cellref.py checks them against openpyxl's and XlsxWriter's).
Rows and columns are 1-based here; XlsxWriter's calls take 0-based ones."""

from __future__ import annotations

import re
from functools import lru_cache


@lru_cache(maxsize=4096)
def column_letters(col: int, absolute: bool = False) -> str:
    """1 -> ``A``, 28 -> ``AB``, 16384 -> ``XFD``; ``$A`` if ``absolute``."""
    letters = ""
    while col > 0:
        col, rem = divmod(col - 1, 26)
        letters = chr(65 + rem) + letters
    return "$" + letters if absolute else letters


def column_number(letters: str) -> int:
    """``A`` -> 1, ``xfd`` -> 16384 (either case)."""
    number = 0
    for ch in letters.upper():
        number = number * 26 + ord(ch) - 64
    return number


def a1(row: int, col: int, absolute: bool = False) -> str:
    """(1, 1) -> ``A1`` (``$A$1`` if ``absolute``): 1-based row and column."""
    if absolute:
        return f"${column_letters(col)}${row}"
    return f"{column_letters(col)}{row}"


def quoted_sheet(sheet: str) -> str:
    """The sheet name before ``!``: quoted unless letters, digits and underscores only."""
    return sheet if sheet.replace("_", "").isalnum() else "'" + sheet.replace("'", "''") + "'"


def cell_name(key: tuple[str, int, int]) -> str:
    """(sheet, row, col), 1-based -> ``Sheet!B3`` (``'My sheet'!B3``)."""
    return f"{quoted_sheet(key[0])}!{a1(key[1], key[2])}"


_CELL = re.compile(r"\$?([A-Za-z]{1,3})\$?([0-9]+)")


def row_col(text: str) -> tuple[int, int]:
    """``B3`` or ``$B$3`` -> (3, 2), 1-based; ValueError if ``text`` is not a cell."""
    m = _CELL.fullmatch(text)
    if m is None:
        raise ValueError(f"not a cell reference: {text!r}")
    return int(m.group(2)), column_number(m.group(1))
