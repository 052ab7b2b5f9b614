"""formula/functions/financial/daycount.py: day-count bases and coupon schedules.

References: Microsoft's COUP* pages (support.microsoft.com, COUPDAYBS, COUPDAYS,
COUPDAYSNC, COUPNCD, COUPNUM, COUPPCD: settlement 25-Jan-2011, maturity 15-Nov-2011,
semiannual, actual/actual: 71, 181, 110, 15-May-2011, 2, 15-Nov-2010; "#NUM! if
frequency is any number other than 1, 2, or 4", "if basis < 0 or > 4", "if settlement >=
maturity"); Python's datetime for actual days; the 30/360 US (NASD/SIA) and European
rules written out below; and LibreOffice recalculating the COUP* functions over random
bonds (one soffice run), whose schedules and day counts the module's own must equal."""

from __future__ import annotations

import calendar
import datetime as dt
import random

import openpyxl
import pytest

from workbook_gen.formula.functions.financial import daycount as dc
from workbook_gen.xlerror import ExcelError

from lo_sheet import recalculated_sheet

RNG = random.Random(2011)
EPOCH = dt.date(1899, 12, 30)


def serial(d: dt.date) -> float:
    return float((d - EPOCH).days)


def last_of_feb(d: dt.date) -> bool:
    return d.month == 2 and d.day == calendar.monthrange(d.year, 2)[1]


def us_30_360(a: dt.date, b: dt.date) -> int:
    """30/360 US (SIA): February's last day is 30 (the end's only when the start's is),
    a 31st is 30 (the end's only when the start is then 30)."""
    d1, d2 = a.day, b.day
    if last_of_feb(a) and last_of_feb(b):
        d2 = 30
    if last_of_feb(a):
        d1 = 30
    if d2 == 31 and d1 >= 30:
        d2 = 30
    if d1 == 31:
        d1 = 30
    return 360 * (b.year - a.year) + 30 * (b.month - a.month) + d2 - d1


def euro_30_360(a: dt.date, b: dt.date) -> int:
    return 360 * (b.year - a.year) + 30 * (b.month - a.month) + min(b.day, 30) - min(a.day, 30)


def random_date(lo=1950, hi=2060) -> dt.date:
    return dt.date(lo, 1, 1) + dt.timedelta(days=RNG.randrange((hi - lo) * 365))


def test_days_in_each_basis():
    for _ in range(2000):
        a = random_date()
        b = a + dt.timedelta(days=RNG.randrange(1, 800))
        if RNG.random() < 0.2:  # month ends, February's in particular
            a = dt.date(a.year, 2, calendar.monthrange(a.year, 2)[1])
            b = dt.date(b.year, b.month, calendar.monthrange(b.year, b.month)[1])
        for basis in (1, 2, 3):
            assert dc.days(a, b, basis) == (b - a).days
        assert dc.days(a, b, 0) == us_30_360(a, b), (a, b)
        assert dc.days(a, b, 4) == euro_30_360(a, b), (a, b)


def test_year_days():
    assert dc.year_days(0) == dc.year_days(2) == dc.year_days(4) == 360.0
    assert dc.year_days(3) == 365.0
    assert dc.year_days(1, dt.date(2024, 5, 1)) == 366.0
    assert dc.year_days(1, dt.date(2100, 5, 1)) == 365.0   # not a leap year


def test_add_months():
    jan31 = dt.date(2023, 1, 31)
    assert dc.add_months(jan31, 1, False) == dt.date(2023, 2, 28)
    assert dc.add_months(jan31, 13, False) == dt.date(2024, 2, 29)
    assert dc.add_months(dt.date(2023, 6, 30), 6, True) == dt.date(2023, 12, 31)
    assert dc.add_months(dt.date(2023, 6, 30), 6, False) == dt.date(2023, 12, 30)
    assert dc.add_months(dt.date(2023, 3, 15), -15, False) == dt.date(2021, 12, 15)


def test_date_of_excels_calendar():
    assert dc.date_of(1.0) == dt.date(1900, 1, 1)
    assert dc.date_of(59.0) == dt.date(1900, 2, 28)
    assert dc.date_of(60.0) == dt.date(1900, 2, 28)          # Excel's 1900-02-29
    assert dc.date_of(61.0) == dt.date(1900, 3, 1)
    assert dc.date_of(0.0) == dt.date(1899, 12, 31)           # 1900-01-00
    d = dt.date(2011, 1, 25)
    assert dc.date_of(serial(d)) == d and dc.serial(d) == serial(d) == 40568.0


