"""workbook-gen audit: recompute every formula cell and check it; name what disagrees."""

from __future__ import annotations

import json
import re
import subprocess
import sys
import zipfile
from pathlib import Path

import openpyxl
import pytest

from workbook_gen import audit
from workbook_gen.engines.libreoffice import recalculate


def run_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "workbook_gen.cli", *args],
                          capture_output=True, text=True, timeout=600)


def rewrite_part(src: Path, dst: Path, part: str, edit) -> None:
    """Copy an xlsx, passing one part's XML text through ``edit``."""
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            data = zin.read(item.filename)
            if item.filename == part:
                data = edit(data.decode()).encode()
            zout.writestr(item, data)


def y_C_cell(path, row: int) -> tuple[str, str]:
    """The cell holding y_C at ``row`` and its formula text (without '=')."""
    table = openpyxl.load_workbook(path)["Table"]
    col = next(c.column_letter for c in table[1] if c.value == "y_C [mm]")
    return f"{col}{row}", table[f"{col}{row}"].value[1:]


def test_our_workbook_passes_with_every_cell_checked(sewing_workbook):
    report = audit(sewing_workbook)
    assert report.ok, report.mismatches
    assert report.cells_checked == report.formula_cells > 1500
    assert report.vector_cells > 1000
    assert report.mechanics is not None
    headers = [c.value.split(" [")[0] for c in openpyxl.load_workbook(sewing_workbook)["Table"][1]]
    assert set(report.reference) == set(headers) - {"theta_1", "status"}  # every column
    assert max(report.reference.values()) <= 1e-9
    # the paper's table: alpha_5 per 10 deg against the model
    assert [row[0] for row in report.mechanics.paper_table] == list(range(0, 361, 10))
    assert max(row[3] for row in report.mechanics.paper_table) < 1e-6


def test_tampered_formula_is_named_by_its_cell(sewing_workbook, tmp_path):
    bad = tmp_path / "tampered.xlsx"
    cell, formula = y_C_cell(sewing_workbook, 11)
    rewrite_part(sewing_workbook, bad, "xl/worksheets/sheet1.xml",
                 lambda xml: xml.replace(f"<f>{formula}</f>", f"<f>{formula}*1.001</f>"))
    report = audit(bad)
    assert not report.ok
    roots = [m for m in report.mismatches if m.root]
    assert [m.cell for m in roots] == [f"Table!{cell}"]
    assert roots[0].formula == f"{formula}*1.001"
    assert len(report.mismatches) > 1  # what y_C feeds disagrees too, marked as following
    # the wrong formula also disagrees with the reference model at that row
    assert any(q.name == "y_C" and not q.ok for q in report.mechanics.quantities)


def test_tampered_cached_value_is_named_by_its_cell(sewing_workbook, tmp_path):
    bad = tmp_path / "tampered.xlsx"
    cell, _ = y_C_cell(sewing_workbook, 20)

    def edit(xml: str) -> str:
        return re.sub(rf'(<c r="{cell}"[^>]*><f>[^<]*</f><v>)([^<]*)(</v>)',
                      lambda m: m.group(1) + repr(float(m.group(2)) + 1e-6) + m.group(3), xml)
    rewrite_part(sewing_workbook, bad, "xl/worksheets/sheet1.xml", edit)
    report = audit(bad)
    assert [m.cell for m in report.mismatches] == [f"Table!{cell}"]


@pytest.mark.parametrize("overrides", [{}, {"l_BC": 20.0}, {"x_F": 60.0, "y_F": 0.0}])
def test_workbook_saved_by_libreoffice_passes(libreoffice, generate, tmp_path, overrides):
    ours = generate("templates/sewing_machine.toml", overrides=overrides)
    saved = recalculate(ours, tmp_path)
    report = audit(saved)
    assert report.ok, (report.mismatches[:5], report.findings[:5])
    assert report.cells_checked == report.formula_cells


