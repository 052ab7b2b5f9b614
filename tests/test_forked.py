"""workbook_gen/forked.py: ``Forked(fn, *args)`` gives ``fn(*args)``: computed in a child
process (whose pid differs), its exception raised in the caller, a result that cannot be
pickled computed again in the caller; a generator's values one by one; with
WORKBOOK_GEN_SERIAL=1 (or where threads run) nothing forks.

The forking checks run in a fresh interpreter: a pytest process may hold threads of
other tests, and then (rightly) nothing forks."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
import threading
from pathlib import Path

from workbook_gen.forked import Forked, can_fork

ROOT = Path(__file__).resolve().parents[1]

FORKING = textwrap.dedent("""
    import os
    from workbook_gen.forked import Forked, can_fork

    def pid_and_square(x):
        return os.getpid(), x * x

    def fails(x):
        raise ValueError(f"bad {x}")

    def unpicklable(x):
        return lambda: x   # a lambda cannot be pickled: the caller computes it itself

    def counting(n):
        for i in range(n):
            yield os.getpid(), i

    assert can_fork()
    pid, value = Forked(pid_and_square, 12).result()
    assert value == 144 and pid != os.getpid(), (pid, value)
    try:
        Forked(fails, 3).result()
        raise AssertionError("no exception")
    except ValueError as exc:
        assert str(exc) == "bad 3"
    assert Forked(unpicklable, 7).result()() == 7
    job = Forked(counting, 4)
    got = [job.next() for _ in range(4)]
    job.close()
    assert [i for _, i in got] == [0, 1, 2, 3]
    assert os.getpid() not in {pid for pid, _ in got}
    job = Forked(pid_and_square, 2)
    child = job._pid
    job.cancel()
    try:
        os.kill(child, 0)
        raise AssertionError("the child still exists")
    except ProcessLookupError:
        pass
    print("ok")
""")


def test_forking_in_a_fresh_interpreter():
    env = {k: v for k, v in os.environ.items() if k != "WORKBOOK_GEN_SERIAL"}
    env["PYTHONPATH"] = str(ROOT)
    done = subprocess.run([sys.executable, "-c", FORKING], capture_output=True, text=True,
                          env=env, timeout=120)
    assert done.returncode == 0 and done.stdout.split() == ["ok"], done.stderr


def pid_and_square(x):
    return os.getpid(), x * x


def test_serial_runs_here(monkeypatch):
    monkeypatch.setenv("WORKBOOK_GEN_SERIAL", "1")
    assert not can_fork()
    assert Forked(pid_and_square, 3).result() == (os.getpid(), 9)


def test_no_fork_while_another_thread_runs(monkeypatch):
    monkeypatch.delenv("WORKBOOK_GEN_SERIAL", raising=False)
    stop = threading.Event()
    other = threading.Thread(target=stop.wait)
    other.start()
    try:
        assert not can_fork()   # a fork would copy the other thread's locks, held
        assert Forked(pid_and_square, 4).result() == (os.getpid(), 16)
    finally:
        stop.set()
        other.join()
