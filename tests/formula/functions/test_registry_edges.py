"""Excel's edge values, read from Excel-saved corpus workbooks: each file's formula cells
that call the named functions, recomputed from the file's own inputs, give the values
Excel cached (issue 20, items 6 and 7: PRICE/YIELD and the odd-period bonds in the
actual/360 and actual/365 bases, ...)."""

from __future__ import annotations

import math
import os
import re

import pytest

from workbook_gen.auditor.inputs import read_inputs
from workbook_gen.evaluator import evaluate_cells

CORPUS = "/work/shared/corpus/xlsx/"

# (file, the functions whose cells are compared, at least this many cells[, only these])
CASES = [
    ("ironcalc__PRICE_YIELD.xlsx", ("PRICE", "YIELD", "ODDFPRICE", "ODDFYIELD", "ODDLPRICE",
                                    "ODDLYIELD"), 120),
    ("ironcalc__DAYS_DAYS360.xlsx", ("DAYS360",), 40),
    ("ironcalc__PMT.xlsx", ("PMT", "PV", "FV", "NPER"), 200),
    ("ironcalc__MMULT.xlsx", ("MMULT",), 20),
    ("ironcalc__link_test.xlsx", ("HYPERLINK",), 1),
    ("formulas__test.xlsx", ("CHISQ.TEST", "CHITEST", "BETA.INV", "BETAINV"), 20),
    ("formulas__test.xlsx", ("PPMT", "IPMT"), 20),
    ("sheetjs__formula_stress_test.xlsx", ("PPMT", "IPMT"), 2),
    # XLOOKUP mapped over its lookup value and modes, its arrays whole; a mode rounded down
    ("formulas__test.xlsx", ("XLOOKUP", "XMATCH"), 200),
    # XNPV's rate: FINANCIAL!S56:Z56 (its array formulas and its XNPV at the XIRR of R54,
    # whose last digits are Excel's iteration's, left out)
    ("formulas__test.xlsx", ("XNPV",), 8, [("FINANCIAL", 56, col) for col in range(19, 27)]),
    # an array of one maps as any array: INDEX({2,3;4,5},{1}) fills LOOKUP!AN54:AO54 with 2
    ("formulas__test.xlsx", ("INDEX",), 2, [("LOOKUP", 54, 40), ("LOOKUP", 54, 41)]),
    ("ironcalc__COMPLEXs.xlsx", ("IMCOT", "IMCSC", "IMTAN", "IMSEC"), 60),
]


def same(a, b, tol=1e-9) -> bool:
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return math.isclose(a, b, rel_tol=tol, abs_tol=1e-12)
    return a == b


def _calls(formula: str, names) -> bool:
    text = formula.upper().replace("_XLFN.", "")
    return any(re.search(rf"(?<![\w.]){re.escape(n)}\(", text) for n in names)


@pytest.mark.parametrize("case", CASES, ids=[f"{c[0]}-{c[1][0]}" for c in CASES])
def test_excel_cached_values(case):
    name, functions, least, *only = case
    path = CORPUS + name
    if not os.path.isfile(path):
        pytest.fail(f"the corpus is missing: {path}")
    inputs = read_inputs(path)
    result = evaluate_cells(inputs.formulas, inputs.constants, inputs.book.defined_names,
                            dialect="excel", book=inputs.book_info(), arrays=inputs.arrays)
    cells = dict(inputs.formulas)
    for (sheet, r0, c0), (formula, (r1, c1)) in inputs.arrays.items():  # array formulas
        cells.update({(sheet, r, col): formula for r in range(r0, r1 + 1)
                      for col in range(c0, c1 + 1)})
    wrong, checked = [], 0
    for key, formula in cells.items():
        if not _calls(formula, functions) or key not in inputs.cached:
            continue
        if only and key not in only[0]:
            continue
        checked += 1
        tol = 1e-8 if "YIELD(" in formula.upper() else 1e-9  # Excel's iterations stop early
        if not same(inputs.cached[key], result.values[key], tol):
            wrong.append(f"{key} ={formula}: Excel {inputs.cached[key]!r}, "
                         f"ours {result.values[key]!r}")
    assert not wrong, "\n".join(wrong)
    assert checked >= least, checked


def test_xnpv_sums_in_order_as_excel():
    """XNPV at the rate Excel cached for XIRR (sheetjs formula_stress_test.xlsx Finance!B11)
    gives the XNPV Excel cached (B12) to the last bit: the terms summed in order, whose
    cancellation leaves -6.2E-06 of terms near 1E+04."""
    from workbook_gen.formula import DictResolver, evaluate, parse
    path = CORPUS + "sheetjs__formula_stress_test.xlsx"
    if not os.path.isfile(path):
        pytest.fail(f"the corpus is missing: {path}")
    inputs = read_inputs(path)
    assert inputs.formulas[("Finance", 12, 2)] == "XNPV(B11,E10:H10,E11:H11)"
    values = {f"{col}{r}": inputs.constants[("Finance", r, c)]
              for r in (10, 11) for col, c in zip("EFGH", range(5, 9))}
    values["B11"] = inputs.cached[("Finance", 11, 2)]
    got = evaluate(parse("=XNPV(B11,E10:H10,E11:H11)"), DictResolver(values), dialect="excel")
    assert got == inputs.cached[("Finance", 12, 2)], got


# Microsoft's function pages: SORT's sort_index and sort_order are optional (1 and
# ascending when omitted, also between commas); a lookup over an error for its array
# gives that error (#REF!: a deleted range), not "not found"
DOCUMENTED = [
    ("INDEX(SORT({3;1;2},,-1),1)", 3.0), ("INDEX(SORT({3;1;2},,-1),3)", 1.0),
    ("INDEX(SORT({3,1;1,5;2,0},,),1,1)", 1.0), ("INDEX(SORTBY({3;1;2},{3;1;2},),3)", 3.0),
    ("XLOOKUP(1,#REF!,{1})", "#REF!"), ("XLOOKUP(1,{1,2},#REF!)", "#REF!"),
    ("XMATCH(1,#REF!)", "#REF!"), ("MATCH(1,#REF!,0)", "#REF!"), ("LOOKUP(1,#REF!)", "#REF!"),
]


@pytest.mark.parametrize("formula,expected", DOCUMENTED, ids=[d[0] for d in DOCUMENTED])
def test_documented_defaults_and_errors(formula, expected):
    from workbook_gen.formula import DictResolver, evaluate, parse
    got = evaluate(parse("=" + formula), DictResolver({}), dialect="excel")
    assert (got.value if hasattr(got, "value") and isinstance(expected, str) else got) == expected
