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

ROOT = Path(__file__).resolve().parent.parent
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
