"""LibreOffice headless as a real engine: forced recalculation, its known differences from Excel.

Every workbook here is written with deliberately wrong cached values, so a value that comes
back right can only have been computed by LibreOffice.
"""

from __future__ import annotations

import math
import threading
from pathlib import Path

import pytest
import xlsxwriter

from workbook_gen.engines import libreoffice as lo
from workbook_gen.errors import WorkbookGenError
from workbook_gen.xlerror import ExcelError

NUM, VALUE, DIV0, NA = ExcelError.NUM, ExcelError.VALUE, ExcelError.DIV0, ExcelError.NA
WRONG = 7  # cached value written beside every formula; no case below evaluates to 7


def _write(path: Path, formulas: dict[str, str], *, values: dict[str, object] | None = None) -> Path:
    """A workbook with Parameters!B2 = 16 named `side`, and Table formulas cached as WRONG."""
    wb = xlsxwriter.Workbook(str(path))
    params = wb.add_worksheet("Parameters")
    params.write_row("A1", ["Name", "Value"])
    params.write_row("A2", ["side", 16.0])
    wb.define_name("side", "=Parameters!$B$2")
    table = wb.add_worksheet("Table")
    for cell, value in (values or {}).items():
        table.write(cell, value)
    for cell, formula in formulas.items():
        table.write_formula(cell, formula, None, WRONG)
    wb.close()
    return path


def _same(got: object, want: object) -> bool:
    if isinstance(want, float) and isinstance(got, float):
        return math.isclose(got, want, rel_tol=1e-14, abs_tol=1e-300)
    return type(got) is type(want) and got == want


# --- (1) recalculation is forced -------------------------------------------------------

FORCED = {
    "A1": 16.0,
}
FORCED_FORMULAS = {
    # cell: (formula, true value from arithmetic by hand)
    "B1": ("=1+1", 2.0),
    "B2": ("=SQRT(A1)", 4.0),
    "B3": ("=side*2+1", 33.0),
    "B4": ("=SQRT(side)+B2", 8.0),
    "B5": ('="len"&side', "len16"),
    "B6": ("=A1>10", True),
}


def test_recalculation_is_forced_and_stale_cached_values_are_replaced(libreoffice, tmp_path):
    src = _write(tmp_path / "stale.xlsx", {c: f for c, (f, _) in FORCED_FORMULAS.items()}, values=FORCED)
    got = lo.recalculated_values(src)
    assert set(got["Table"]) == set(FORCED_FORMULAS)
    assert got["Parameters"] == {}
    for cell, (formula, want) in FORCED_FORMULAS.items():
        assert _same(got["Table"][cell], want), (cell, formula, got["Table"][cell])


def test_recalculate_never_overwrites_src(libreoffice, tmp_path):
    src = _write(tmp_path / "book.xlsx", {"B1": "=1+1"})
    before = src.read_bytes()
    out = lo.recalculate(src, tmp_path)
    assert out != src and out.is_file() and out.parent == tmp_path
    assert src.read_bytes() == before
    assert lo.read_formula_values(out)["Table"]["B1"] == 2.0
    assert lo.read_formula_values(src)["Table"]["B1"] == float(WRONG)


