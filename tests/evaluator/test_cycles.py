"""Circular references as Excel evaluates them with iterative calculation off (issue 10):
the cells on a run-time cycle, and what takes its value, show 0; a loop of the static
references that the values do not take is computed normally.

References: formulas__circular.xlsx (saved by Excel for Mac, iteration off: its cached
values and the ``ca="1"`` Excel writes on the cells caught in a cycle), and LibreOffice
7.4 recalculating hand-made cases (its Err:522 is exported as #VALUE!)."""

from __future__ import annotations

import re
import zipfile
from pathlib import Path

import pytest

from workbook_gen import audit
from workbook_gen.evaluator import evaluate_cells
from workbook_gen.xlerror import ExcelError

from lo_sheet import recalculated_sheet

CORPUS = Path("/work/shared/corpus/xlsx")


@pytest.fixture(scope="module")
def circular() -> Path:
    path = CORPUS / "formulas__circular.xlsx"
    if not path.is_file():
        pytest.fail(f"corpus file missing: {path}")
    return path


def _ca_cells(path: Path) -> set[str]:
    with zipfile.ZipFile(path) as z:
        xml = z.read("xl/worksheets/sheet1.xml").decode()
    return {"DATA!" + m.group(1) for m in re.finditer(r'<c r="([A-Z]+\d+)"[^>]*><f[^>]*ca="1"',
                                                      xml)}


def test_excel_saved_cycles_agree_cell_by_cell(circular):
    report = audit(circular)
    assert report.mismatches == [] and report.not_checked == {}
    assert report.cells_checked >= report.formula_cells == 55
    on_cycles = set()
    for f in report.findings:
        if f.kind == "circular_reference":
            on_cycles.update(re.findall(r"DATA!\w+", f.message.split(";")[0]))
    # Excel marks with ca="1" the cells of a run-time cycle and the cells reading them
    # (column E); nothing else (rows 6, 10, 12, 14-16 are static loops only)
    readers = {"DATA!E2", "DATA!E3", "DATA!E4", "DATA!E5", "DATA!E7", "DATA!E8", "DATA!E9",
               "DATA!E11", "DATA!E13", "DATA!E17"}
    assert on_cycles == _ca_cells(circular) - readers
    assert {"DATA!D11", "DATA!D8", "DATA!D9"} <= on_cycles      # array cells on a cycle
    assert not on_cycles & {"DATA!D10", "DATA!B6", "DATA!B10", "DATA!B16", "DATA!C14"}


def _edited(src: Path, dst: Path, part: str, old: str, new: str) -> Path:
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            data = zin.read(item).decode("utf-8")
            if item.filename == part:
                assert old in data
                data = data.replace(old, new, 1)
            zout.writestr(item, data.encode("utf-8"))
    return dst


def test_a_wrong_cached_value_on_or_off_a_cycle_disagrees(circular, tmp_path):
    # E2=B2+1 with B2 on a cycle: Excel caches 0, never 1
    bad = _edited(circular, tmp_path / "e2.xlsx", "xl/worksheets/sheet1.xml",
                  '<f ca="1">B2+1</f><v>0</v>', '<f ca="1">B2+1</f><v>1</v>')
    assert [m.cell for m in audit(bad).mismatches] == ["DATA!E2"]
    # D6: a static loop that IF does not take is computed: 1, not 0
    bad = _edited(circular, tmp_path / "d6.xlsx", "xl/worksheets/sheet1.xml",
                  "<f>IF(IF(A6,B6,TRUE),1,B6)</f><v>1</v>", "<f>IF(IF(A6,B6,TRUE),1,B6)</f><v>0</v>")
    assert "DATA!D6" in [m.cell for m in audit(bad).mismatches]


def test_with_iteration_on_the_cycles_are_not_checked(circular, tmp_path):
    on = _edited(circular, tmp_path / "iterate.xlsx", "xl/workbook.xml",
                 '<calcPr calcId="191029" iterateCount="1"',
                 '<calcPr calcId="191029" iterate="1" iterateCount="1"')
    report = audit(on)
    assert report.mismatches == []
    assert "DATA!B2" in report.not_checked and "DATA!E2" in report.not_checked
    assert "DATA!B6" not in report.not_checked and "DATA!E6" not in report.not_checked
    assert any("iterative calculation is on" in f.message for f in report.findings
               if f.kind == "circular_reference")


