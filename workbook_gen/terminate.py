"""SIGTERM as an exception, so that a terminated command cleans up as on an error.

By default SIGTERM ends a Python process at once: no ``finally`` runs, and a batch
leaves its temporary files (``.summary.*.csv.tmp``, ``.<name>-0007.*.xlsx.tmp``).
Inside ``sigterm_raises()`` the first SIGTERM is noted, and ``check()``, which the
batch calls between its steps (each chunk of variants, and every quarter second while
it waits for workers), raises ``Terminated``: the code unwinds through its ``finally``
and ``except BaseException`` blocks (temporary files removed, worker processes ended)
and the command line exits 143 (128 + 15, the shells' code for a SIGTERM'd process).
The handler itself raises nothing: an exception raised wherever the main thread
happens to be can leave a lock half-taken (``concurrent.futures.wait`` takes one per
future) and the process hung at exit.  A second SIGTERM ends the process at once, as
usual.  Processes forked meanwhile (local workers) keep the default: they end at once,
and the command that forked them deals with it.
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading

EXIT_CODE = 128 + signal.SIGTERM
POLL = 0.25   # seconds between checks while blocked waiting

_requested = False


class Terminated(BaseException):
    """SIGTERM arrived (a BaseException, as KeyboardInterrupt: not an error to handle)."""


def check() -> None:
    """Raise ``Terminated`` if SIGTERM arrived (inside ``sigterm_raises``)."""
    if _requested:
        raise Terminated()


@contextlib.contextmanager
def sigterm_raises():
    """SIGTERM makes ``check()`` raise ``Terminated`` while inside (main thread only)."""
    global _requested
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    owner = os.getpid()

    def handler(signum, frame):
        global _requested
        signal.signal(signal.SIGTERM, signal.SIG_DFL)  # the next one ends us at once
        if os.getpid() != owner:  # a forked worker: end as by default
            os.kill(os.getpid(), signal.SIGTERM)
            return
        _requested = True

    _requested = False
    previous = signal.signal(signal.SIGTERM, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)
        _requested = False
