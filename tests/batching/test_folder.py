"""A batch rerun never destroys work (docs/batch.md, Running again; issue 22 items 5-7): files
edited since the batch wrote them are kept and named (exit 1) unless --force; the temporary files of
a killed run are removed by the next run, and a SIGTERM'd run removes its own; with --scheduler and
no Dask worker connected the run says so, waits, and gives up after --timeout.  Real processes
throughout: the batches killed are `workbook-gen batch` subprocesses, the cluster a `dask scheduler`
and a `dask worker`."""

from __future__ import annotations

import csv
import io
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import openpyxl
import pytest

from workbook_gen import cli

ROOT = Path(__file__).resolve().parents[2]
SEWING = str(ROOT / "templates" / "sewing_machine.toml")
SMALL = ["--vary", "l_BC=95,100,105", "--step", "30"]
# Enough variants (22, 36 rows each) that a run is killed with most of them to do.
LONG = ["--vary", "l_BC=95:105:1", "--vary", "l_AB=30,32", "--step", "10"]
FOLDER = "sewing_machine-batch"
ENV = dict(os.environ, PYTHONPATH=os.pathsep.join(
    [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
PATIENCE = 300  # seconds before a wait for a subprocess is a failure (a hang, not a time)


def _batch(out: Path, *extra: str) -> list[str]:
    return ["batch", SEWING, *SMALL, "--out", str(out), "--jobs", "1", "--quiet", *extra]


def _files(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir()) if not p.name.startswith(".")}


def _temporaries(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.endswith(".tmp"))


def _rows(data: bytes) -> dict[str, dict[str, str]]:
    return {r["file"]: r for r in csv.DictReader(io.StringIO(data.decode()))}


def _edit_workbook(path: Path, note: str) -> None:
    """What a user does: open the workbook (openpyxl, not our writer), type, save."""
    book = openpyxl.load_workbook(path)
    book.worksheets[0]["A1"] = note
    book.save(path)


# -- 5. a rerun keeps what was edited since ----------------------------------------------

def test_rerun_keeps_an_edited_workbook_names_it_and_exits_1(tmp_path, capsys):
    assert cli.main(_batch(tmp_path)) == 0
    folder = tmp_path / FOLDER
    made = _files(folder)
    edited = folder / "sewing_machine-0002.xlsx"
    _edit_workbook(edited, "my design note")
    mine = edited.read_bytes()
    (folder / "sewing_machine-0003.xlsx").unlink()   # and a workbook to make again
    capsys.readouterr()
    assert cli.main(_batch(tmp_path)) == 1
    err = capsys.readouterr().err
    assert err.count("kept ") == 1 and f"kept {edited}:" in err and "--force" in err
    assert edited.read_bytes() == mine                             # the user's work
    assert openpyxl.load_workbook(edited).worksheets[0]["A1"].value == "my design note"
    assert (folder / "sewing_machine-0003.xlsx").read_bytes() == made["sewing_machine-0003.xlsx"]
    # The summary still describes the variant as the batch made it.
    assert _rows((folder / "summary.csv").read_bytes()) == _rows(made["summary.csv"])
    assert (folder / "summary.xlsx").read_bytes() == made["summary.xlsx"]
    # --force regenerates it.
    assert cli.main(_batch(tmp_path, "--force")) == 0
    assert _files(folder) == made


def test_rerun_keeps_edited_summaries_and_writes_the_unedited(tmp_path, capsys):
    assert cli.main(_batch(tmp_path)) == 0
    folder = tmp_path / FOLDER
    made = _files(folder)
    summary_csv, summary_xlsx = folder / "summary.csv", folder / "summary.xlsx"
    with summary_csv.open("a") as handle:
        handle.write("checked by R. Ito,,,\n")
    mine = summary_csv.read_bytes()
    (folder / "sewing_machine-0001.xlsx").unlink()
    capsys.readouterr()
    assert cli.main(_batch(tmp_path)) == 1
    err = capsys.readouterr().err
    assert f"kept {summary_csv}" in err and "summary.xlsx" not in err
    assert summary_csv.read_bytes() == mine
    assert summary_xlsx.read_bytes() == made["summary.xlsx"]  # unedited: written again
    assert (folder / "sewing_machine-0001.xlsx").read_bytes() == made["sewing_machine-0001.xlsx"]
    # Now the workbook of summaries edited too: both kept, and again on the next rerun.
    book = openpyxl.load_workbook(summary_xlsx)
    book["Variants"]["A1"] = "variant (R. Ito's pick: 2)"
    book.save(summary_xlsx)
    mine_xlsx = summary_xlsx.read_bytes()
    for _ in range(2):
        assert cli.main(_batch(tmp_path)) == 1
        err = capsys.readouterr().err
        assert f"kept {summary_csv}" in err and f"kept {summary_xlsx}" in err
        assert summary_csv.read_bytes() == mine and summary_xlsx.read_bytes() == mine_xlsx
    assert cli.main(_batch(tmp_path, "--force")) == 0
    assert _files(folder) == made


def test_a_workbook_without_its_journal_line_is_adopted_if_ours_and_kept_if_not(tmp_path,
                                                                                capsys):
    """A run killed between a workbook's rename and its journal line leaves the batch's
    own file: adopted untouched.  Any other file under that name is kept and named."""
    assert cli.main(_batch(tmp_path)) == 0
    folder = tmp_path / FOLDER
    made = _files(folder)
    journal = folder / ".batch-journal.jsonl"
    lines = journal.read_text().splitlines()
    variant_lines = [line for line in lines if '"index"' in line]
    third = next(line for line in variant_lines if '"index": 3' in line)
    journal.write_text("\n".join(line for line in lines if line != third) + "\n")
    stamp = (folder / "sewing_machine-0003.xlsx").stat().st_mtime_ns
    assert cli.main(_batch(tmp_path)) == 0
    assert (folder / "sewing_machine-0003.xlsx").stat().st_mtime_ns == stamp  # not rewritten
    assert _files(folder) == made
    # Another file under a variant's name, with no journal line for it.
    lines = journal.read_text().splitlines()
    journal.write_text("\n".join(line for line in lines if '"index": 3' not in line) + "\n")
    other = made["sewing_machine-0001.xlsx"]
    (folder / "sewing_machine-0003.xlsx").write_bytes(other)
    capsys.readouterr()
    assert cli.main(_batch(tmp_path)) == 1
    assert f"kept {folder / 'sewing_machine-0003.xlsx'}" in capsys.readouterr().err
    assert (folder / "sewing_machine-0003.xlsx").read_bytes() == other


# -- 6. temporary files of a killed run --------------------------------------------------

def _spawn(args: list[str], cwd: Path, log: Path) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", *args], env=ENV, cwd=cwd,
                            stdout=log.open("w"), stderr=subprocess.STDOUT,
                            start_new_session=True)


def _start_long_batch(run: Path, *extra: str) -> subprocess.Popen:
    """A `workbook-gen batch` subprocess of 22 variants (``LONG`` and ``extra``),
    returned once it has finished two of them (its journal says so) and is still
    running."""
    run.mkdir(parents=True, exist_ok=True)
    process = _spawn(["workbook_gen.cli", "batch", SEWING, *LONG, "--out", "out", "--quiet",
                      *extra], run, run / "batch.log")
    journal = run / "out" / FOLDER / ".batch-journal.jsonl"
    deadline = time.monotonic() + PATIENCE
    while time.monotonic() < deadline and process.poll() is None:
        if journal.exists() and journal.read_text().count('"index"') >= 2:
            break
        time.sleep(0.02)
    assert process.poll() is None, (run / "batch.log").read_text()
    return process


@pytest.fixture(scope="module")
def reference(tmp_path_factory) -> dict[str, bytes]:
    """The files of an uninterrupted run of the long batch (same relative --out)."""
    run = tmp_path_factory.mktemp("reference")
    done = subprocess.run([sys.executable, "-m", "workbook_gen.cli", "batch", SEWING, *LONG,
                           "--out", "out", "--quiet", "--jobs", "2"], env=ENV, cwd=run,
                          capture_output=True, text=True, timeout=PATIENCE)
    assert done.returncode == 0, done.stderr
    return _files(run / "out" / FOLDER)


def _no_process_left(group: int) -> bool:
    try:
        os.killpg(group, 0)
    except ProcessLookupError:
        return True
    return False


def test_sigterm_mid_run_removes_its_temporaries_ends_its_workers_and_exits_143(tmp_path,
                                                                                reference):
    run = tmp_path / "run"
    process = _start_long_batch(run, "--jobs", "2")
    folder = run / "out" / FOLDER
    assert any(n.startswith(".summary.") for n in _temporaries(folder))  # in the middle
    os.kill(process.pid, signal.SIGTERM)       # the command only, as `kill PID` does
    assert process.wait(timeout=PATIENCE) == 143, (run / "batch.log").read_text()
    log = (run / "batch.log").read_text()
    assert log.strip() == "workbook-gen: terminated (SIGTERM)", log  # no traceback
    assert _temporaries(folder) == [], log
    deadline = time.monotonic() + PATIENCE     # the forked workers ended with it
    while not _no_process_left(process.pid) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert _no_process_left(process.pid), subprocess.run(
        ["ps", "-o", "pid,stat,cmd", "-g", str(process.pid)], capture_output=True,
        text=True).stdout
    # The journal kept what was done: the rerun completes the batch as an uninterrupted run.
    again = subprocess.run([sys.executable, "-m", "workbook_gen.cli", "batch", SEWING, *LONG,
                            "--out", "out", "--quiet", "--jobs", "2"], env=ENV, cwd=run,
                           capture_output=True, text=True, timeout=PATIENCE)
    assert again.returncode == 0 and again.stderr == "", again.stderr
    assert _files(folder) == reference


_MID_RESULT = """
import sys
from workbook_gen.batching.runners import LocalPool

def big(spec, part):
    return b"x" * 50_000_000   # sent through a pipe for a while

run = LocalPool(2).run(big, None, [[i] for i in range(6)])
next(run), next(run)   # (the first in this process)
run.close()            # what an error or SIGTERM in the batch does
print("stopped")
"""


def test_a_pool_stopped_mid_result_lets_the_process_exit():
    """Workers ended while they send a result must not leave the pool's reading thread
    (and the interpreter's exit, which waits for it) blocked for ever."""
    done = subprocess.run([sys.executable, "-c", _MID_RESULT], env=ENV, capture_output=True,
                          text=True, timeout=PATIENCE)
    assert done.returncode == 0 and done.stdout == "stopped\n", done.stderr


@pytest.mark.parametrize("mode", [[], ["--force"]], ids=["rerun", "force"])
def test_the_next_run_removes_the_temporaries_of_a_killed_run(tmp_path, mode, reference):
    run = tmp_path / "run"
    process = _start_long_batch(run, "--jobs", "1")
    os.killpg(process.pid, signal.SIGKILL)     # no chance to clean up
    process.wait(timeout=PATIENCE)
    folder = run / "out" / FOLDER
    left = _temporaries(folder)
    assert any(n.startswith(".summary.") and n.endswith(".csv.tmp") for n in left)
    # What an interrupted write of a workbook leaves (a killed rename), beside a file
    # of the user's that only looks alike.
    (folder / ".sewing_machine-0020.k2j_h4g5.xlsx.tmp").write_bytes(b"PK\x03\x04")
    (folder / ".notes.k2j_h4g5.csv.tmp").write_text("mine")
    done = subprocess.run([sys.executable, "-m", "workbook_gen.cli", "batch", SEWING, *LONG,
                           "--out", "out", "--quiet", "--jobs", "2", *mode], env=ENV,
                          cwd=run, capture_output=True, text=True, timeout=PATIENCE)
    assert done.returncode == 0, done.stderr
    assert _temporaries(folder) == [".notes.k2j_h4g5.csv.tmp"]
    assert _files(folder) == reference


def test_a_second_run_into_a_folder_being_written_is_refused(tmp_path, capsys, monkeypatch):
    """The next run sweeps temporaries only of runs that have ended: one still running
    holds the folder, and a second command into it is refused (exit 2) and touches
    nothing, --force or not."""
    run = tmp_path / "run"
    slower = ["--step", "5", "--jobs", "1"]  # (the last --step counts)
    process = _start_long_batch(run, *slower)
    monkeypatch.chdir(run)
    try:
        for extra in ([], ["--force"]):
            capsys.readouterr()
            assert cli.main(["batch", SEWING, *LONG, "--out", "out", "--quiet", *slower,
                             *extra]) == 2
            err = capsys.readouterr().err
            assert "still running" in err and err.count("\n") == 1
        assert process.wait(timeout=PATIENCE) == 0, (run / "batch.log").read_text()
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
    assert _temporaries(run / "out" / FOLDER) == []
    assert len(list((run / "out" / FOLDER).glob("sewing_machine-*.xlsx"))) == 22


# -- 7. --scheduler with no Dask worker ------------------------------------------------------

def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _stop(process: subprocess.Popen) -> None:
    if process.poll() is None:
        os.killpg(process.pid, signal.SIGTERM)
        try:
            process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()


@pytest.fixture(scope="module")
def lone_scheduler(tmp_path_factory):
    """A real `dask scheduler` with no worker; its address."""
    logs = tmp_path_factory.mktemp("scheduler")
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    process = _spawn(["distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port",
                      str(port), "--dashboard-address", ":0"], logs, logs / "scheduler.log")
    try:
        deadline = time.monotonic() + PATIENCE
        while time.monotonic() < deadline:
            assert process.poll() is None, (logs / "scheduler.log").read_text()
            with socket.socket() as s:
                if s.connect_ex(("127.0.0.1", port)) == 0:
                    break
            time.sleep(0.1)
        yield address
    finally:
        _stop(process)


@pytest.mark.parametrize("extra, message", [
    (["--timeout", "5"], "--timeout goes with --scheduler"),
    (["--timeout", "0", "--scheduler", "tcp://127.0.0.1:9"], "--timeout must be > 0"),
])
def test_a_bad_timeout_exits_2_and_writes_nothing(tmp_path, capsys, extra, message):
    assert cli.main(["batch", SEWING, *SMALL, "--out", str(tmp_path), "--quiet", *extra]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []


def test_no_dask_worker_is_said_and_the_timeout_gives_up_with_exit_2(tmp_path, lone_scheduler,
                                                                     monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    code = cli.main(["batch", SEWING, *SMALL, "--out", "out", "--quiet",
                     "--scheduler", lone_scheduler, "--timeout", "3"])
    err = capsys.readouterr().err.splitlines()
    assert code == 2
    assert (f"workbook-gen: waiting for Dask workers at {lone_scheduler}: none connected"
            in err)
    assert err[-1] == (f"workbook-gen: error: --scheduler {lone_scheduler}: no Dask worker "
                       f"connected within --timeout 3 s")
    assert not (tmp_path / "out").exists()  # nothing written


def test_a_worker_started_late_runs_the_waiting_batch(tmp_path, lone_scheduler, monkeypatch):
    run = tmp_path / "dask"
    run.mkdir()
    log = run / "batch.log"
    command = _spawn(["workbook_gen.cli", "batch", SEWING, *SMALL, "--out", "out", "--quiet",
                      "--scheduler", lone_scheduler, "--timeout", str(PATIENCE)], run, log)
    worker = None
    try:
        deadline = time.monotonic() + PATIENCE
        while "none connected" not in log.read_text() and time.monotonic() < deadline:
            assert command.poll() is None, log.read_text()
            time.sleep(0.05)
        assert "none connected" in log.read_text()
        assert not (run / "out").exists()    # waiting, nothing written yet
        worker = _spawn(["distributed.cli.dask_worker", lone_scheduler, "--nthreads", "1",
                         "--no-nanny", "--dashboard-address", ":0"], run, run / "worker.log")
        assert command.wait(timeout=PATIENCE) == 0, log.read_text()
    finally:
        _stop(command)
        if worker is not None:
            _stop(worker)
    local = tmp_path / "local"
    local.mkdir()
    monkeypatch.chdir(local)
    assert cli.main(["batch", SEWING, *SMALL, "--out", "out", "--quiet", "--jobs", "1"]) == 0
    assert _files(run / "out" / FOLDER) == _files(local / "out" / FOLDER)
