"""Excel's error values as an Enum, so they are never confused with text."""

from __future__ import annotations

import enum


class ExcelError(enum.Enum):
    """An Excel error value; ``.value`` is the text Excel shows and stores."""

    NULL = "#NULL!"
    DIV0 = "#DIV/0!"
    VALUE = "#VALUE!"
    REF = "#REF!"
    NAME = "#NAME?"
    NUM = "#NUM!"
    NA = "#N/A"
    # Newer Excel errors (dynamic arrays, data types, connections); appended so
    # that the codes above keep their numbers.
    SPILL = "#SPILL!"
    CALC = "#CALC!"
    GETTING_DATA = "#GETTING_DATA"
    FIELD = "#FIELD!"
    BLOCKED = "#BLOCKED!"
    CONNECT = "#CONNECT!"
    BUSY = "#BUSY!"
    UNKNOWN = "#UNKNOWN!"
    # Not an Excel error: the evaluator's mark for a cell on (or fed by) a circular
    # reference (evaluator.cycles), shown as 0 (Excel) or #VALUE! (LibreOffice) once the
    # workbook is evaluated; never read from or written to a file.
    CIRC = "#CIRCULAR"

    @property
    def code(self) -> int:
        """Small positive integer used in numpy error masks (0 means no error)."""
        return _CODES[self]

    @classmethod
    def from_code(cls, code: int) -> "ExcelError":
        return _BY_CODE[code]

    @classmethod
    def from_text(cls, text: str) -> "ExcelError | None":
        """The error whose text is ``text`` (case-insensitive), or None."""
        return _BY_TEXT.get(text.strip().upper())

    def __str__(self) -> str:
        return self.value


#: SIN, COS and TAN of an argument this large or larger are #NUM! in Excel: the
#: kernels (xlmath/kernels.py, formula/functions/math.py) and the actuator's check of
#: its bracket (mechanisms/actuator_linkage.py) read it here.
TRIG_LIMIT = 2.0 ** 27


_CODES = {err: i + 1 for i, err in enumerate(ExcelError)}
_BY_CODE = {code: err for err, code in _CODES.items()}
_BY_TEXT = {err.value: err for err in ExcelError if err.name != "CIRC"}
