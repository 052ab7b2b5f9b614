"""Lookup and reference (Excel's category): INDEX, MATCH, VLOOKUP ... (:mod:`.core`), XLOOKUP
and XMATCH (:mod:`.xlookup`), references themselves (:mod:`.reference`), the dynamic-array
functions that shape (:mod:`.shape`) and select (:mod:`.arrayops`), the spill operators
(:mod:`.spill`), RTD (:mod:`.rtd`), TRIMRANGE and the trim references (:mod:`.trimrange`),
GROUPBY and PIVOTBY (:mod:`.groupby`, their axes :mod:`.pivot`).

Every function registered here has the family ``lookup``: the registry takes it
from this package (:func:`..registry.family_of`)."""

from __future__ import annotations

from workbook_gen.formula.functions.lookup import (  # noqa: F401  (each module registers)
    core, xlookup, reference, shape, arrayops, spill, rtd, trimrange, groupby,
)
