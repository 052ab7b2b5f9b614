"""Findings (docs/audit.md, Findings and the file): the mistakes spreadsheet checkers look for, and
none where the layout is deliberate. Cases are written with openpyxl and recalculated by
LibreOffice, so the cached values (errors included) are a real engine's."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import openpyxl
import pytest

from workbook_gen import audit
from workbook_gen.auditor.findings import KINDS
from workbook_gen.engines.libreoffice import recalculate


def _case_book(path: Path) -> Path:
    book = openpyxl.Workbook()
    ws = book.active
    ws.title = "Runs"
    ws.append(["a", "b", "a*b", "a+b", "ratio"])
    for r in range(2, 12):
        ws.append([r * 1.5, r - 0.25, f"=A{r}*B{r}", f"=A{r}+B{r}", f"=C{r}/D{r}"])
    ws["C6"] = "=A6+B6"                 # inconsistent_formula
    ws["D8"] = 42.5                     # constant_in_formula_run
    ws["C12"] = "=SUM(C2:C11)"          # a total at the end of the run: a boundary
    ws["D12"] = "=SUM(D2:D11)"
    ws["E12"] = "=SUM(E2:E11)"          # the total row agrees across: deliberate

    ws = book.create_sheet("Totals")
    ws.append(["item", 2023, 2024, 2025])   # years: integers in sequence, a header
    for r in range(2, 9):
        ws.append([f"item {r}", r * 10.5, r * 7.25, r * 3.5])
    ws["B9"] = "=SUM(B2:B7)"            # formula_omits_adjacent_cells: B8 left out
    ws["C9"] = "=SUM(C2:C8)"            # right; C1 above is the year 2024
    ws["D9"] = "=AVERAGE(D2:D8)"
    ws["B5"] = "52.5"                   # number_stored_as_text inside a SUM's range
    ws["A11"] = "007"                   # a code with a leading zero: not a number
    ws["F2"] = "=B2*Z2"                 # reference_to_empty_cell: column Z is empty
    ws["F3"] = "=IF(ISBLANK(Z3),0,B3)"  # a test of emptiness is not a use
    ws["G2"] = 1.0                      # an input, blank in G3 on purpose
    ws["H2"] = "=G2*2"
    ws["H3"] = "=G3*2"                  # a blank in a filled column: not reported

    ws = book.create_sheet("Errors")
    ws.append([1.0, 0.0, "=A1/B1", "=C1*2", "=D1+1", "=SUM(C1:C1)+A1"])
    ws.append([2.0, 4.0, "=A2/B2", "=C2*2", "=D2+1", "=NA()"])
    ws.append(["x", 1.0, "=A3*B3", "=IFERROR(C3,0)"])

    ws = book.create_sheet("Layout")
    for r in range(1, 13):  # two formulas alternating down a column: a layout
        ws.cell(r, 1, r * 2.0)
        ws.cell(r, 2, f"=A{r}*2" if r % 2 else f"=A{r}+1")
    for r in range(1, 13):  # a subtotal row inside a block, the same across three columns
        for c in (4, 5, 6):
            letter = "DEF"[c - 4]
            ws.cell(r, c, f"=$A{r}*{c}" if r != 6 else f"=SUM({letter}1:{letter}5)")
    path.parent.mkdir(parents=True, exist_ok=True)
    book.save(path)
    return path


@pytest.fixture(scope="module")
def findings(libreoffice, tmp_path_factory):
    folder = tmp_path_factory.mktemp("findings")
    saved = recalculate(_case_book(folder / "cases.xlsx"), folder / "lo")
    report = audit(saved)
    return {(f.kind, f.cell): f.message for f in report.findings if f.kind in KINDS}


def _cells(findings, kind):
    return sorted(cell for k, cell in findings if k == kind)


def test_formula_differing_from_its_run_is_found_not_the_run_ends(findings):
    assert _cells(findings, "inconsistent_formula") == ["Runs!C6"]
    message = findings[("inconsistent_formula", "Runs!C6")]
    assert "=A6+B6" in message and "RC[-2]*RC[-1]" in message


def test_number_typed_over_a_formula_is_found(findings):
    assert _cells(findings, "constant_in_formula_run") == ["Runs!D8"]


def test_sum_that_stops_short_of_its_block_is_found(findings):
    assert _cells(findings, "formula_omits_adjacent_cells") == ["Totals!B9"]
    assert "Totals!B8" in findings[("formula_omits_adjacent_cells", "Totals!B9")]


def test_number_stored_as_text_only_where_numbers_are_expected(findings):
    assert _cells(findings, "number_stored_as_text") == ["Totals!B5"]


def test_reference_to_an_empty_column_is_found_not_a_blank_input(findings):
    assert _cells(findings, "reference_to_empty_cell") == ["Totals!F2"]


def test_error_is_reported_where_it_starts_with_the_cells_it_spoils(findings):
    # C1 divides by zero; D1, E1 and F1 only follow it. C3 multiplies text (#VALUE!);
    # D3 catches it. F2 is NA() on purpose.
    assert _cells(findings, "error_value") == ["Errors!C1", "Errors!C3"]
    message = findings[("error_value", "Errors!C1")]
    assert "#DIV/0!" in message and "spoils 3 cells" in message
    assert all(cell in message for cell in ("Errors!D1", "Errors!E1", "Errors!F1"))


def test_deliberate_layouts_are_not_findings(findings):
    assert not [cell for _, cell in findings if cell.startswith("Layout!")]


TEMPLATES = sorted(Path("templates").glob("*.toml"))


@pytest.mark.parametrize("scene", TEMPLATES, ids=[t.stem for t in TEMPLATES])
def test_workbook_gen_workbooks_have_no_findings(generate, scene):
    report = audit(generate(str(scene)))
    found = Counter(f.kind for f in report.findings if f.kind in KINDS)
    assert not found, [(f.cell, f.message) for f in report.findings if f.kind in KINDS][:5]


def test_findings_are_in_json_with_cell_kind_message(tmp_path):
    book = openpyxl.Workbook()
    ws = book.active
    for r in range(1, 6):
        ws.cell(r, 1, float(r))
        ws.cell(r, 2, f"=A{r}*2")
    ws["B3"] = 6.0
    path = tmp_path / "typed.xlsx"
    book.save(path)
    data = audit(path).to_json()
    entries = [f for f in data["findings"] if f.get("kind") == "constant_in_formula_run"]
    assert len(entries) == 1
    assert entries[0]["cell"] == "Sheet!B3" and "typed" in entries[0]["message"]
