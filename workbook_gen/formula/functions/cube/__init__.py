"""Cube (Excel's category): answered from the OLAP cache the file keeps (:mod:`.core`).

Every function registered here has the family ``cube``: the registry takes it
from this package (:func:`..registry.family_of`)."""

from __future__ import annotations

from workbook_gen.formula.functions.cube import (  # noqa: F401  (each module registers)
    core,
)
