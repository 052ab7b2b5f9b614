"""formula/functions/arrayargs.py by hand-derived cases and Excel's documented rules: an
omitted argument takes its default, an empty cell is 0 and a number is truncated
(SEQUENCE, TAKE, CHOOSEROWS...: "whole number" arguments), a text argument is coerced as
Excel coerces text to a number ("2" is 2, "x" is #VALUE!); an array result with no cells
is #CALC! (support.microsoft.com, "How to correct a #CALC! error": Excel cannot return an
empty array)."""

from __future__ import annotations

import pytest

from workbook_gen.formula.functions import arrayargs as aa
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError


def test_as_grid():
    assert aa.as_grid(3.0) == [[3.0]]
    assert aa.as_grid("a") == [["a"]]
    assert aa.as_grid(ExcelError.NA) is ExcelError.NA
    grid = aa.as_grid(Range.of([[1.0, 2.0], [3.0, None]]))
    assert grid == [[1.0, 2.0], [3.0, None]]
    assert all(isinstance(r, list) for r in grid)          # rows a caller may change
    assert aa.as_grid(Range.of([])) is ExcelError.CALC
    assert aa.as_grid(Range.of([[]])) is ExcelError.CALC


def test_array_result():
    r = aa.array_result([[1.0, "x"], [True, None]])
    assert isinstance(r, Range) and r.array and r.ref is None
    assert r.rows == ((1.0, "x"), (True, None))
    assert aa.array_result([]) is ExcelError.CALC
    assert aa.array_result([[]]) is ExcelError.CALC


@pytest.mark.parametrize("value, default, expected", [
    (aa.OMITTED, 7, 7), (aa.OMITTED, None, None),
    (None, 7, 0),                       # an empty cell given: 0, not the default
    (3.9, None, 3), (-3.9, None, -3),   # truncated towards zero
    (True, None, 1), (False, None, 0),
    ("2", None, 2), ("2.7", None, 2), (" 5 ", None, 5),
    ("x", None, ExcelError.VALUE), ("", None, ExcelError.VALUE),
    (ExcelError.REF, None, ExcelError.REF),
])
def test_whole_arg(value, default, expected):
    got = aa.whole_arg(value, default)
    assert got == expected and type(got) is type(expected)


def test_whole_args_stops_at_the_first_error():
    assert aa.whole_args(1, 2, 3) == [1, 2, 3]
    assert aa.whole_args(1, ExcelError.NUM, ExcelError.VALUE) is ExcelError.NUM
    assert aa.whole_args() == []


def test_omitted_is_not_an_empty_cell():
    assert aa.OMITTED is not None and aa.OMITTED != 0
