"""SIGTERM as an exception, so that a terminated command cleans up as on an error.

By default SIGTERM ends a Python process at once: no ``finally`` runs, and a batch
leaves its temporary files (``.summary.*.csv.tmp``, ``.<name>-0007.*.xlsx.tmp``).
Inside ``sigterm_raises()`` the first SIGTERM raises ``Terminated`` in the main thread
instead: the code unwinds through its ``finally`` and ``except BaseException`` blocks
(temporary files removed, worker processes ended) and the command line exits 143
(128 + 15, the shells' code for a SIGTERM'd process).  A second SIGTERM ends the
process at once, as usual.  Processes forked meanwhile (local workers) keep the
default: they end at once, and the command that forked them deals with it.
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading

EXIT_CODE = 128 + signal.SIGTERM


class Terminated(BaseException):
    """SIGTERM arrived (a BaseException, as KeyboardInterrupt: not an error to handle)."""


_requested = False


def check() -> None:
    """Raise ``Terminated`` if SIGTERM arrived: a long loop calls this between steps, in
    case the handler's exception was raised inside a ``__del__`` or a callback, where
    Python prints it and goes on."""
    if _requested:
        raise Terminated()


@contextlib.contextmanager
def sigterm_raises():
    """SIGTERM raises ``Terminated`` while inside (in the main thread only)."""
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
        raise Terminated()

    global _requested
    _requested = False
    previous = signal.signal(signal.SIGTERM, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)
        _requested = False
