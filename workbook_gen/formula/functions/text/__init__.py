"""Text (Excel's category): :mod:`.core`, the byte-counting forms (:mod:`.textbytes`),
regular expressions (:mod:`.regex`), the Excel 365 functions that split text into arrays
and write arrays as text (:mod:`.arrays`), BAHTTEXT (:mod:`.bahttext`).

Every function registered here has the family ``text``: the registry takes it
from this package (:func:`..registry.family_of`)."""

from __future__ import annotations

from workbook_gen.formula.functions.text import (  # noqa: F401  (each module registers)
    core, textbytes, regex, arrays, bahttext,
)
