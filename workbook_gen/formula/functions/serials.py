"""Serial numbers and calendar dates in the workbook's date system.

Excel counts days from one of two epochs, chosen per workbook (``workbookPr date1904``):

* the 1900 system: serial 1 is 1900-01-01, serial 60 the 29 February 1900 that never was
  (Lotus 1-2-3's leap-year bug, kept by Excel) and serial 0 is 1900-01-00; from serial 61
  on a serial counts the days since 1899-12-30. Weekdays follow the serials, so before
  March 1900 they are a day early (serial 1 is a Sunday).
* the 1904 system (Excel for Mac's old default): serial 0 is 1904-01-01, a Friday; a 1904
  serial is the 1900 serial of the same day less 1,462, and the last day, 9999-12-31, is
  2,957,003. Serials below 0 are not dates (DATE(1903,12,31) is #NUM!).

The system of the workbook being evaluated is a context variable that the evaluator sets
(``with date_system(book.date1904):``), as :mod:`decimal` keeps its context: every
conversion between serials and dates (DATE, YEAR, WEEKDAY, EDATE, DATEVALUE, the date
arguments of the day-count and coupon functions, dates read from text, TEXT's date
formats, TODAY and NOW, the audit's reading of the file's save time) goes through this
module and so honours it. Outside an evaluation the 1900 system applies.
"""

from __future__ import annotations

import contextlib
import contextvars
import datetime as dt
import math

from workbook_gen.xlerror import ExcelError

_EPOCH = dt.date(1899, 12, 30)
_EPOCH_MOMENT = dt.datetime(1899, 12, 30)
_EPOCH_1904 = dt.date(1904, 1, 1)
OFFSET_1904 = 1462  # days from serial 0 of 1904 back to the 1900 system's serial of that day
MAX_SERIAL_1900 = 2958465  # 9999-12-31 in the 1900 system

_DATE1904: contextvars.ContextVar[bool] = contextvars.ContextVar("date1904", default=False)


@contextlib.contextmanager
def date_system(date1904: bool):
    """Evaluate in the 1904 date system (``True``) or the 1900 one, within the block."""
    token = _DATE1904.set(bool(date1904))
    try:
        yield
    finally:
        _DATE1904.reset(token)


def is_1904() -> bool:
    return _DATE1904.get()


def offset() -> int:
    """What a serial of the current system adds to become a 1900 serial (0 or 1462)."""
    return OFFSET_1904 if _DATE1904.get() else 0


def max_serial() -> int:
    """The serial of 9999-12-31, Excel's last day."""
    return MAX_SERIAL_1900 - offset()


def to_serial(d: dt.date) -> float:
    """The serial of a calendar day; in the 1904 system days before 1904 count back on the
    true calendar (negative: DATE(1900,1,1500) is 1904-02-09, serial 39)."""
    if _DATE1904.get():
        return float((d - _EPOCH_1904).days)
    n = (d - _EPOCH).days
    return float(n if n >= 61 else n - 1)


def from_serial(x: float) -> tuple[int, int, int] | ExcelError:
    """(year, month, day) of a serial; in the 1900 system 0 is 1900-01-00 and 60 is
    1900-02-29, as in Excel; #NUM! below 0 or after 9999-12-31."""
    if x < 0 or x >= max_serial() + 1:
        return ExcelError.NUM
    n = int(math.floor(x)) + offset()
    if n == 0:
        return (1900, 1, 0)
    if n == 60:
        return (1900, 2, 29)
    d = _EPOCH + dt.timedelta(days=n if n > 60 else n + 1)
    return (d.year, d.month, d.day)


def null_date_plus(n: int) -> dt.date:
    """LibreOffice's day of serial ``n``: its null date (1899-12-30, or 1904-01-01 in the
    1904 system) plus ``n`` days, with no 29 February 1900."""
    return _EPOCH + dt.timedelta(days=n + offset())


def weekday(n: float) -> int:
    """The weekday of serial ``n``, Monday 0 ... Sunday 6, counted from the serials (the
    1900 system's first two months included)."""
    return (int(math.floor(n)) + offset() + 5) % 7


def serial_1900(n: float) -> float:
    """Serial ``n`` of the current system as a serial of the 1900 system."""
    return n + offset()


def moment_serial(moment: dt.datetime, date1904: bool | None = None) -> float:
    """The serial of a moment (naive): its day's serial plus the time of day as the
    fraction, as NOW gives it; in the system ``date1904`` (None: the current one)."""
    x = (moment - _EPOCH_MOMENT).total_seconds() / 86400.0
    if _DATE1904.get() if date1904 is None else date1904:
        return x - OFFSET_1904
    return x if x >= 61 else x - 1


def moment_of(x: float, date1904: bool | None = None) -> dt.datetime | None:
    """The moment serial ``x`` stands for, in the system ``date1904`` (None: the current
    one); None where it is no calendar day (1900-01-00, 1900-02-29, out of range)."""
    with date_system(_DATE1904.get() if date1904 is None else date1904):
        ymd = from_serial(x)
    if isinstance(ymd, ExcelError) or ymd[2] == 0 or ymd == (1900, 2, 29):
        return None
    return dt.datetime(*ymd) + dt.timedelta(days=x - math.floor(x))
