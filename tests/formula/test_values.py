"""formula/values.py: number-to-text keeps Excel's 15 significant digits (the text reads
back as Python's ``%.15g`` of the number) in Excel's forms; text-to-number reads what
Excel's VALUE reads; comparisons follow Excel's documented order (numbers < text <
FALSE < TRUE, text case-insensitive, an empty operand as the other's type)."""

from __future__ import annotations

import functools
import random

import pytest

from workbook_gen.formula.values import compare, number_to_text, text_to_number, to_bool
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)


def numbers():
    yield from [0.1 + 0.2, 1 / 3, 1e-5, 1e-19, 123456789012345678.0, 1e21, -2.5e-8, 100.0,
                0.5, -7.0, 1e15, 1e16 + 2, 2.0 ** 70, 9.99999999999999e-6]
    for _ in range(2000):
        yield RNG.choice([-1, 1]) * RNG.uniform(1, 10) * 10.0 ** RNG.randint(-25, 25)


def test_number_to_text_keeps_15_digits_in_excels_forms():
    for x in numbers():
        text = number_to_text(x)
        assert float(text) == float(f"{x:.15g}"), (x, text)
        assert not text.endswith(".0") and "e" not in text and text.count(".") <= 1
        if "E" in text:   # 1.23456789012346E+20: one digit, the point, up to 14, E, sign, 2+
            mantissa, exponent = text.lstrip("-").split("E")
            assert mantissa[0] != "0" and len(mantissa.replace(".", "")) <= 15
            assert exponent[0] in "+-" and len(exponent) >= 3
            assert abs(x) >= 1e20 or len(f"{abs(float(f'{x:.15g}')):.30f}".rstrip("0")) > 20
        else:
            assert len(text.lstrip("-").replace(".", "").lstrip("0")) <= 20


def test_number_to_text_of_special_values():
    assert number_to_text(0.0) == "0" and number_to_text(-0.0) == "0"
    assert number_to_text(5e-324) == "0"                    # a denormal shows as 0
    assert number_to_text(1e-5) == "0.00001"                # POI: SEARCH(1, 0.00001) is 7
    assert number_to_text(123456789012345678.0) == "123456789012346000"
    assert number_to_text(1e21) == "1E+21"


@pytest.mark.parametrize("text, value", [("1e3", 1000.0), (" 12 ", 12.0), ("1,000", 1000.0),
                                         ("$1,000", 1000.0), ("50%", 0.5), ("-0.25", -0.25),
                                         ("2020-01-01", 43831.0), ("abc", ExcelError.VALUE),
                                         ("TRUE", ExcelError.VALUE), ("", ExcelError.VALUE)])
def test_text_to_number_as_value_reads_it(text, value):
    assert text_to_number(text) == value


def test_excels_comparison_order():
    values = [True, "b", 2.0, False, "A", -1.0, "a", "", 0.0]
    order = sorted(values, key=functools.cmp_to_key(compare))
    assert order == [-1.0, 0.0, 2.0, "", "A", "a", "b", False, True]
    assert compare("A", "a") == 0                  # ="A"="a" is TRUE
    assert compare(None, 0.0) == 0 and compare(None, "") == 0 and compare(None, False) == 0
    assert compare(None, -1.0) == 1 and compare("x", None) == 1
    assert compare(ExcelError.NA, 1.0) is ExcelError.NA
    assert compare(1.0, ExcelError.DIV0) is ExcelError.DIV0


def test_to_bool():
    assert to_bool(2.0) is True and to_bool(0.0) is False
    assert to_bool("true") is True and to_bool(" FALSE ") is False
    assert to_bool("yes") is ExcelError.VALUE
