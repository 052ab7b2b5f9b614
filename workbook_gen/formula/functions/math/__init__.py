"""Math and trigonometry (Excel's category): arithmetic, rounding, logarithms, trigonometry,
products (:mod:`.core`), SUMIF and SUMIFS (:mod:`.conditional`), the reciprocal
trigonometric functions (:mod:`.reciprocal`), numerals in other scripts and radixes
(:mod:`.numerals`), MULTINOMIAL, SERIESSUM and SEQUENCE (:mod:`.series`), matrices and
paired sums, SUMPRODUCT (:mod:`.matrix`), SUBTOTAL and AGGREGATE (:mod:`.subtotal`),
RANDARRAY (:mod:`.randarray`), PERCENTOF (:mod:`.percentof`).

Every function registered here has the family ``math``: the registry takes it
from this package (:func:`..registry.family_of`)."""

from __future__ import annotations

from workbook_gen.formula.functions.math import (  # noqa: F401  (each module registers)
    core, conditional, reciprocal, numerals, series, matrix, randarray, subtotal, percentof,
)
