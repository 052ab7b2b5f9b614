"""workbook_gen/terminate.py: inside ``sigterm_raises()`` a SIGTERM is noted and the next
``check()`` raises Terminated (a BaseException, so ``finally`` blocks run); a second
SIGTERM ends the process as by default; outside, SIGTERM's handler is what it was. The
signals are real (os.kill of a child Python process, or of this one)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap

import pytest

from workbook_gen import terminate
from workbook_gen.terminate import EXIT_CODE, Terminated, check, sigterm_raises


def test_exit_code_is_the_shells():
    assert EXIT_CODE == 143 and issubclass(Terminated, BaseException)
    assert not issubclass(Terminated, Exception)


def test_a_sigterm_inside_raises_at_the_next_check_and_the_handler_is_restored():
    before = signal.getsignal(signal.SIGTERM)
    cleaned = []
    with pytest.raises(Terminated):
        with sigterm_raises():
            check()                            # nothing yet
            os.kill(os.getpid(), signal.SIGTERM)
            try:
                check()
            finally:
                cleaned.append(True)
    assert cleaned == [True]
    assert signal.getsignal(signal.SIGTERM) == before
    check()                                    # outside: never raises
    assert terminate._requested is False


def run(code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True,
                          text=True, timeout=60, env={**os.environ, "PYTHONPATH": os.getcwd()})


def test_the_second_sigterm_ends_the_process_at_once():
    done = run("""
        import os, signal
        from workbook_gen.terminate import sigterm_raises
        with sigterm_raises():
            os.kill(os.getpid(), signal.SIGTERM)   # noted
            print("noted", flush=True)
            os.kill(os.getpid(), signal.SIGTERM)   # the default: the process ends here
            print("still running", flush=True)
    """)
    assert done.stdout.split() == ["noted"]
    assert done.returncode == -signal.SIGTERM


def test_a_terminated_command_unwinds_through_finally():
    done = run("""
        import os, signal
        from workbook_gen.terminate import EXIT_CODE, Terminated, check, sigterm_raises
        try:
            with sigterm_raises():
                try:
                    os.kill(os.getpid(), signal.SIGTERM)
                    check()
                finally:
                    print("cleaned", flush=True)
        except Terminated:
            raise SystemExit(EXIT_CODE)
    """)
    assert done.stdout.split() == ["cleaned"] and done.returncode == 143
