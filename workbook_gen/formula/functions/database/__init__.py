"""Database (Excel's category): the D* functions over a table and criteria (:mod:`.core`).

Every function registered here has the family ``database``: the registry takes it
from this package (:func:`..registry.family_of`)."""

from __future__ import annotations

from workbook_gen.formula.functions.database import (  # noqa: F401  (each module registers)
    core,
)
