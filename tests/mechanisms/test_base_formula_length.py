"""Every formula short enough to read (issue 22 item 18): the four-bar's h_B factors were
1,420 characters of nested MAX/MIN, the five-bar's clearance errors 800.  Constants of the
linkage are derived values on the Parameters sheet, repeated subexpressions columns of
their own, with the cached values unchanged to the bit (the tests of each template compare
them with 50-digit references)."""

from __future__ import annotations

import glob

import openpyxl
import pytest

# characters.  The longest left: the parallel mechanism's leg closure rates on the Checks
# sheet (502, a dot product of two 3-vectors over a norm) and the actuator's count of 20
# halvings (472, one IF each): regular, each term readable.
LONGEST = 520
TABLE_LONGEST = 330  # a Table formula


def _formulas(path):
    book = openpyxl.load_workbook(path, read_only=True)
    for sheet in book.worksheets:
        for row in sheet.iter_rows(values_only=True):
            for value in row:
                if isinstance(value, str) and value.startswith("="):
                    yield sheet.title, value


@pytest.mark.parametrize("scene", sorted(glob.glob("templates/*.toml")))
def test_every_formula_is_short_enough_to_read(generate, scene):
    path = generate(scene)
    longest = {}
    for sheet, text in _formulas(path):
        longest[sheet] = max(longest.get(sheet, 0), len(text))
    assert max(longest.values()) <= LONGEST, longest
    if "actuator" not in scene:
        assert longest["Table"] <= TABLE_LONGEST, longest
