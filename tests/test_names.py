"""One legal-name rule for the writer and the auditor, checked on Microsoft's own examples.

Sources: MS-XLSB 2.5.166 XLNameWideString (the grammar, "MUST NOT begin with an R1C1 cell
reference"), support.microsoft.com "Names in formulas" (syntax rules: Sales_Tax,
First.Quarter, Z$100, R1C1, and C, c, R, r reserved), KB 111393 "Some names are reserved"
(C, R, RC, R1C1, A1, AB2, DF24, 1A, 22Name), ECMA-376 18.17 limits (LOG10 is a cell
reference, LOGO1000 can be a name).
"""

from __future__ import annotations

import openpyxl
import pytest
from openpyxl.workbook.defined_name import DefinedName

from workbook_gen import audit
from workbook_gen.errors import IllegalNameError
from workbook_gen.names import check_name, excel_name_problem, name_problem

REFUSED = [
    "C", "c", "R", "r", "RC", "R1C1",                 # KB 111393, "Names in formulas"
    "A1", "AB2", "DF24", "Z100", "XFD1048576",        # KB 111393; the last cell of a sheet
    "LOG10",                                          # ECMA-376: always a cell reference
    "1A", "22Name",                                   # KB 111393: begins with a number
    "Sales Tax",                                      # "spaces are not valid"
    "TRUE", "false",                                  # MS-XLSB: not TRUE or FALSE
    "C1_FOO", "R2D2", "r12abc", "C16384x",            # MS-XLSB: begins with an R1C1 reference
    "x" * 256,                                        # at most 255 characters
    "",
]
EXCEL_ACCEPTS = [
    "Sales_Tax", "First.Quarter",                     # "Names in formulas"
    "LOGO1000", "XFE1", "A1048577",                   # outside A1..XFD1048576
    "B1_FOO", "Rate", "Cost_R1", "R0x",               # not beginning with R<n> or C<n>
    "_x", "\\name", "Why?", "Größe", "x" * 255,       # MS-XLSB name characters
]


@pytest.mark.parametrize("name", REFUSED)
def test_excel_refuses_what_microsoft_lists(name):
    assert excel_name_problem(name) is not None
    assert name_problem(name) is not None
    with pytest.raises(IllegalNameError):
        check_name(name, "scene.toml: parameters")


@pytest.mark.parametrize("name", EXCEL_ACCEPTS)
def test_excel_accepts_what_the_grammar_allows(name):
    assert excel_name_problem(name) is None


def test_the_writer_keeps_to_ascii_names_excel_accepts():
    assert [n for n in EXCEL_ACCEPTS if name_problem(n) is None] == [
        "Sales_Tax", "First.Quarter", "LOGO1000", "XFE1", "A1048577", "B1_FOO", "Rate",
        "Cost_R1", "R0x", "_x", "x" * 255]


def test_the_auditor_flags_a_name_beginning_with_an_r1c1_reference(tmp_path):
    book = openpyxl.Workbook()
    sheet = book.active
    sheet["A1"] = 2.0
    sheet["B1"] = "=A1*3"
    for name in ("C1_FOO", "B1_FOO"):
        book.defined_names[name] = DefinedName(name, attr_text="Sheet!$A$1")
    path = tmp_path / "names.xlsx"
    book.save(path)
    flagged = [f.cell for f in audit(path).findings if f.kind == "illegal_name"]
    assert flagged == ["C1_FOO"]
