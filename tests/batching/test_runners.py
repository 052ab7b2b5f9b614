"""workbook-gen batch on a Dask cluster (docs/batch.md, Running on several cores or a Dask cluster):
the same bytes as a local run, on a LocalCluster and on a real `dask scheduler` with two `dask
worker` processes, one of which is killed in the middle of the batch."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

from workbook_gen import batch

ROOT = Path(__file__).resolve().parents[2]
SEWING = str(ROOT / "templates" / "sewing_machine.toml")
VARY = ["l_BC=20,95,105", "l_AB=-1,30,32"]
# Enough variants that a worker can be killed while many are still to do.
LONG_VARY = ["l_BC=95:105:1", "l_AB=30,32"]


def _files(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())
            if p.suffix in (".xlsx", ".csv")}


def _local(folder: Path, monkeypatch, vary) -> dict[str, bytes]:
    folder.mkdir(parents=True)
    monkeypatch.chdir(folder)
    batch(SEWING, vary=vary, out="out", step=30.0, jobs=1, progress=False)
    return _files(folder / "out" / "sewing_machine-batch")


@pytest.fixture(scope="session")
def dask_client():
    """A LocalCluster of two single-threaded worker processes, with this tree importable."""
    from distributed import Client, LocalCluster
    os.environ["PYTHONPATH"] = os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])
    cluster = LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                           dashboard_address=":0")
    client = Client(cluster)
    try:
        yield client
    finally:
        client.close()
        cluster.close()


def test_dask_local_cluster_writes_the_bytes_of_a_local_run(tmp_path, monkeypatch,
                                                            dask_client):
    local = _local(tmp_path / "local", monkeypatch, VARY)
    (tmp_path / "dask").mkdir()
    monkeypatch.chdir(tmp_path / "dask")
    frame = batch(SEWING, vary=VARY, out="out", step=30.0, client=dask_client,
                  progress=False)
    assert _files(tmp_path / "dask" / "out" / "sewing_machine-batch") == local
    assert frame.attrs["failed"] == 5  # 3 refused, 2 partial, as locally


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _spawn(args: list[str], env: dict, log: Path, cwd: Path | None = None
           ) -> subprocess.Popen:
    return subprocess.Popen(args, env=env, cwd=cwd, stdout=log.open("w"),
                            stderr=subprocess.STDOUT, start_new_session=True)


def _stop(process: subprocess.Popen) -> None:
    if process.poll() is None:
        os.killpg(process.pid, signal.SIGTERM)
        try:
            process.wait(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()


def test_a_worker_killed_mid_batch_loses_nothing(tmp_path, monkeypatch):
    local = _local(tmp_path / "local", monkeypatch, LONG_VARY)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    dask = [sys.executable, "-m", "distributed.cli.dask_scheduler"]
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    processes = []
    try:
        processes.append(_spawn(dask + ["--host", "127.0.0.1", "--port", str(port),
                                        "--dashboard-address", ":0"], env,
                                tmp_path / "scheduler.log"))
        workers = [_spawn([sys.executable, "-m", "distributed.cli.dask_worker", address,
                           "--nthreads", "1", "--no-nanny", "--dashboard-address", ":0"],
                          env, tmp_path / f"worker{i}.log") for i in range(2)]
        processes += workers
        from distributed import Client
        with Client(address, timeout="60s") as client:
            client.wait_for_workers(2, timeout=120)
        run = tmp_path / "dask"
        run.mkdir()
        command = _spawn([sys.executable, "-m", "workbook_gen.cli", "batch", SEWING,
                          "--step", "30", "--out", "out", "--scheduler", address, "--quiet"]
                         + [a for v in LONG_VARY for a in ("--vary", v)], env,
                         tmp_path / "batch.log", cwd=run)
        processes.append(command)
        journal = run / "out" / "sewing_machine-batch" / ".batch-journal.jsonl"
        deadline = time.monotonic() + 300
        while time.monotonic() < deadline and command.poll() is None:
            if journal.exists() and len(journal.read_text().splitlines()) >= 3:
                break
            time.sleep(0.05)
        done_at_kill = len(journal.read_text().splitlines()) if journal.exists() else 0
        assert command.poll() is None, (tmp_path / "batch.log").read_text()
        os.killpg(workers[0].pid, signal.SIGKILL)
        assert command.wait(timeout=600) == 0, (tmp_path / "batch.log").read_text()
        assert done_at_kill < 22  # the kill came with most variants still to do
        assert _files(run / "out" / "sewing_machine-batch") == local
    finally:
        for process in reversed(processes):
            _stop(process)
