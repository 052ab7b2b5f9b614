"""Formulas as Excel stores them in a file: functions newer than the standard (ECMA-376
Part 1, 18.17.7) carry the ``_xlfn.`` prefix, else Excel and LibreOffice read #NAME?.

The names are availability.FUTURE, the evaluator's one list of them; a name missing there
makes LibreOffice answer #NAME? in the tests that write files with ``stored``."""

from __future__ import annotations

import re

from workbook_gen.formula.functions.availability import FUTURE

_NAMES = sorted((n for n in FUTURE if not n.startswith("_")), key=len, reverse=True)
_FUTURE = re.compile(r"(?<![A-Z0-9._])(" + "|".join(map(re.escape, _NAMES)) + r")\(")


def stored(formula: str) -> str:
    """``formula`` with the ``_xlfn.`` prefix on each future function it calls."""
    return _FUTURE.sub(lambda m: "_xlfn." + m.group(1) + "(", formula)
