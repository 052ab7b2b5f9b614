"""audit PATH...: several files and folders in worker processes, one line (or one JSON
object) per file, a total, the worst exit code; macros are named, not checked."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import xlsxwriter

from workbook_gen import audit
from workbook_gen.auditor.report import format_report

CORPUS = Path("/work/shared/corpus/xlsx")


def run_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "workbook_gen.cli", *args],
                          capture_output=True, text=True, timeout=600)


def _book(path: Path, cached: float) -> Path:
    """=A1+A2 over 1.5 and 2.25, with ``cached`` as its stored value."""
    path.parent.mkdir(parents=True, exist_ok=True)
    book = xlsxwriter.Workbook(path)
    sheet = book.add_worksheet()
    sheet.write_number("A1", 1.5)
    sheet.write_number("A2", 2.25)
    sheet.write_formula("A3", "=A1+A2", None, cached)
    book.close()
    return path


@pytest.fixture
def folder(tmp_path):
    _book(tmp_path / "books" / "a_good.xlsx", 3.75)
    _book(tmp_path / "books" / "sub" / "b_wrong.xlsx", 3.5)
    _book(tmp_path / "books" / "sub" / "c_good.xlsm", 3.75)
    (tmp_path / "books" / "notes.txt").write_text("not a workbook, not searched")
    return tmp_path / "books"


def test_folder_gives_one_line_per_file_and_a_total_with_the_worst_exit(folder, tmp_path):
    garbage = tmp_path / "garbage.xlsx"
    garbage.write_text("not a zip")
    result = run_cli("audit", str(folder), str(garbage), "--jobs", "2")
    lines = result.stdout.strip().splitlines()
    assert result.returncode == 2, result.stderr
    assert [line.split()[0] for line in lines[:-1]] == ["OK", "FAIL", "OK", "ERROR"]
    assert "a_good.xlsx" in lines[0] and "b_wrong.xlsx" in lines[1] and "c_good.xlsm" in lines[2]
    assert "not a zip" in lines[3] and "Traceback" not in result.stderr
    assert lines[-1].startswith("total: 4 files: 2 ok, 1 failed (1 with cells that disagree), "
                               "1 refused")
    only_folder = run_cli("audit", str(folder), "--jobs", "2")
    assert only_folder.returncode == 1  # the worst of ok and disagree


def test_json_lines_one_object_per_file(folder):
    result = run_cli("audit", str(folder), "--json", "--jobs", "2")
    objects = [json.loads(line) for line in result.stdout.splitlines()]
    assert [Path(o["file"]).name for o in objects] == ["a_good.xlsx", "b_wrong.xlsx",
                                                        "c_good.xlsm"]
    assert [o["ok"] for o in objects] == [True, False, True]
    assert objects[1]["cells_disagree"] == 1 and objects[1]["mismatches"][0]["cell"] == "Sheet1!A3"


def test_single_file_json_is_one_line(folder):
    result = run_cli("audit", str(folder / "a_good.xlsx"), "--json")
    assert result.returncode == 0
    assert len(result.stdout.strip().splitlines()) == 1
    assert json.loads(result.stdout)["cells_agree"] == 1


def test_missing_path_is_one_line_exit_2(tmp_path):
    result = run_cli("audit", str(tmp_path / "nowhere"), str(tmp_path))
    assert result.returncode == 2
    assert result.stderr.strip().endswith("nowhere: no such file or folder")


@pytest.fixture(scope="module")
def macro_book() -> Path:
    path = CORPUS / "xlcalculator__use_case_01.xlsm"
    if not path.is_file():
        pytest.fail(f"the corpus workbook {path} is missing (see ../shared/corpus/README.md)",
                    pytrace=False)
    return path


def test_macros_are_named_as_not_checked(macro_book, folder):
    report = audit(macro_book)
    assert report.macros == "xl/vbaProject.bin"
    assert report.to_json()["macros"] == "xl/vbaProject.bin"
    assert "holds a VBA project (xl/vbaProject.bin); the audit does not check macros" \
        in format_report(report)
    plain = audit(folder / "a_good.xlsx")
    assert plain.macros is None and "VBA project" not in format_report(plain)


@pytest.mark.parametrize("many", [False, True], ids=["one file", "a folder"])
def test_audit_draws_a_bar_on_a_terminal(folder, many):
    """In a real pseudo-terminal the audit shows a bar on stderr (its delay set to 0: these
    audits take less than the 1 s the command line waits); not otherwise (tests above)."""
    from terminal import run_in_terminal
    target = folder if many else folder / "a_good.xlsx"
    status, text = run_in_terminal(['audit', str(target), '--jobs', '1'])
    assert status == (1 if many else 0), text
    assert ("/3 [" if many else "/5 [") in text, text  # 3 files; 5 phases without --engine
    assert ("file/s" if many else "phase/s") in text, text


def test_engine_lines_truncate_long_values(folder):
    """--engine libreoffice prints a disagreement's formula and values cut to a line."""
    from workbook_gen.auditor.report import EngineResult, Mismatch
    report = audit(folder / "a_good.xlsx")
    long = "x" * 5000
    report.engine = EngineResult("libreoffice", 1, [Mismatch(
        "Sheet1!A3", f'REPT("{long}",2)', long * 2, long + "y")], 0, 0.1)
    lines = format_report(report).splitlines()
    shown = [line for line in lines if "Sheet1!A3" in line]
    assert shown and all(len(line) < 400 for line in lines)
    assert "..." in shown[0]
