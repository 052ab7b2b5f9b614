"""LENB, LEFTB, RIGHTB, MIDB, FINDB, SEARCHB, REPLACEB: the byte-counting forms of the text
functions. Microsoft: they count 2 bytes per character only when a double-byte language
(Japanese, Chinese, Korean) is Excel's default editing language; otherwise they behave as
LEN, LEFT... do. That is the setting assumed here (formulas test.xlsx, saved by an
English Excel, agrees); a workbook computed under a double-byte default would disagree."""

from __future__ import annotations

import dataclasses

from workbook_gen.formula.functions import text  # noqa: F401  (registers LEN, LEFT...)
from workbook_gen.formula.functions.registry import REGISTRY

for _name in ("LEN", "LEFT", "RIGHT", "MID", "FIND", "SEARCH", "REPLACE"):
    REGISTRY[_name + "B"] = dataclasses.replace(REGISTRY[_name], name=_name + "B")
