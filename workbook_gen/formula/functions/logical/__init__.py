"""Logical (Excel's category): IF, AND, ... (:mod:`.core`), LAMBDA, LET and the functions that
call a LAMBDA (:mod:`.lambdas`).

Every function registered here has the family ``logical``: the registry takes it
from this package (:func:`..registry.family_of`)."""

from __future__ import annotations

from workbook_gen.formula.functions.logical import (  # noqa: F401  (each module registers)
    core, lambdas,
)
