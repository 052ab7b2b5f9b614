"""Engineering (Excel's category): CONVERT and its unit table (:mod:`.convert`), numbers
in bases 2, 8, 16 and their bits (:mod:`.bases`), ERF, ERFC, DELTA, GESTEP
(:mod:`.special`), Bessel functions (:mod:`.bessel`), complex numbers (:mod:`.complex`).

Every function registered here has the family ``engineering``: the registry takes it
from this package (:func:`..registry.family_of`)."""

from __future__ import annotations

from workbook_gen.formula.functions.engineering import (  # noqa: F401  (each module registers)
    convert, bases, special, bessel, complex,
)
