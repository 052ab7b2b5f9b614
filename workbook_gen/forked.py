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

A generator function sends each value as it is made: ``job.next()`` gives them in turn,
so that the caller can use the first while the child makes the next.
"""

from __future__ import annotations

import inspect
import os
import pickle
import signal
import struct
import threading

_LENGTH = struct.Struct("<Q")  # each value a generator sends: its length, then its pickle


def can_fork() -> bool:
    return (hasattr(os, "fork") and threading.active_count() == 1
            and os.environ.get("WORKBOOK_GEN_SERIAL", "") != "1")


class Forked:
    """``fn(*args)`` computed in a child process (see the module's docstring)."""

    def __init__(self, fn, *args) -> None:
        self._fn, self._args = fn, args
        self._pid: int | None = None
        self._parts = inspect.isgeneratorfunction(fn)
        self._taken, self._here = 0, None  # values received; the generator run here
        if not can_fork():
            return
        read_end, write_end = os.pipe()
        pid = os.fork()
        if pid == 0:  # the child: compute, send, and leave without running any cleanup
            try:
                os.close(read_end)
                with os.fdopen(write_end, "wb") as out:
                    if self._parts:
                        _send_each(fn(*args), out)
                    else:
                        out.write(_pickled(fn, args))
            finally:
                os._exit(0)
        os.close(write_end)
        self._pid, self._fd = pid, read_end
        if self._parts:
            self._pipe = os.fdopen(read_end, "rb")

    def next(self):
        """The next value a generator function made (its exception, raised here)."""
        if self._here is None and self._pid is not None:
            head = self._pipe.read(_LENGTH.size)
            data = self._pipe.read(_LENGTH.unpack(head)[0]) if len(head) == _LENGTH.size else b""
            try:
                ok, value = pickle.loads(data)
            except Exception:  # the child died or could not pickle: go on here
                self.cancel()
            else:
                self._taken += 1
                if ok:
                    return value
                self.cancel()
                raise value
        if self._here is None:  # made here, after the values the child sent
            self._here = self._fn(*self._args)
            for _ in range(self._taken):
                next(self._here)
        return next(self._here)

    def close(self) -> None:
        """After a generator's last value: wait for the child to end."""
        if self._pid is not None:
            self._pipe.close()
            os.waitpid(self._pid, 0)
            self._pid = None

    def result(self):
        if self._parts:
            return self.next()
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
        """Stop the child (when its result, or its next values, are no longer wanted)."""
        if self._pid is None:
            return
        try:
            os.kill(self._pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        if self._parts:
            self._pipe.close()
        else:
            os.close(self._fd)
        os.waitpid(self._pid, 0)
        self._pid = None


def _pickled(fn, args) -> bytes:
    """``(True, fn(*args))`` or ``(False, its exception)`` pickled; b"" if it cannot be."""
    try:
        outcome = (True, fn(*args))
    except BaseException as exc:  # handed to the parent, which raises it
        outcome = (False, exc)
    return _dumps(outcome)


def _dumps(outcome: tuple) -> bytes:
    """An outcome pickled; b"" if it cannot be (the parent then computes it itself)."""
    try:
        return pickle.dumps(outcome, protocol=pickle.HIGHEST_PROTOCOL)
    except Exception:
        return b""


def _send_each(values, out) -> None:
    """Each value of a generator as it is made, its length first; nothing more after an
    exception (sent, for the parent to raise) or a value that cannot be pickled."""
    it = iter(values)
    while True:
        try:
            outcome = (True, next(it))
        except StopIteration:
            return
        except BaseException as exc:
            outcome = (False, exc)
        data = _dumps(outcome)
        if not data:
            return  # the parent makes it, and those after it, itself
        out.write(_LENGTH.pack(len(data)) + data)
        out.flush()
        if not outcome[0]:
            return
