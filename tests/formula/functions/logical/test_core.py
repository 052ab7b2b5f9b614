"""formula/functions/logical.py: AND, OR, XOR, NOT against Python's all/any/parity over
every combination of up to four truth values given as booleans, numbers and references
holding text (skipped, as Microsoft documents); IF's laziness, IFS and SWITCH choosing the
first match; IFERROR/IFNA catching what they should."""

from __future__ import annotations

import itertools

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError


def ev(text: str, data=None):
    return evaluate(parse(text), DictResolver(data or {}))


SPELLINGS = {True: ["TRUE", "1", "-2.5"], False: ["FALSE", "0"]}


@pytest.mark.parametrize("n", [1, 2, 3, 4])
def test_and_or_xor_not_truth_tables(n):
    for values in itertools.product([True, False], repeat=n):
        for k in range(2):
            args = ",".join(SPELLINGS[v][k % len(SPELLINGS[v])] for v in values)
            assert ev(f"=AND({args})") is all(values)
            assert ev(f"=OR({args})") is any(values)
            assert ev(f"=XOR({args})") is (sum(values) % 2 == 1)
        assert ev(f"=NOT({SPELLINGS[values[0]][0]})") is (not values[0])


def test_text_in_references_is_skipped_and_alone_is_value():
    data = {"A1": True, "A2": "text", "A3": None, "A4": False}
    assert ev("=AND(A1:A3)", data) is True and ev("=OR(A2:A4)", data) is False
    assert ev("=AND(A2:A3)", data) == ExcelError.VALUE          # nothing logical in it
    assert ev('=AND("TRUE",TRUE)') is True                        # text typed in: read
    assert ev('=AND("x",TRUE)') == ExcelError.VALUE
    assert ev("=AND(1/0,TRUE)") == ExcelError.DIV0


def test_choosers():
    assert ev("=IF(TRUE,1,1/0)") == 1 and ev("=IF(FALSE,1/0,2)") == 2     # lazy
    assert ev("=IF(FALSE,1)") is False
    assert ev("=IFS(FALSE,1,1>2,2,TRUE,3)") == 3
    assert ev("=IFS(FALSE,1)") == ExcelError.NA
    assert ev('=SWITCH(2,1,"a",2,"b","c")') == "b"
    assert ev('=SWITCH(9,1,"a",2,"b","c")') == "c"
    assert ev('=SWITCH(9,1,"a")') == ExcelError.NA
    assert ev("=IFERROR(1/0,7)") == 7 and ev("=IFERROR(5,7)") == 5
    assert ev("=IFNA(NA(),7)") == 7 and ev("=IFNA(1/0,7)") == ExcelError.DIV0
