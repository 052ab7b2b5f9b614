"""formula/functions/info.py: the IS* functions, TYPE, N, T and ERROR.TYPE over every kind
of value (number, text, boolean, each error, empty), against Microsoft's tables:
TYPE 1/2/4/16/64, ERROR.TYPE 1..8 for #NULL! .. #GETTING_DATA, ISEVEN/ISODD truncating."""

from __future__ import annotations

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

ERRORS = ["#NULL!", "#DIV/0!", "#VALUE!", "#REF!", "#NAME?", "#NUM!", "#N/A"]
CELLS = {"A1": 3.5, "A2": "text", "A3": True, "A4": None, "A5": ExcelError.NA,
         "A6": ExcelError.DIV0, "A7": ""}
# cell -> (ISNUMBER, ISTEXT, ISLOGICAL, ISBLANK, ISERROR, ISERR, ISNA, ISNONTEXT, TYPE)
KINDS = {
    "A1": (True, False, False, False, False, False, False, True, 1),
    "A2": (False, True, False, False, False, False, False, False, 2),
    "A3": (False, False, True, False, False, False, False, True, 4),
    "A4": (False, False, False, True, False, False, False, True, 1),
    "A5": (False, False, False, False, True, False, True, True, 16),
    "A6": (False, False, False, False, True, True, False, True, 16),
    "A7": (False, True, False, False, False, False, False, False, 2),
}


def ev(text: str):
    return evaluate(parse(text), DictResolver(CELLS))


@pytest.mark.parametrize("cell", sorted(KINDS))
def test_is_functions_and_type(cell):
    names = ["ISNUMBER", "ISTEXT", "ISLOGICAL", "ISBLANK", "ISERROR", "ISERR", "ISNA",
             "ISNONTEXT"]
    got = tuple(ev(f"={name}({cell})") for name in names) + (ev(f"=TYPE({cell})"),)
    assert got == KINDS[cell]


def test_type_of_an_array_n_and_t():
    assert ev("=TYPE({1,2})") == 64
    assert ev("=N(A1)") == 3.5 and ev("=N(A2)") == 0 and ev("=N(A3)") == 1
    assert ev("=N(A5)") == ExcelError.NA
    assert ev("=T(A2)") == "text" and ev("=T(A1)") == "" and ev("=T(A5)") == ExcelError.NA


def test_error_type_numbers():
    for number, text in enumerate(ERRORS, 1):
        assert ev(f"=ERROR.TYPE({text})") == number
    assert ev("=ERROR.TYPE(1)") == ExcelError.NA


@pytest.mark.parametrize("x", [-3.7, -2.0, -1.2, 0.0, 0.9, 1.0, 2.5, 3.99, 1e9 + 1])
def test_iseven_isodd_truncate(x):
    whole = int(x)   # towards zero
    assert ev(f"=ISEVEN({x!r})") is (whole % 2 == 0)
    assert ev(f"=ISODD({x!r})") is (whole % 2 == 1)