def test_concurrent_calls_use_separate_profiles(libreoffice, tmp_path):
    results: dict[int, object] = {}

    def run(i: int) -> None:
        src = _write(tmp_path / f"c{i}.xlsx", {"B1": f"={i}*3"})
        try:
            results[i] = lo.recalculated_values(src)["Table"]["B1"]
        except Exception as exc:  # reported by the assertion below
            results[i] = exc

    threads = [threading.Thread(target=run, args=(i,)) for i in (1, 2, 4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == {1: 3.0, 2: 6.0, 4: 12.0}


# --- (2) LibreOffice 7.4 against Excel: the engine we test against ----------------------

# formula, LibreOffice 7.4 (measured, forced recalc, saved as xlsx), Excel (documented)
DIFFERENCES = [
    ("=SQRT(-1)", VALUE, NUM),
    ("=ACOS(2)", NUM, NUM),
    ("=ATAN2(0,0)", 0.0, DIV0),
    ("=POWER(0,0)", 1.0, NUM),
    ("=0^0", 1.0, NUM),
    ("=(-8)^(1/3)", -2.0, NUM),
    ("=POWER(-1,0.5)", NUM, NUM),
    ("=10^400", NUM, NUM),
    ("=LN(0)", VALUE, NUM),
    ("=MOD(-7,3)", 2.0, 2.0),
    ("=MOD(7,0)", DIV0, DIV0),
    ("=-2^2", 4.0, 4.0),
    ("=2^3^2", 64.0, 64.0),
    ("=-2%^2", 0.0004, 0.0004),
]
_DIFF_CELLS = {f"B{i + 1}": row for i, row in enumerate(DIFFERENCES)}


@pytest.fixture(scope="module")
def differences(libreoffice, tmp_path_factory) -> dict[str, object]:
    src = _write(tmp_path_factory.mktemp("diff") / "diff.xlsx", {c: r[0] for c, r in _DIFF_CELLS.items()})
    return lo.recalculated_values(src)["Table"]


@pytest.mark.parametrize("cell", list(_DIFF_CELLS), ids=[r[0] for r in DIFFERENCES])
def test_libreoffice_against_excel(differences, cell):
    formula, libreoffice_value, _excel_value = _DIFF_CELLS[cell]
    assert _same(differences[cell], libreoffice_value), (formula, differences[cell])


# --- (3) errors, empty strings, lookups, rounding --------------------------------------

SEMANTICS_VALUES = {"A1": 1.0, "A2": 2.0, "A3": 3.0, "D1": 1.5, "D2": 0.3000000000000001, "D3": 2.75}
SEMANTICS = {
    # cell: (formula, expected)
    "A4": ("=ACOS(2)", NUM),
    "A5": ("=1/0", DIV0),
    "B1": ("=MAX(A1:A5)", NUM),  # the first error of the range propagates
    "B2": ("=MIN(A1:A3)", 1.0),
    "B3": ("=MATCH(9,D1:D3,0)", NA),
    "B4": ("=INDEX(D1:D3,MATCH(2.75,D1:D3,0))", 2.75),
    "B5": ('=IF(A1>0,"",A1)', ""),
    "B6": ('=IF(A1>5,"",A1)', 1.0),
    "B7": ('="#N/A"', "#N/A"),  # text that looks like an error stays text
    "B8": ("=IFERROR(SQRT(-1),-1)", -1.0),
    "B9": ("=ISERROR(A4)", True),
    # LibreOffice snaps a difference that is tiny against its operands to 0 (rtl::math::approxSub)
    "C1": ("=0.1+0.2-0.3", 0.0),
    "C2": ("=1E15+0.3-1E15", 0.0),
    # ... and saves 15 significant digits
    "C3": ("=1/3", 0.333333333333333),
    "C4": ("=1E15+0.3", 1e15),
    "C5": ("=0.1+0.2-0.3+1E-20", 1e-20),
}


def test_errors_strings_lookups_and_rounding(libreoffice, tmp_path):
    src = _write(tmp_path / "sem.xlsx", {c: f for c, (f, _) in SEMANTICS.items()}, values=SEMANTICS_VALUES)
    got = lo.recalculated_values(src)["Table"]
    wrong = {c: (f, got[c], want) for c, (f, want) in SEMANTICS.items() if not _same(got[c], want)}
    assert wrong == {}


def test_error_cells_come_back_as_excel_error(libreoffice, tmp_path):
    src = _write(tmp_path / "err.xlsx", {"B1": "=ACOS(2)", "B2": "=1/0", "B3": "=MATCH(5,A1:A2,0)"},
                 values={"A1": 1.0, "A2": 2.0})
    got = lo.recalculated_values(src)["Table"]
    assert got == {"B1": ExcelError.NUM, "B2": ExcelError.DIV0, "B3": ExcelError.NA}


def test_date_and_time_formatted_cells_come_back_as_serial_numbers(libreoffice, tmp_path):
    # openpyxl reads a number in a date format as a datetime: the values must stay the
    # serial numbers the file stores (Microsoft: DATE(2009,5,11) is 39944, 6:00 is 0.25)
    wb = xlsxwriter.Workbook(str(tmp_path / "dates.xlsx"))
    sheet = wb.add_worksheet("Table")
    date, time = wb.add_format({"num_format": "yyyy-mm-dd"}), wb.add_format({"num_format": "hh:mm"})
    sheet.write_formula("A1", "=DATE(2009,5,11)", date, WRONG)
    sheet.write_formula("A2", "=A1+7", date, WRONG)
    sheet.write_formula("A3", "=TIME(6,0,0)", time, WRONG)
    sheet.write_formula("A4", "=DATE(2009,5,11)+TIME(18,0,0)", date, WRONG)
    sheet.write_formula("A5", "=2958465+1", date, WRONG)  # past 9999-12-31: still a number
    wb.close()
    got = lo.recalculated_values(tmp_path / "dates.xlsx")["Table"]
    assert got == {"A1": 39944.0, "A2": 39951.0, "A3": 0.25, "A4": 39944.75, "A5": 2958466.0}


# --- (4) failures are clean WorkbookGenErrors ------------------------------------------

def test_missing_soffice_is_a_clean_error(tmp_path, monkeypatch):
    src = _write(tmp_path / "book.xlsx", {"B1": "=1+1"})
    monkeypatch.setenv(lo.SOFFICE_ENV, str(tmp_path / "no-such-soffice"))
    assert lo.find_soffice() is None
    with pytest.raises(WorkbookGenError) as info:
        lo.recalculated_values(src)
    assert type(info.value) is WorkbookGenError
    assert "LibreOffice" in str(info.value) and "\n" not in str(info.value)


def test_find_soffice_patched_out_is_a_clean_error(tmp_path, monkeypatch):
    src = _write(tmp_path / "book.xlsx", {"B1": "=1+1"})
    monkeypatch.setattr(lo, "find_soffice", lambda: None)
    with pytest.raises(WorkbookGenError, match="soffice"):
        lo.recalculate(src, tmp_path / "out")
    assert not (tmp_path / "out" / "book.xlsx").exists()


def test_timeout_kills_soffice_and_raises(libreoffice, tmp_path):
    src = _write(tmp_path / "book.xlsx", {"B1": "=1+1"})
    with pytest.raises(WorkbookGenError, match="did not finish"):
        lo.recalculate(src, tmp_path / "out", timeout=0.01)


def test_non_xlsx_input_is_refused(tmp_path):
    src = tmp_path / "text.xlsx"
    src.write_text("a,b\n1,2\n")
    with pytest.raises(WorkbookGenError, match="not an xlsx"):
        lo.recalculate(src, tmp_path / "out")
    assert not (tmp_path / "out" / "text.xlsx").exists()
