"""formula/functions/math/reciprocal.py: COT, CSC, SEC, COTH, CSCH, SECH, ACOT and ACOTH
against mpmath at 50 digits, Microsoft's documented examples (support.microsoft.com: "COT
function", "CSC function", "SEC function", "COTH function", "CSCH function", "SECH
function", "ACOT function", "ACOTH function"), their documented limits (|x| < 2^27 for
COT, CSC and SEC, else #NUM!; COT(0) #DIV/0!; ACOTH of |x| <= 1 #NUM!) and ranges (ACOT:
0 to pi, where mpmath.acot is -pi/2 to pi/2)."""

from __future__ import annotations

import random

import mpmath
import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

RNG = random.Random(6)

MP = {"COT": mpmath.cot, "CSC": mpmath.csc, "SEC": mpmath.sec, "COTH": mpmath.coth,
      "CSCH": mpmath.csch, "SECH": mpmath.sech, "ACOTH": mpmath.acoth,
      "ACOT": lambda x: mpmath.pi / 2 - mpmath.atan(x)}  # 0 to pi (the page)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


@pytest.mark.parametrize("name", sorted(MP))
def test_against_mpmath(name):
    for _ in range(200):
        x = RNG.uniform(-20, 20)
        if name == "ACOTH" and abs(x) <= 1:
            x = x + (2 if x >= 0 else -2)
        with mpmath.workdps(50):
            want = float(MP[name](mpmath.mpf(x)))
        # the circular ones lose digits near their poles only as the argument's rounding
        assert ev(f"={name}({x!r})") == pytest.approx(want, rel=1e-12), x


@pytest.mark.parametrize("formula, shown", [
    ("COT(30)", -0.156), ("COT(45)", 0.617), ("CSC(15)", 1.538), ("SEC(45)", 1.903),
    ("COTH(2)", 1.037), ("CSCH(1.5)", 0.4696), ("ACOT(2)", 0.4636), ("ACOTH(6)", 0.168236118),
])
def test_microsofts_examples(formula, shown):
    """The pages' results, as shown (rounded to the digits the page prints)."""
    digits = len(repr(shown).split(".")[1])
    assert round(ev("=" + formula), digits) == pytest.approx(shown, abs=10 ** -digits)


def test_sech_of_45_is_5_73e_20():
    assert ev("=SECH(45)") == pytest.approx(5.725037161098787e-20, rel=1e-12)


@pytest.mark.parametrize("name", ["COT", "CSC", "SEC"])
def test_the_2_to_27_limit(name):
    big = 2 ** 27
    assert ev(f"={name}({big})") == ExcelError.NUM
    assert ev(f"={name}(-{big})") == ExcelError.NUM
    assert isinstance(ev(f"={name}({big - 1})"), float)


def test_poles_and_domains():
    assert ev("=COT(0)") == ExcelError.DIV0
    assert ev("=CSC(0)") == ExcelError.DIV0
    assert ev("=COTH(0)") == ExcelError.DIV0
    assert ev("=CSCH(0)") == ExcelError.DIV0
    assert ev("=SEC(0)") == 1.0 and ev("=SECH(0)") == 1.0
    assert ev("=ACOT(0)") == pytest.approx(float(mpmath.pi / 2), rel=1e-15)
    for x in ("1", "-1", "0.5", "0"):
        assert ev(f"=ACOTH({x})") == ExcelError.NUM
    assert ev('=COT("a")') == ExcelError.VALUE
