"""LENB, LEFTB, RIGHTB, MIDB, FINDB, SEARCHB, REPLACEB: the byte-counting forms of the text
functions; ASC (full-width to half-width characters). Microsoft: they count 2 bytes per character only when a double-byte language
(Japanese, Chinese, Korean) is Excel's default editing language; otherwise they behave as
LEN, LEFT... do. That is the setting assumed here (formulas test.xlsx, saved by an
English Excel, agrees); a workbook computed under a double-byte default would disagree."""

from __future__ import annotations

import dataclasses
import unicodedata

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.text import core as text  # noqa: F401  (registers LEN, LEFT...)
from workbook_gen.formula.functions.registry import REGISTRY, register

for _name in ("LEN", "LEFT", "RIGHT", "MID", "FIND", "SEARCH", "REPLACE"):
    REGISTRY[_name + "B"] = dataclasses.replace(REGISTRY[_name], name=_name + "B")


# ASC: full-width (double-byte) characters to half-width ones (Microsoft's ASC page,
# ASC("ＥＸＣＥＬ") is "EXCEL"): the full-width ASCII forms and the katakana, with the voiced
# marks split off as half-width marks (the ideographic space stays, as in LibreOffice: no
# Excel evidence either way). The table is the inverse
# of Unicode's compatibility decomposition of the half-width forms (U+FF61..U+FF9F).
def _half_width_table() -> dict[str, str]:
    table = {chr(0xFF01 + i): chr(0x21 + i) for i in range(0x5E)}
    half = [chr(k) for k in range(0xFF61, 0xFFA0)]
    for h in half:
        full = unicodedata.normalize("NFKC", h)
        if len(full) == 1 and full != h:
            table.setdefault(full, h)
        for mark in ("\uff9e", "\uff9f"):
            composed = unicodedata.normalize("NFKC", h + mark)
            if len(composed) == 1:
                table.setdefault(composed, h + mark)
    return table


_HALF = str.maketrans(_half_width_table())


@register("ASC", 1, 1)
def _asc(ctx, v):
    t = c.to_text(v)
    return t if not isinstance(t, str) else t.translate(_HALF)
