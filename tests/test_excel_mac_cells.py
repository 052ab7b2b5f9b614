"""Excel's rules where LibreOffice's differ, on the cells of the corpus's
formulas__test.xlsx (saved by Mac Excel 16): each cell below must be recomputed and agree
with Excel's cached value. (The LibreOffice side of each rule is in
test_functions_libreoffice.py, against LibreOffice itself.)"""

from __future__ import annotations

import pytest

CORPUS = "formulas__test.xlsx"
CELLS = {
    # an Analysis ToolPak function takes no boolean: #VALUE!
    "'MATH & TRIG'!Y31": "FACTDOUBLE(TRUE)",
    "'MATH & TRIG'!Y45": "MROUND(TRUE,0)",
    "'MATH & TRIG'!Y70": "SQRTPI(TRUE)",
    "FINANCIAL!Y13": "CUMIPMT(TRUE,5.5,125000,3,5,1)",
    # FACTDOUBLE: -1 is the empty product, below -1 #NUM!
    "'MATH & TRIG'!V31": "FACTDOUBLE(-1) = 1",
    "'MATH & TRIG'!T31": "FACTDOUBLE(-1.1) = #NUM!",
    # ARABIC read from the right, subtracting a numeral below the largest seen
    "'MATH & TRIG'!T9": 'ARABIC("IIIIIIV") = -1',
    "'MATH & TRIG'!V9": 'ARABIC("IILmIIC") = 1046',
    "'MATH & TRIG'!AJ9": "the same in an array formula",
    # ADDRESS with an empty sheet name writes its "!"
    "LOOKUP!S3": 'ADDRESS(1.1,3,4,4.1,<empty cell>) = "!C1"',
    "LOOKUP!AI3": "the same in an array formula",
    # IMSUM and IMPRODUCT of "i" and "j" numbers: #VALUE! (IMSUB: #NUM!)
    "ENGINEERING!S52": "IMSUM(D52:E52,F52)",
    "ENGINEERING!T44": "IMPRODUCT(F44,E44)",
    "ENGINEERING!T51": "IMSUB(E51,F51) = #NUM!",
    # AND/OR/XOR: a text argument's #VALUE! gives way to a later error value
    "LOGICAL!AP3": 'AND(TRUE,"0",#REF!) = #REF!',
    "LOGICAL!AS3": 'AND(TRUE,"ciao",#REF!,"0") = #REF!',
    "LOGICAL!AP21": 'OR(TRUE,"0",#REF!) = #REF!',
    "LOGICAL!AP27": 'XOR(TRUE,"0",#REF!) = #REF!',
    # ROW and COLUMN of an empty intersection: its #NULL!
    "LOOKUP!AG13": "COLUMN(C12:E13 F12:H13) = #NULL!",
    "LOOKUP!AG113": "ROW(C112:E113 F112:H113) = #NULL!",
}


@pytest.fixture(scope="module")
def report(corpus_audits):
    return corpus_audits[CORPUS].report


@pytest.mark.parametrize("cell", list(CELLS), ids=list(CELLS.values()))
def test_cell_agrees_with_mac_excel(report, cell):
    assert cell not in report.not_checked
    assert cell not in {m.cell for m in report.mismatches}