def test_foreign_workbook_recalculated_by_libreoffice_passes(libreoffice, tmp_path):
    book = openpyxl.Workbook()
    sheet = book.active
    sheet.title = "Data Sheet"
    other = book.create_sheet("Other Sheet")
    other["A1"] = 2.5
    for r in range(1, 41):
        sheet.cell(r, 1, r * 0.37 - 4)
        sheet.cell(r, 2, f"=SIN(A{r})*'Other Sheet'!$A$1+A{r}^2")
        sheet.cell(r, 3, f'=IF(A{r}<0,"neg",B{r}/A{r})')
        sheet.cell(r, 4, f"=MOD(A{r},-3)+ATAN2(A{r},B{r})")
        sheet.cell(r, 5, f"=SQRT(A{r})")           # #NUM! in Excel, #VALUE! in LibreOffice
    sheet["G1"] = "=MAX(B1:B40)"
    sheet["G2"] = "=INDEX(A1:A40,MATCH(G1,B1:B40,0))"
    sheet["G3"] = "=SUM(B1:B40)/-2^2"
    sheet["G4"] = "=IFERROR(1/0,\"none\")"
    src = tmp_path / "foreign.xlsx"
    book.save(src)
    saved = recalculate(src, tmp_path / "lo")
    report = audit(saved)
    assert report.ok, report.mismatches[:5]
    assert report.mechanics is None
    # saved by LibreOffice (docProps/app.xml): recomputed with its semantics, so the SQRT
    # of negatives is #VALUE! as cached, with nothing left to explain
    assert report.semantics == "libreoffice"
    assert report.application.startswith("LibreOffice/")
    assert report.to_json()["semantics"] == "libreoffice"
    assert report.libreoffice_semantics == 0
    assert report.cells_checked == report.formula_cells == 40 * 4 + 4


def test_cli_exit_codes_and_json(sewing_workbook, tmp_path):
    result = run_cli("audit", str(sewing_workbook), "--json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    for key in ("ok", "formula_cells", "cells_checked", "mismatches", "max_abs_error",
                "max_rel_error", "reference", "seconds"):
        assert key in data
    bad = tmp_path / "bad.xlsx"
    cell, formula = y_C_cell(sewing_workbook, 11)
    rewrite_part(sewing_workbook, bad, "xl/worksheets/sheet1.xml",
                 lambda xml: xml.replace(f"<f>{formula}</f>", f"<f>{formula.replace('-', '+')}</f>"))
    result = run_cli("audit", str(bad))
    assert result.returncode == 1
    assert f"Table!{cell}" in result.stdout and "=" + formula.replace("-", "+") in result.stdout
    garbage = tmp_path / "garbage.xlsx"
    garbage.write_text("not a workbook")
    result = run_cli("audit", str(garbage))
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1


def test_cycle_is_reported_and_the_rest_still_audited(tmp_path):
    import xlsxwriter
    path = tmp_path / "cycle.xlsx"
    book = xlsxwriter.Workbook(path)
    sheet = book.add_worksheet()
    sheet.write_formula("A1", "=B1+1", None, 0)
    sheet.write_formula("B1", "=A1*2", None, 0)
    sheet.write_formula("C1", "=A1+5", None, 0)       # reads the cycle: 0 as well
    sheet.write_number("D1", 3)
    sheet.write_formula("E1", "=D1*2", None, 6)       # independent: checked, agrees
    sheet.write_formula("F1", "=D1*3", None, 10)      # independent: checked, disagrees
    book.close()
    result = run_cli("audit", str(path), "--json")
    assert result.returncode == 1, result.stderr
    data = json.loads(result.stdout)
    # (Excel, iteration off: the cycle and what reads it show 0, checked as such)
    assert data["not_checked"] == []
    assert (data["cells_agree"], data["cells_disagree"], data["cells_not_checked"]) == (4, 1, 0)
    assert [m["cell"] for m in data["mismatches"]] == ["Sheet1!F1"]
    cycle = [f for f in data["findings"] if f["kind"] == "circular_reference"]
    assert len(cycle) == 1 and "Sheet1!A1" in cycle[0]["message"] \
        and "Sheet1!B1" in cycle[0]["message"]


def test_range_size_functions_make_no_cycle(tmp_path):
    import xlsxwriter
    path = tmp_path / "rows.xlsx"
    book = xlsxwriter.Workbook(path)
    sheet = book.add_worksheet()
    sheet.write_formula("A1", "=ROWS(A1:B3)*COLUMNS(A1:B3)", None, 6)
    sheet.write_formula("B2", "=ROW(B2)+COLUMN(A1:A2)", None, 3)
    book.close()
    report = audit(path)
    assert not any(f.kind == "circular_reference" for f in report.findings)
    assert all("circular" not in r for r in report.not_checked.values())


