"""auditor/caught.py: warnings and workbook_gen's log records raised inside ``caught()``
are counted (message -> times) instead of written to stderr; nothing outside the block,
nothing below WARNING, nothing from another logger's tree."""

from __future__ import annotations

import inspect
import logging
import warnings

from workbook_gen.auditor.caught import caught


def test_warnings_are_counted_by_message_and_place():
    with caught() as said:
        for _ in range(3):
            line = inspect.currentframe().f_lineno + 1
            warnings.warn("drop me", UserWarning)
        warnings.warn("other", RuntimeWarning)
    assert said[f"UserWarning: drop me (test_caught.py:{line})"] == 3
    assert sum(v for k, v in said.items() if k.startswith("RuntimeWarning: other")) == 1
    assert len(said) == 2


def test_log_records_at_warning_and_above_of_workbook_gen_only():
    log = logging.getLogger("workbook_gen.somewhere")
    with caught() as said:
        log.warning("cell %s odd", "A1")
        log.warning("cell %s odd", "A1")
        log.error("bad")
        log.info("not counted")
        logging.getLogger("elsewhere").warning("not ours")
    assert said == {"workbook_gen.somewhere: cell A1 odd": 2, "workbook_gen.somewhere: bad": 1}


def test_nothing_is_written_to_stderr_and_the_handler_leaves(capsys):
    handlers = list(logging.getLogger("workbook_gen").handlers)
    with caught() as said:
        logging.getLogger("workbook_gen").warning("quiet")
        warnings.warn("quiet too")
    assert capsys.readouterr().err == ""
    assert len(said) == 2
    assert logging.getLogger("workbook_gen").handlers == handlers
    # after the block, a warning is Python's again (not counted in the old dict)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        warnings.warn("after")
    assert len(seen) == 1 and len(said) == 2


def test_counts_survive_an_exception_in_the_block():
    said = None
    try:
        with caught() as said:
            warnings.warn("before the failure")
            raise KeyError("x")
    except KeyError:
        pass
    assert sum(said.values()) == 1
