"""Date and time (Excel's category): serial-number dates and times (:mod:`.core`), week numbers
(:mod:`.weeks`), working days with a chosen weekend (:mod:`.workdays`).

Every function registered here has the family ``date``: the registry takes it
from this package (:func:`..registry.family_of`)."""

from __future__ import annotations

from workbook_gen.formula.functions.date import (  # noqa: F401  (each module registers)
    core, weeks, workdays,
)