def test_microsofts_coupon_example():
    settle, maturity = dt.date(2011, 1, 25), dt.date(2011, 11, 15)
    s = dc.Schedule(settle, maturity, 2)
    assert (s.pcd, s.ncd, s.n) == (dt.date(2010, 11, 15), dt.date(2011, 5, 15), 2)
    assert dc.days_before(s, settle, 1) == 71.0
    assert dc.coupon_days(s, 1) == 181.0
    assert dc.days_after(s, settle, 1) == 110.0


def test_month_end_maturity_pays_on_month_ends():
    s = dc.Schedule(dt.date(2023, 8, 1), dt.date(2024, 2, 29), 4)
    assert (s.pcd, s.ncd, s.n) == (dt.date(2023, 5, 31), dt.date(2023, 8, 31), 3)
    s = dc.Schedule(dt.date(2023, 11, 30), dt.date(2024, 5, 31), 2)   # on a coupon date
    assert (s.pcd, s.ncd, s.n) == (dt.date(2023, 11, 30), dt.date(2024, 5, 31), 1)


@pytest.mark.parametrize("args, expected", [
    ((40568, 40862, 3, 1), ExcelError.NUM),          # frequency not 1, 2, 4
    ((40568, 40862, 2, 5), ExcelError.NUM),          # basis > 4
    ((40568, 40862, 2, -1), ExcelError.NUM),
    ((40862, 40862, 2, 0), ExcelError.NUM),          # settlement >= maturity
    ((40900, 40862, 2, 0), ExcelError.NUM),
    (("x", 40862, 2, 0), ExcelError.VALUE),
    ((40568, 40862, "two", 0), ExcelError.VALUE),
    ((ExcelError.NA, 40862, 2, 0), ExcelError.NA),
    ((-1, 40862, 2, 0), ExcelError.NUM),             # before Excel's calendar
])
def test_bond_args_refusals(args, expected):
    assert dc.bond_args(*args) == expected


def test_bond_args_truncates_and_reads_text():
    got = dc.bond_args(40568.9, "2011-11-15", 2.7, None, (0.05, "100"))
    assert got == (dt.date(2011, 1, 25), dt.date(2011, 11, 15), 2, 0, [0.05, 100.0])


BONDS = []
for _ in range(25):
    settle = random_date(1990, 2040)
    BONDS.append((settle, settle + dt.timedelta(days=RNG.randrange(20, 4000)),
                  RNG.choice(dc.FREQUENCIES), RNG.randrange(5)))
BONDS.append((dt.date(2023, 8, 1), dt.date(2024, 2, 29), 4, 0))
BONDS.append((dt.date(2023, 2, 28), dt.date(2026, 8, 31), 2, 0))
COUP = ("COUPPCD", "COUPNCD", "COUPNUM", "COUPDAYBS", "COUPDAYS", "COUPDAYSNC")


@pytest.fixture(scope="module")
def libreoffice_coupons(libreoffice, tmp_path_factory):
    cells = {}
    for i, (s, m, f, b) in enumerate(BONDS, 1):
        for j, name in enumerate(COUP):
            cells[f"{'ABCDEF'[j]}{i}"] = f"={name}({serial(s):.0f},{serial(m):.0f},{f},{b})"
    out = recalculated_sheet(tmp_path_factory.mktemp("daycount"), "Coupons", cells)
    ws = openpyxl.load_workbook(out, data_only=True)["Coupons"]
    return [[ws[f"{'ABCDEF'[j]}{i}"].value for j in range(len(COUP))]
            for i in range(1, len(BONDS) + 1)]


def test_schedules_and_day_counts_agree_with_libreoffice(libreoffice_coupons):
    for (s, m, f, b), lo in zip(BONDS, libreoffice_coupons):
        sch = dc.Schedule(s, m, f)
        pcd, ncd, n, a, e, dsc = (float(v) if not isinstance(v, dt.datetime) else v.date()
                                  for v in lo)
        if isinstance(pcd, float):  # a serial where openpyxl saw no date format
            pcd, ncd = (EPOCH + dt.timedelta(days=x) for x in (pcd, ncd))
        case = (s, m, f, b)
        assert (sch.pcd, sch.ncd, sch.n) == (pcd, ncd, n), case
        assert dc.days_before(sch, s, b) == a, case
        assert dc.coupon_days(sch, b) == pytest.approx(e, rel=1e-15), case
        assert dc.days_after(sch, s, b) == dsc, case
