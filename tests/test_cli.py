"""Errors a user meets at the command line, and verdicts that name their cause
(issue 22, items 9 to 14): one line and exit 2 for a place that cannot be written, a
quiet exit for a closed pipe, a refusal to audit nothing, and a FAILED that says what
failed."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import openpyxl
import pytest

ROOT = Path(__file__).resolve().parents[1]
FOUR_BAR = str(ROOT / "templates" / "four_bar.toml")
# sysfs: no user, root included, can create a file there (EACCES, or EROFS where /sys
# is mounted read-only), unlike a chmod 555 folder, which root writes into
UNWRITABLE = Path("/sys")


def run_cli(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run([sys.executable, "-m", "workbook_gen.cli", *args], cwd=cwd,
                          capture_output=True, text=True, timeout=600, env=env)


def one_line_exit_2(result: subprocess.CompletedProcess, *names: str) -> str:
    assert result.returncode == 2, (result.returncode, result.stdout, result.stderr)
    message = result.stderr.strip()
    assert len(message.splitlines()) == 1 and "Traceback" not in message, message
    assert message.startswith("workbook-gen: error: "), message
    for name in names:
        assert name in message, (name, message)
    return message


@pytest.fixture(scope="module")
def small_four_bar(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("fb")
    result = run_cli("generate", FOUR_BAR, "--out", str(out), "--step", "10")
    assert result.returncode == 0, result.stderr
    return out / "four_bar.xlsx"


def test_unwritable_folder_is_refused_in_one_line_by_every_command(small_four_bar, tmp_path):
    with pytest.raises(OSError):  # the premise: not even this process may write there
        tempfile.mkstemp(dir=UNWRITABLE)
    cases = {
        "generate": ("generate", FOUR_BAR, "--out", str(UNWRITABLE), "--step", "10"),
        "batch": ("batch", FOUR_BAR, "--vary", "l_AB=30,32", "--step", "30", "--out",
                  str(UNWRITABLE), "--quiet"),
        "tradeoff": ("tradeoff", FOUR_BAR, "--out", str(UNWRITABLE)),
        "audit --annotate": ("audit", str(small_four_bar), "--annotate",
                             str(UNWRITABLE / "copy.xlsx")),
    }
    for name, args in cases.items():
        result = run_cli(*args, cwd=tmp_path)
        one_line_exit_2(result, str(UNWRITABLE))
        assert result.stdout == "", (name, result.stdout)  # refused before any work
    assert list(tmp_path.iterdir()) == []


def test_output_path_that_is_a_folder_is_refused_even_with_force(small_four_bar, tmp_path):
    (tmp_path / "four_bar.xlsx").mkdir()
    result = run_cli("generate", FOUR_BAR, "--out", str(tmp_path), "--step", "10", "--force")
    one_line_exit_2(result, str(tmp_path / "four_bar.xlsx"), "is a folder")
    (tmp_path / "copy.xlsx").mkdir()
    result = run_cli("audit", str(small_four_bar), "--annotate", str(tmp_path / "copy.xlsx"),
                     "--force")
    one_line_exit_2(result, "copy.xlsx", "is a folder")
    assert result.stdout == ""
    (tmp_path / "four_bar_tradeoff.xlsx").mkdir()
    result = run_cli("tradeoff", FOUR_BAR, "--out", str(tmp_path), "--force")
    one_line_exit_2(result, "four_bar_tradeoff.xlsx", "is a folder")
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "copy.xlsx", "four_bar.xlsx", "four_bar_tradeoff.xlsx"]
    assert all(not any(p.iterdir()) for p in tmp_path.iterdir())


def _closed_early(args: list[str]) -> tuple[int, str, str]:
    """Run the command with its stdout read by a reader that takes one line and goes
    away (``| head -1``): (exit code, the line, stderr)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    process = subprocess.Popen([sys.executable, "-m", "workbook_gen.cli", *args],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    line = process.stdout.readline().decode()
    process.stdout.close()
    err = process.stderr.read().decode()
    return process.wait(timeout=600), line, err


def test_a_reader_that_stops_early_ends_the_audit_quietly(tmp_path):
    book = openpyxl.Workbook()  # saved without values: --verbose lists its 3,000 cells
    for r in range(1, 3001):
        book.active.cell(r, 1, r)
        book.active.cell(r, 2, f"=A{r}*2")
    book.save(tmp_path / "a.xlsx")
    book.save(tmp_path / "b.xlsx")
    # a report far larger than a pipe's buffer, and a folder reported a line per file
    for args in (["audit", str(tmp_path / "a.xlsx"), "--verbose"],
                 ["audit", str(tmp_path), "--jobs", "1"]):
        code, line, err = _closed_early(args)
        assert code == 141, (args, code, err)  # 128 + SIGPIPE, as `yes | head` in a shell
        assert line.strip() and err == "", (args, line, err)


def test_audit_of_nothing_fails_in_one_line(tmp_path):
    (tmp_path / "empty").mkdir()
    (tmp_path / "other" / "deeper").mkdir(parents=True)
    (tmp_path / "other" / "deeper" / "notes.txt").write_text("no workbook")
    one_line_exit_2(run_cli("audit", str(tmp_path / "empty")), "nothing to audit")
    one_line_exit_2(run_cli("audit", str(tmp_path / "empty"), str(tmp_path / "other"),
                            "--json"), "nothing to audit")
    # a glob the shell found nothing for reaches us as the pattern itself
    one_line_exit_2(run_cli("audit", str(tmp_path / "empty" / "*.xlsx")),
                    "*.xlsx", "nothing to audit")
    from workbook_gen.auditor.many import audit_many
    from workbook_gen.errors import WorkbookReadError
    with pytest.raises(WorkbookReadError, match="nothing to audit"):
        list(audit_many([tmp_path / "empty"]))


def _theta_4_off_by_2_deg(source: Path, folder: Path, libreoffice: str) -> Path:
    """The four-bar with theta_4 two degrees off at rows 13-15, recalculated by
    LibreOffice: every cell agrees with its formula, and the mechanics are wrong there."""
    import re
    import zipfile
    from workbook_gen.engines.libreoffice import recalculate
    tampered = folder / "theta4.xlsx"
    with zipfile.ZipFile(source) as zin, zipfile.ZipFile(tampered, "w",
                                                         zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            data = zin.read(item.filename)
            if item.filename == "xl/worksheets/sheet1.xml":  # the Table
                xml = data.decode()
                table = openpyxl.load_workbook(source)["Table"]
                col = next(c.column_letter for c in table[1] if c.value == "theta_4 [deg]")
                for row in (13, 14, 15):
                    xml, n = re.subn(rf'(<c r="{col}{row}"[^>]*><f>[^<]*)(</f>)',
                                     lambda m: m.group(1) + "+2" + m.group(2), xml)
                    assert n == 1
                data = xml.encode()
            zout.writestr(item, data)
    return recalculate(tampered, folder / "recalculated")


def test_verdict_names_the_reference_model_and_the_checks_not_cells(
        libreoffice, small_four_bar, tmp_path):
    bad = _theta_4_off_by_2_deg(small_four_bar, tmp_path, libreoffice)
    result = run_cli("audit", str(bad))
    assert result.returncode == 1, result.stderr
    verdict = result.stdout.strip().splitlines()[-1]
    assert verdict.startswith("  FAILED: reference model: theta_4 differs at rows 13-15, "
                              "max error "), verdict
    assert "Checks: closure residuals loop_position" in verdict, verdict
    assert "cells disagree" not in verdict and "disagreement" not in verdict, verdict
    data = json.loads(run_cli("audit", str(bad), "--json").stdout)
    assert [c["kind"] for c in data["failed"]] == ["reference", "checks"]
    assert data["failed"][0]["message"].startswith("reference model: theta_4 differs at "
                                                   "rows 13-15")
    # several files: the file's line and the total say why too
    many = run_cli("audit", str(bad), str(small_four_bar), "--jobs", "1")
    lines = many.stdout.strip().splitlines()
    assert many.returncode == 1
    assert lines[0].startswith("FAIL") and "reference model: theta_4 differs at rows 13-15" \
        in lines[0], lines[0]
    assert lines[1].startswith("OK")
    assert lines[-1].startswith("total: 2 files: 1 ok, 1 failed (1 failing the reference "
                                "model, 1 failing their Checks), 0 refused"), lines[-1]
    # a good file's JSON says nothing failed
    assert json.loads(run_cli("audit", str(small_four_bar), "--json").stdout)["failed"] == []


def test_verdict_names_the_disagreeing_cell(small_four_bar, tmp_path):
    import re
    import zipfile
    bad = tmp_path / "cached.xlsx"
    with zipfile.ZipFile(small_four_bar) as zin, zipfile.ZipFile(bad, "w") as zout:
        for item in zin.infolist():
            data = zin.read(item.filename)
            if item.filename == "xl/worksheets/sheet1.xml":
                data, n = re.subn(rb'(<c r="J20"[^>]*><f>[^<]*</f><v>)([^<]*)(</v>)',
                                  lambda m: m.group(1) + repr(float(m.group(2)) + 1e-3
                                                              ).encode() + m.group(3), data)
                assert n == 1
            zout.writestr(item, data)
    result = run_cli("audit", str(bad))
    assert result.returncode == 1
    verdict = result.stdout.strip().splitlines()[-1]
    assert verdict.startswith("  FAILED: 1 cell disagrees at the source: Table!J20"), verdict
    assert "reference model" not in verdict  # the cell's own formula is right


from corpus_audits import CORPUS  # noqa: E402  (the one place the corpus path lives)


def test_libreoffice_own_semantics_are_its_difference_not_the_file_failure(libreoffice):
    """pycel__stats.xlsx, saved by Excel: SLOPE, INTERCEPT and FORECAST of two areas of
    different sizes are #N/A there (Microsoft's rule), #VALUE! in LibreOffice."""
    stats = CORPUS / "pycel__stats.xlsx"
    assert stats.is_file(), f"the corpus is missing: {stats}"
    result = run_cli("audit", str(stats), "--engine", "libreoffice", "--json")
    assert result.returncode == 0, (result.stdout[-2000:], result.stderr)
    data = json.loads(result.stdout)
    assert data["ok"] and data["failed"] == [] and data["engine"]["mismatches"] == []
    differences = {d["cell"]: d for d in data["engine"]["libreoffice_differences"]}
    assert {"Stats!P3", "Stats!Q3", "Stats!R3", "Stats!P4", "Stats!P5"} <= set(differences)
    assert differences["Stats!P3"]["formula"] == "=SLOPE(J3:N3,J4:N5)"
    assert (differences["Stats!P3"]["libreoffice"], differences["Stats!P3"]["excel"]) == (
        "#VALUE!", "#N/A")
    assert data["engine"]["libreoffice_semantics"] == len(differences)


# (formula on sheet Calc, Excel's value): a reference to a sheet the workbook lacks is
# #REF! in Excel (as after deleting the sheet); INDIRECT's text names a cell of the
# calling cell's sheet unless it names another, and the cell it names is computed first
HOSTILE = {
    "A1": ("=MAX(Sheet2!A1:A3)", "#REF!"),
    "A2": ("=Sheet2!A1+1", "#REF!"),
    "A3": ('=IFERROR(SUM(Sheet2!A1:B2),"gone")', "gone"),
    "A4": ('=INDIRECT("B1")', 7.0),
    "A5": ('=SUM(INDIRECT("B1:B2"))*2', 28.0),
    "A6": ('=INDIRECT("Data!A1")', 9.0),
    "A7": ('=INDIRECT("Sheet2!A1")', "#REF!"),
    "A8": ('=SUM(INDIRECT("C1:C3"))', 6.0),
}


def _hostile_cells(sheet, data) -> None:
    sheet["B1"] = "=3+4"   # a formula INDIRECT reads: computed after it, it would read 0
    sheet["B2"] = "=B1*1"
    for r, v in enumerate((1, 2, 3), start=1):
        sheet[f"C{r}"] = f"={v}*1"
    data["A1"] = "=4+5"


def test_hostile_references_recompute_as_excel_does(tmp_path):
    import xlsxwriter
    path = tmp_path / "hostile.xlsx"
    book = xlsxwriter.Workbook(str(path))
    data, calc = book.add_worksheet("Data"), book.add_worksheet("Calc")
    calc.write_formula("B1", "=3+4", None, 7)
    calc.write_formula("B2", "=B1*1", None, 7)
    for r, v in enumerate((1, 2, 3)):
        calc.write_formula(r, 2, f"={v}*1", None, v)
    data.write_formula("A1", "=4+5", None, 9)
    for ref, (formula, value) in HOSTILE.items():
        calc.write_formula(ref, formula, None, value)
    book.close()
    from workbook_gen import audit
    report = audit(path)
    assert report.ok, [(m.cell, m.cached, m.recomputed) for m in report.mismatches]
    assert report.cells_checked == report.formula_cells == len(HOSTILE) + 6
    assert any(f.kind == "unresolved_reference" and "Sheet2" in f.message
               for f in report.findings)


def test_hostile_references_agree_with_libreoffice(libreoffice, tmp_path):
    from workbook_gen import audit
    from workbook_gen.engines.libreoffice import recalculate
    book = openpyxl.Workbook()
    data = book.active
    data.title = "Data"
    calc = book.create_sheet("Calc")
    _hostile_cells(calc, data)
    for ref, (formula, _) in HOSTILE.items():
        calc[ref] = formula
    book.save(tmp_path / "hostile.xlsx")
    saved = recalculate(tmp_path / "hostile.xlsx", tmp_path / "lo")
    values = openpyxl.load_workbook(saved, data_only=True)["Calc"]
    # LibreOffice reads a missing sheet's reference as an unknown name: #NAME?
    assert [values[r].value for r in ("A1", "A4", "A5", "A6", "A7", "A8")] == [
        "#NAME?", 7, 28, 9, "#REF!", 6]
    report = audit(saved)
    assert report.semantics == "libreoffice"
    assert report.ok, [(m.cell, m.cached, m.recomputed) for m in report.mismatches]
    assert report.cells_checked == report.formula_cells


def _chain(path: Path, n: int) -> Path:
    """A1 = 1, A(r) = A(r-1)+1 filled down: n formula cells with Excel's cached values."""
    import xlsxwriter
    book = xlsxwriter.Workbook(str(path))
    sheet = book.add_worksheet("Chain")
    sheet.write_number(0, 0, 1.0)
    for r in range(1, n + 1):
        sheet.write_formula(r, 0, f"=A{r}+1", None, float(r + 1))
    book.close()
    return path


def test_max_cells_flag_and_argument_read_a_larger_workbook(tmp_path):
    from workbook_gen import audit
    from workbook_gen.errors import WorkbookGenError
    chain = _chain(tmp_path / "chain.xlsx", 1500)  # 1,501 cells
    message = one_line_exit_2(run_cli("audit", str(chain), "--max-cells", "1000"),
                              "more than 1000 cells", "--max-cells N")
    assert "max_cells=N" in message  # the instruction names what exists
    result = run_cli("audit", str(chain), "--max-cells", "1501")
    assert result.returncode == 0, result.stderr
    assert "1500 formula cells: 1500 checked (1500 agree" in result.stdout
    many = run_cli("audit", str(chain), str(chain), "--max-cells", "1000", "--jobs", "1")
    assert many.returncode == 2 and many.stdout.startswith("ERROR") and "--max-cells" in many.stdout
    report = audit(chain, max_cells=1501)
    assert report.ok and report.cells_checked == 1500
    with pytest.raises(WorkbookGenError, match="more than 1000 cells"):
        audit(chain, max_cells=1000)
    for bad in (0, -5, 2.5, True):
        with pytest.raises(WorkbookGenError, match="max_cells"):
            audit(chain, max_cells=bad)
    for bad in ("0", "x", "inf", "1.5"):
        result = run_cli("audit", str(chain), "--max-cells", bad)
        assert result.returncode == 2 and "--max-cells" in result.stderr, (bad, result.stderr)


def test_a_chain_is_evaluated_without_a_unit_per_cell():
    """=A(r-1)*1.0001+SIN(ROW()) filled down 20,000 rows: each row as Python computes it,
    in a few hundred bytes a cell (a unit and a tree per cell took ~1.4 KB: a
    million-formula chain peaked at 2.06 GB)."""
    import math
    import tracemalloc
    from workbook_gen.evaluator import evaluate_cells
    n = 20_000
    formulas = {("S", r, 1): f"A{r - 1}*1.0001+SIN(ROW())" for r in range(2, n + 2)}
    tracemalloc.start()
    try:
        result = evaluate_cells(formulas, {("S", 1, 1): 1.0}, {})
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    expected = 1.0
    for r in range(2, n + 2):
        expected = expected * 1.0001 + math.sin(r)
        assert result.values[("S", r, 1)] == pytest.approx(expected, rel=1e-12, abs=1e-12), r
    assert peak / n < 500, f"{peak / n:.0f} bytes a cell"
