"""What the audit's own code says while it runs, kept for the report instead of printed.

The output of ``audit`` is its report (docs/audit.md, The report: stdout and stderr hold only the
report), so a Python warning or a log record of ``workbook_gen`` at WARNING or above
raised during an audit is counted in the report's ``warnings`` (message -> times), where
a test can see it, rather than written to stderr by Python's last-resort handler.
Warnings expected by design are silenced where they arise, not here: numpy's
floating-point warnings inside a formula (Excel's #NUM!, ``evaluator.engine``),
openpyxl's about parts it drops (``engines.libreoffice``). Work done in a forked child
(``forked.py``) says nothing either: its warnings stay in the child.
"""

from __future__ import annotations

import logging
import os
import warnings
from contextlib import contextmanager


class _Count(logging.Handler):
    def __init__(self, counts: dict[str, int]):
        super().__init__(logging.WARNING)
        self.counts = counts

    def emit(self, record: logging.LogRecord) -> None:
        key = f"{record.name}: {record.getMessage()}"
        self.counts[key] = self.counts.get(key, 0) + 1


@contextmanager
def caught():
    """``with caught() as said:`` ... ``said`` is {message: times} once the block ends."""
    counts: dict[str, int] = {}
    handler = _Count(counts)
    logger = logging.getLogger("workbook_gen")
    logger.addHandler(handler)  # (a handler found: the last-resort one is not used)
    seen: list = []
    try:
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            yield counts
    finally:
        logger.removeHandler(handler)
        for w in seen:
            key = (f"{w.category.__name__}: {w.message} "
                   f"({os.path.basename(w.filename)}:{w.lineno})")
            counts[key] = counts.get(key, 0) + 1
