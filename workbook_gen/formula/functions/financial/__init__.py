"""Financial (Excel's category): annuities and cash flows (:mod:`.core`), depreciation
(:mod:`.depreciation`), securities (:mod:`.bonds`, :mod:`.oddbonds`) on the day-count bases
of :mod:`.daycount`.

Every function registered here has the family ``financial``: the registry takes it
from this package (:func:`..registry.family_of`)."""

from __future__ import annotations

from workbook_gen.formula.functions.financial import (  # noqa: F401  (each module registers)
    core, depreciation, bonds, oddbonds,
)
