"""Reading a ``--design`` table: the rows of a CSV or of an xlsx file's first sheet.

A CSV is what a spreadsheet exports: its separator is ``,`` or ``;`` (the header
row tells which: the one that splits it into more cells; a single column of numbers
with a decimal comma is a ``;`` file), its text UTF-8 (a
byte-order mark allowed) or, failing that, Windows-1252 (what Excel's plain "CSV"
writes on Windows).  Excel in a locale with a decimal comma (German, French, ...)
writes ``;`` between cells and ``32,5`` for 32.5: in a ``;`` file a cell's decimal
comma is read as a point (``32.5`` is read as written too).
"""

from __future__ import annotations

import csv
import io
import re
from pathlib import Path

from ..errors import SceneError

# A number with a decimal comma: 32,5  -0,25  1,5E-3 (no thousands separators)
_DECIMAL_COMMA = re.compile(r"\s*[+-]?(\d+,\d*|,\d+)([eE][+-]?\d+)?\s*")


def _text(path: Path, where: str) -> str:
    data = path.read_bytes()
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        pass
    try:
        return data.decode("cp1252")
    except UnicodeDecodeError:
        raise SceneError(f"{where}: neither UTF-8 nor Windows-1252 text") from None


def separator(text: str) -> str:
    """``;`` when it splits the first non-blank line into more cells than ``,`` does,
    or when the table has one column (Excel then writes no separator at all) whose
    cells are numbers with a decimal comma; else ``,``."""
    lines = [line for line in text.splitlines() if line.strip()]
    first = lines[0] if lines else ""
    counts = {sep: len(next(csv.reader([first], delimiter=sep), [])) for sep in ",;"}
    if counts[";"] > counts[","]:
        return ";"
    if counts[","] == 1 and any(_DECIMAL_COMMA.fullmatch(line) for line in lines[1:]):
        return ";"
    return ","


def decimal_comma(cell: object) -> object:
    """A ``;``-file's cell: ``32,5`` as ``32.5``; any other cell as it is."""
    if isinstance(cell, str) and _DECIMAL_COMMA.fullmatch(cell):
        return cell.replace(",", ".")
    return cell


def design_rows(path: Path, where: str) -> tuple[list[list[object]], bool]:
    """The table's rows, cells as texts (CSV) or as openpyxl reads them (xlsx), and
    whether a number's text may have a decimal comma (a ``;`` CSV)."""
    suffix = path.suffix.lower()
    try:
        if suffix == ".csv":
            text = _text(path, where)
            sep = separator(text)
            return list(csv.reader(io.StringIO(text, newline=""), delimiter=sep)), sep == ";"
        if suffix in (".xlsx", ".xlsm"):
            import openpyxl
            book = openpyxl.load_workbook(path, read_only=True, data_only=True)
            try:
                sheet = book.worksheets[0]
                return [list(row) for row in sheet.iter_rows(values_only=True)], False
            finally:
                book.close()
    except SceneError:
        raise
    except OSError as exc:
        raise SceneError(f"{where}: cannot read: {exc.strerror or exc}") from None
    except csv.Error as exc:
        raise SceneError(f"{where}: not a readable CSV file ({exc})") from None
    except Exception as exc:  # openpyxl's many ways of refusing a file
        raise SceneError(f"{where}: not a readable xlsx file ({exc})") from None
    raise SceneError(f"{where}: expected a .csv or .xlsx file")
