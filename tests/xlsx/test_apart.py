"""The forked reading of the biggest sheets (tests/apart_cases.py), run in a fresh pytest
process: a process forks only while it has no other thread (workbook_gen/forked.py), and
this suite's process has some once the session's Dask cluster runs."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

CASES = Path(__file__).resolve().parents[1] / "apart_cases.py"


def test_forked_reading_in_a_process_without_threads():
    env = {k: v for k, v in os.environ.items() if k != "WORKBOOK_GEN_SERIAL"}
    done = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                           str(CASES)], capture_output=True, text=True, env=env,
                          cwd=CASES.parent.parent, timeout=600)
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-2000:]
    assert " passed" in done.stdout and "skipped" not in done.stdout, done.stdout[-2000:]
