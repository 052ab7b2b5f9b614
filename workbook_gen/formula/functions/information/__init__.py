"""Information (Excel's category): IS* tests, N, T, TYPE, CELL ... (:mod:`.core`), SHEET
and SHEETS (:mod:`.sheets`).

Every function registered here has the family ``information``: the registry takes it
from this package (:func:`..registry.family_of`)."""

from __future__ import annotations

from workbook_gen.formula.functions.information import (  # noqa: F401  (each module registers)
    core, sheets,
)
