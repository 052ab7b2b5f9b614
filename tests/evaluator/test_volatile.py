"""Volatile functions (TODAY, NOW, RAND, RANDBETWEEN) in foreign workbooks: the cached value
is checked against the function's contract, and its dependents are recomputed from it.

A workbook of cases is written with openpyxl and recalculated by LibreOffice headless (the
independent engine draws the numbers and stamps the save date); the audit must accept every
cell. Then cached values are edited in the saved XML to break each contract: those cells,
and only those, must disagree (or stay not checked where the contract cannot be searched).
"""

from __future__ import annotations

import re
import zipfile

import pytest

from workbook_gen import audit
from workbook_gen.auditor.saved import parse_w3cdtf

from lo_sheet import recalculated_sheet

CASES = {
    "B1": "=TODAY()",
    "B2": "=TODAY()+A1",
    "B3": "=NOW()",
    "B4": "=RAND()",
    "B5": "=RANDBETWEEN(1,6)",
    "B6": "=(RANDBETWEEN(-50,250)+100)*10",
    "B7": '=TEXT(TODAY(),"yyyy-mm-dd")',
    "B8": "=RANDBETWEEN(A1,A1+2)",
    "B9": "=RAND()<=1",
    # dependents: recomputed from the cached volatile values
    "C1": "=B1-A1",
    "C4": "=B4*10",
    "C5": "=B5^2",
    "C6": "=C5+B6",
}
VOLATILE = {f"Vol!B{i}" for i in range(1, 10)}


@pytest.fixture(scope="module")
def recalculated(libreoffice, tmp_path_factory):
    return recalculated_sheet(tmp_path_factory.mktemp("volatile"), "Vol", {"A1": 3, **CASES})


def _with_cached(src, dst, values: dict[str, str]):
    """A copy of ``src`` with the cached ``<v>`` of the given cells of sheet1 replaced."""
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            data = zin.read(item)
            if item.filename == "xl/worksheets/sheet1.xml":
                text = data.decode("utf-8")
                for ref, value in values.items():
                    text, n = re.subn(rf'(<c r="{ref}"[^>]*>.*?<v>)[^<]*(</v>)',
                                      rf"\g<1>{value}\g<2>", text, count=1)
                    assert n == 1, ref
                data = text.encode("utf-8")
            zout.writestr(item, data)
    return dst


def test_every_volatile_cell_checked_by_contract_and_dependents_recomputed(recalculated):
    report = audit(recalculated)
    assert report.ok, [(m.cell, m.cached, m.recomputed) for m in report.mismatches]
    assert report.not_checked == {}
    assert set(report.by_contract) == VOLATILE
    assert report.cells_checked == len(CASES)
    assert "TODAY() = " in report.by_contract["Vol!B2"]
    assert "whole number in [3, 5]" in report.by_contract["Vol!B8"]
    assert report.to_json()["cells_by_contract"] == len(VOLATILE)


def test_values_outside_the_contract_disagree(recalculated, tmp_path):
    with zipfile.ZipFile(recalculated) as z:
        core = z.read("docProps/core.xml").decode()
    saved = parse_w3cdtf(re.search(r"<dcterms:modified[^>]*>([^<]+)<", core).group(1))
    assert saved is not None
    broken = _with_cached(recalculated, tmp_path / "broken.xlsx", {
        "B4": "1.5",       # RAND() is below 1
        "B6": "1",         # (k+100)*10 for a whole k in [-50, 250]: never 1
        "B8": "9",         # RANDBETWEEN(3, 5)
        "B9": "0",         # RAND()<=1 is always TRUE
        "B3": "2958465",   # NOW() long after the file was saved (9999-12-31)
    })
    report = audit(broken)
    disagree = {m.cell for m in report.mismatches}
    # C4 and C6 read B4 and B6: recomputed from the edited values, against LibreOffice's
    assert disagree == {"Vol!B4", "Vol!B6", "Vol!B8", "Vol!B3", "Vol!C4", "Vol!C6"}, disagree
    assert {m.cell for m in report.mismatches if m.root} == disagree - {"Vol!C4", "Vol!C6"}
    # RAND()<=1 cached FALSE: no probe gives it, and [0, 1) cannot be searched: not checked
    assert "Vol!B9" in report.not_checked
    assert not report.ok


# -- cycles of the reference graph that the values do not take ----------------------------

CYCLES = {
    # a row sums the cells to its left through INDEX over the row itself (koala's layout)
    "A2": 3, "B2": "=SUM(INDEX($A$2:$E$2,1,1):INDEX($A$2:$E$2,1,COLUMN()-1))",
    "C2": "=SUM(INDEX($A$2:$E$2,1,1):INDEX($A$2:$E$2,1,COLUMN()-1))",
    "D2": "=SUM(INDEX($A$2:$E$2,1,1):INDEX($A$2:$E$2,1,COLUMN()-1))",
    "E2": "=SUM(INDEX($A$2:$E$2,1,1):INDEX($A$2:$E$2,1,COLUMN()-1))",
    # IF never reads the branch that closes the loop while A3 is FALSE
    "A3": False, "B3": "=C3", "C3": "=IF(A3,B3,5)", "D3": "=B3*2",
    "A4": 0, "B4": "=VLOOKUP(1,A4:C5,2,FALSE)", "A5": 1, "B5": 7, "C4": "=B4+1",
    # a real cycle: LibreOffice's Err:522 (#VALUE!) there and in what reads it
    "B6": "=C6+1", "C6": "=B6", "D6": "=B6",
}


@pytest.fixture(scope="module")
def cycles_recalculated(libreoffice, tmp_path_factory):
    return recalculated_sheet(tmp_path_factory.mktemp("cycles"), "Cyc", CYCLES)


def test_false_cycles_are_evaluated_and_real_ones_reported(cycles_recalculated):
    report = audit(cycles_recalculated)
    assert report.mismatches == []
    assert report.not_checked == {}
    formulas = {ref for ref, v in CYCLES.items() if isinstance(v, str) and v.startswith("=")}
    # (LibreOffice saves the boolean A3 as the formula FALSE())
    assert report.cells_checked == report.formula_cells >= len(formulas)
    cycles = [f for f in report.findings if f.kind == "circular_reference"]
    assert len(cycles) == 1 and "Cyc!B6" in cycles[0].message


def test_a_sheet_listed_without_its_part_is_reported_and_the_rest_audited(
        cycles_recalculated, tmp_path):
    """(closedxml__tdf111974.xlsm lists two macro sheets with r:id="")"""
    target = tmp_path / "unreadable.xlsx"
    with zipfile.ZipFile(cycles_recalculated) as zin, \
            zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            data = zin.read(item).decode("utf-8", "surrogateescape")
            if item.filename == "xl/workbook.xml":
                data, n = re.subn(r"(<sheet [^>]*/>)", r'\1<sheet name="Gone" sheetId="99" '
                                  r'state="veryHidden" r:id=""/>', data, count=1)
                assert n == 1
            elif item.filename == "xl/worksheets/sheet1.xml":
                data, n = re.subn(r"<f([^>]*)>B3\*2</f>", r"<f\1>Gone!A1*2</f>", data)
                assert n == 1
            zout.writestr(item, data.encode("utf-8", "surrogateescape"))
    report = audit(target)
    assert report.mismatches == []
    assert "Gone" in report.not_checked["Cyc!D3"]
    assert set(report.not_checked) == {"Cyc!D3"}
    assert [f.cell for f in report.findings if f.kind == "unreadable_sheet"] == ["Gone"]