def test_unsupported_function_is_reported_by_cell(tmp_path):
    import xlsxwriter
    path = tmp_path / "webservice.xlsx"
    book = xlsxwriter.Workbook(path)
    sheet = book.add_worksheet()
    sheet.write_number("A1", 1)
    sheet.write_formula("B1", '=_xlfn.WEBSERVICE("http://example.com/"&A1)', None, 1)
    sheet.write_formula("C1", "=B1*2", None, 2)       # reads B1's cached value: checked
    sheet.write_formula("D1", "=A1+1", None, 2)       # independent: checked
    book.close()
    report = audit(path)
    assert report.ok  # a cell not checked never fails the audit on its own
    assert report.not_checked == {"Sheet1!B1": "unsupported function WEBSERVICE"}
    assert (report.cells_agree, report.cells_disagree, report.cells_not_checked) == (2, 0, 1)
    assert any(f.kind == "unsupported_function" and f.cell == "Sheet1!B1"
               and "WEBSERVICE" in f.message for f in report.findings)
    result = run_cli("audit", str(path))
    assert result.returncode == 0 and len(result.stdout.splitlines()) <= 8, result.stdout
    assert "1 unsupported function WEBSERVICE" in result.stdout


def test_reader_of_an_unrecomputable_cell_is_checked_against_its_cached_value(tmp_path):
    """The consistency rule: B1 cannot be recomputed, but its cached value is what Excel
    computed in the same recalculation as C1's: C1 = B1*2 must give C1's cached value
    from it, and a C1 that does not is a real disagreement."""
    import xlsxwriter
    path = tmp_path / "webservice.xlsx"
    book = xlsxwriter.Workbook(path)
    sheet = book.add_worksheet()
    sheet.write_formula("B1", '=_xlfn.WEBSERVICE("http://example.com/")', None, 21)
    sheet.write_formula("C1", "=B1*2", None, 42)
    sheet.write_formula("C2", "=B1*2", None, 40)      # stale: disagrees
    sheet.write_formula("C3", "=C2+1", None, 43)      # follows from B1 through C2
    book.close()
    report = audit(path)
    assert report.not_checked == {"Sheet1!B1": "unsupported function WEBSERVICE"}
    assert [m.cell for m in report.mismatches if m.root] == ["Sheet1!C2"]
    assert report.cells_agree == 2


def test_engine_libreoffice_agrees_on_our_workbook(libreoffice, sewing_workbook):
    report = audit(sewing_workbook, engine="libreoffice")
    assert report.engine is not None and report.engine.cells == report.formula_cells
    assert report.engine.mismatches == []
    assert report.ok


def _zip(path: Path, parts: dict[str, str]) -> Path:
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        for name, text in parts.items():
            z.writestr(name, text)
    return path


def test_hostile_or_broken_files_exit_2_in_one_line(tmp_path, sewing_workbook):
    bomb = ('<?xml version="1.0"?><!DOCTYPE lolz [<!ENTITY lol "lol">'
            + "".join(f'<!ENTITY lol{i} "{"&lol%s;" % ("" if i == 1 else i - 1) * 10}">'
                      for i in range(1, 10))
            + ']><workbook>&lol9;</workbook>')
    files = {
        "bomb.xlsx": _zip(tmp_path / "bomb.xlsx", {"[Content_Types].xml": "<Types/>",
                                                   "xl/workbook.xml": bomb}),
        "empty.xlsx": _zip(tmp_path / "empty.xlsx", {"readme.txt": "no workbook here"}),
        "truncated.xlsx": tmp_path / "truncated.xlsx",
        "missing.xlsx": tmp_path / "missing.xlsx",
    }
    files["truncated.xlsx"].write_bytes(Path(sewing_workbook).read_bytes()[:5000])
    for name, path in files.items():
        result = run_cli("audit", str(path))
        assert result.returncode == 2, (name, result.stdout, result.stderr)
        message = result.stderr.strip()
        assert len(message.splitlines()) == 1 and "Traceback" not in message, (name, message)
        assert str(path) in message or path.name in message, (name, message)
