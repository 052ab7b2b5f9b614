"""The 1904 date system (workbookPr date1904): serial 0 is 1904-01-01 in every function
that converts serial numbers and dates.

References: ECMA-376 Part 4's date representation (DATEVALUE examples for both systems);
a 1904 workbook recalculated by LibreOffice headless and audited (the auditor must read
``date1904`` from the file: in the 1900 system every one of these formulas gives another
value); NPOI's DateFormatTests.xlsx, saved by Excel in the 1904 system
(tests/formula/functions/numfmt/test_numfmt.py).
"""

from __future__ import annotations

import re
import zipfile

import openpyxl
import pytest
import datetime as dt

from openpyxl.utils.datetime import CALENDAR_MAC_1904, CALENDAR_WINDOWS_1900, to_excel

from workbook_gen import audit
from workbook_gen.engines.libreoffice import recalculate
from workbook_gen.formula import functions as fx
from workbook_gen.formula.functions.serials import date_system, moment_of, moment_serial


def _call(name, *args):
    with date_system(True):
        return fx.call(name, list(args))


@pytest.mark.parametrize("text, serial_1900, serial_1904", [  # ECMA-376 Part 4, DATEVALUE
    ("01-Jan-1904", 1462.0, 0.0), ("03-Feb-1910", 3687.0, 2225.0),
    ("01-Feb-2006", 38749.0, 37287.0), ("31-Dec-9999", 2958465.0, 2957003.0),
])
def test_datevalue_in_both_systems(text, serial_1900, serial_1904):
    assert fx.call("DATEVALUE", [text]) == serial_1900
    assert _call("DATEVALUE", text) == serial_1904


MOMENTS = [dt.datetime(1900, 1, 1), dt.datetime(1900, 2, 28, 18), dt.datetime(1900, 3, 1, 6),
           dt.datetime(1904, 1, 1), dt.datetime(2008, 1, 1, 12), dt.datetime(2024, 2, 29, 23, 59, 59)]


@pytest.mark.parametrize("moment", MOMENTS)
def test_a_moment_and_its_serial_agree_with_openpyxl_in_both_systems(moment):
    """The save time the audit reads (TODAY/NOW contracts) and NOW: openpyxl's to_excel is
    the reference (the 1900 system's missing 29 February 1900 included)."""
    for date1904, epoch in ((False, CALENDAR_WINDOWS_1900), (True, CALENDAR_MAC_1904)):
        if date1904 and moment.year < 1904:
            continue
        x = moment_serial(moment, date1904)
        assert x == pytest.approx(to_excel(moment, epoch), abs=1e-9)
        assert moment_of(x, date1904) == moment
        with date_system(date1904):
            assert moment_serial(moment) == x and moment_of(x) == moment


def test_the_days_that_are_no_calendar_day_have_no_moment():
    assert moment_of(0.5, False) is None and moment_of(60.25, False) is None
    assert moment_of(-1.0, True) is None and moment_of(2958466.0, False) is None


def test_limits_of_the_1904_system():
    """ECMA-376: serial 0 is 1904-01-01, 2,957,003 is 9999-12-31; nothing outside."""
    assert _call("DATE", 1904.0, 1.0, 1.0) == 0.0
    assert _call("DATE", 9999.0, 12.0, 31.0) == 2957003.0
    assert _call("DATE", 1903.0, 12.0, 31.0) == fx.ExcelError.NUM
    assert _call("YEAR", 0.0) == 1904.0 and _call("DAY", 2957003.0) == 31.0
    assert _call("YEAR", 2957004.0) == fx.ExcelError.NUM
    assert _call("DATEVALUE", "12/31/1903") == fx.ExcelError.VALUE
    assert _call("EDATE", 0.0, -1.0) == fx.ExcelError.NUM


CASES = {  # formula -> what it exercises (each differs in the 1900 system)
    "=DATE(2024,2,29)": "DATE", "=YEAR(40000)+MONTH(40000)/100+DAY(40000)/10000": "parts",
    "=WEEKDAY(0)": "weekday of 1904-01-01", "=WEEKDAY(40000,2)": "weekday",
    "=EDATE(40000,13)": "EDATE", "=EOMONTH(40000,-2)": "EOMONTH",
    '=DATEVALUE("2020-03-01")': "DATEVALUE", '=VALUE("2020-03-01")+1': "date text",
    '=TEXT(40000,"dddd d mmmm yyyy")': "TEXT", '=TEXT(0,"yyyy-mm-dd ddd")': "TEXT at 0",
    "=NETWORKDAYS(40000,40100)": "NETWORKDAYS", "=WORKDAY(40000,25)": "WORKDAY",
    "=WEEKNUM(40000)": "WEEKNUM", "=_xlfn.ISOWEEKNUM(40000)": "ISOWEEKNUM",
    "=DAYS360(10000,40000)": "DAYS360", "=YEARFRAC(10000,40000,1)": "YEARFRAC",
    '=DATEDIF(10000,40000,"md")': "DATEDIF", "=DATE(1900,1,1500)": "days before 1904",
}


def test_libreoffice_1904_workbook_fully_agrees(libreoffice, tmp_path):
    wb = openpyxl.Workbook()
    wb.epoch = CALENDAR_MAC_1904
    ws = wb.active
    ws.title = "D"
    for row, formula in enumerate(CASES, 1):
        ws.cell(row, 1, formula)
    wb.save(tmp_path / "d1904.xlsx")
    out = recalculate(tmp_path / "d1904.xlsx", tmp_path / "out")
    assert openpyxl.load_workbook(out).epoch == CALENDAR_MAC_1904
    sheet = zipfile.ZipFile(out).read("xl/worksheets/sheet1.xml").decode()
    first = re.search(r'<c r="A1"[^>]*>.*?<v>([^<]*)</v>', sheet).group(1)
    assert float(first) == 45351 - 1462  # DATE(2024,2,29): the 1900 serial less 1462
    report = audit(out)
    assert report.mismatches == [] and report.not_checked == {}
    assert report.cells_checked == len(CASES)
