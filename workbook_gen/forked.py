"""Run one function in a forked child process, on another core, while the caller goes on.

    job = Forked(read_these_sheets, path, parts)
    ...                       # the caller's own share of the work
    result = job.result()     # the child's return value (or its exception, raised here)

The child inherits the caller's memory as it is at the fork (nothing is sent to it) and
sends its result back pickled through a pipe, so a result should be compact (columns, not
many small objects). Where fork is not available, where other threads run (a fork copies
only the calling thread, and locks the others hold would stay held in the child), or with
``WORKBOOK_GEN_SERIAL=1`` in the environment, the function simply runs inside
``result()``. A child that dies or whose result cannot be pickled is no failure either:
the function then runs inside ``result()`` too, so the outcome is always the function's own.
"""

from __future__ import annotations

import os
import pickle
import signal
import threading


def can_fork() -> bool:
    return (hasattr(os, "fork") and threading.active_count() == 1
            and os.environ.get("WORKBOOK_GEN_SERIAL", "") != "1")


class Forked:
    """``fn(*args)`` computed in a child process (see the module's docstring)."""

    def __init__(self, fn, *args) -> None:
        self._fn, self._args = fn, args
        self._pid: int | None = None
        if not can_fork():
            return
        read_end, write_end = os.pipe()
        pid = os.fork()
        if pid == 0:  # the child: compute, send, and leave without running any cleanup
            try:
                os.close(read_end)
                try:
                    outcome = (True, fn(*args))
                except BaseException as exc:  # handed to the parent, which raises it
                    outcome = (False, exc)
                try:
                    data = pickle.dumps(outcome, protocol=pickle.HIGHEST_PROTOCOL)
                except Exception:
                    data = b""  # the parent computes it itself
                with os.fdopen(write_end, "wb") as out:
                    out.write(data)
            finally:
                os._exit(0)
        os.close(write_end)
        self._pid, self._fd = pid, read_end

    def result(self):
        if self._pid is None:
            return self._fn(*self._args)
        try:
            with os.fdopen(self._fd, "rb") as pipe:
                data = pipe.read()
        finally:
            os.waitpid(self._pid, 0)
            self._pid = None
        try:
            ok, value = pickle.loads(data)
        except Exception:  # the child died or could not pickle: compute it here
            return self._fn(*self._args)
        if ok:
            return value
        raise value

    def cancel(self) -> None:
        """Stop the child (when its result is no longer wanted)."""
        if self._pid is None:
            return
        try:
            os.kill(self._pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        os.close(self._fd)
        os.waitpid(self._pid, 0)
        self._pid = None