def test_hand_made_cycles_follow_the_values():
    S = "S"
    formulas = {(S, 1, 2): "C1", (S, 1, 3): "IF(A1,B1,5)", (S, 1, 5): "B1+1",
                (S, 2, 2): "C2", (S, 2, 3): "IF(A2,B2,5)", (S, 2, 5): "B2+1",
                (S, 3, 2): "OR(A3,C3)", (S, 3, 3): "B3", (S, 3, 5): "IFERROR(B3,7)"}
    constants = {(S, 1, 1): True, (S, 2, 1): False, (S, 3, 1): True}
    excel = evaluate_cells(formulas, constants, {})
    assert sorted(excel.cycles) == [[(S, 1, 2), (S, 1, 3)], [(S, 3, 2), (S, 3, 3)]]
    assert [excel.values[(S, 1, c)] for c in (2, 3, 5)] == [0.0, 0.0, 0.0]
    assert [excel.values[(S, 2, c)] for c in (2, 3, 5)] == [5.0, 5.0, 6.0]
    lo = evaluate_cells(formulas, constants, {}, dialect="libreoffice")
    assert lo.values[(S, 1, 5)] is ExcelError.VALUE and lo.values[(S, 3, 5)] == 7.0
    assert lo.values[(S, 2, 5)] == 6.0
    it = evaluate_cells(formulas, constants, {}, iterate=True)
    assert {(S, 1, 2), (S, 1, 3), (S, 1, 5)} <= set(it.not_checked)
    assert (S, 2, 5) not in it.not_checked


def test_array_formula_cells_are_apart_on_a_cycle():
    S = "S"  # formulas__circular rows 10-12, with the middle condition TRUE
    formulas = {(S, r, 2): f"IF(A{r},C{r},1)" for r in (1, 2, 3)}
    formulas.update({(S, r, 3): f"D{r}" for r in (1, 2, 3)})
    constants = {(S, 1, 1): False, (S, 2, 1): True, (S, 3, 1): False}
    result = evaluate_cells(formulas, constants, {},
                            arrays={(S, 1, 4): ("IF(A1:A3,B1:B3,1)", (3, 4))})
    assert result.cycles == [[(S, 2, 2), (S, 2, 3), (S, 2, 4)]]
    assert [result.values[(S, r, 4)] for r in (1, 2, 3)] == [1.0, 0.0, 1.0]


# LibreOffice 7.4 recalculating: Err:522 is an error to what reads it (IFERROR, ISERROR,
# COUNT), exported as #VALUE!; an argument's error comes before a wrong argument count
LO_CASES = {"A1": "=IFERROR(nosuchname,1)", "A2": "=FLOOR(nosuchname,1,2)",
            "A3": "=FLOOR(1.2,1,2)", "A4": "=IF(TRUE,1,nosuchname)",
            "B1": "=C1", "C1": "=IF(D1,B1,5)", "D1": True, "E1": "=IFERROR(B1,7)",
            "F1": "=ISERROR(B1)", "G1": "=B1+1", "H1": "=COUNT(B1)",
            "B2": "=C2", "C2": "=IF(D2,B2,5)", "D2": False, "E2": "=B2+1",
            "B3": "=C3+1", "C3": "=B3", "D3": "=B3"}


@pytest.fixture(scope="module")
def lo_cycles(libreoffice, tmp_path_factory):
    return recalculated_sheet(tmp_path_factory.mktemp("lo_cycles"), "S", LO_CASES)


def test_libreoffice_cycles_agree(lo_cycles):
    report = audit(lo_cycles)
    assert report.semantics == "libreoffice"
    assert report.mismatches == [] and report.not_checked == {}
    assert report.cells_checked == report.formula_cells
    cycles = [f.message for f in report.findings if f.kind == "circular_reference"]
    assert len(cycles) == 2 and any("S!B1" in m for m in cycles)
    assert not any("S!B2" in m for m in cycles)
