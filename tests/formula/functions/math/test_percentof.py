"""math/percentof.py: PERCENTOF, "logically equivalent to =SUM(data_subset)/SUM(data_all)"
(Microsoft's "PERCENTOF function", support.microsoft.com/en-us/excel/percentof-function),
against fsum over the numbers on random data with SUM's coercion (a range keeps only
numbers), and Microsoft Excel's cached values of formulas__test.xlsx (MATH & TRIG!R49:AW49,
where an error in either argument is #NUM!)."""

from __future__ import annotations

import math
import random
import re
import zipfile

import pytest

from tests.formula.functions import excel_cached as xc
from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula.arrays import evaluate_array
from workbook_gen.xlerror import ExcelError

RNG = random.Random(49)


def ev(text: str, res=None):
    return evaluate_array(parse(text), res or DictResolver({}), "excel", None)


def test_every_percentof_of_formulas_test_agrees_with_excel():
    res = xc.resolver(("MATH & TRIG",), 49, 49)
    values = xc.book()["MATH & TRIG"]
    with zipfile.ZipFile(xc.PATH) as z:
        text = z.read("xl/worksheets/sheet12.xml").decode()
    plain = re.findall(r'<c r="([A-Z]+)49"[^>]*><f>(_xlfn\.PERCENTOF\([^<]*)</f>', text)
    assert len(plain) >= 6
    for cell, formula in plain:
        cached = xc.value(values[f"{cell}49"].value)
        assert xc.same(ev(formula, res), cached), (cell, formula)
    for anchor, ref, formula in xc.array_formulas("sheet12", r"PERCENTOF"):
        xc.assert_spill(formula, ref, "MATH & TRIG", res)


@pytest.mark.parametrize("seed", range(10))
def test_percentof_is_the_sum_of_the_subset_over_the_sum_of_all(seed):
    rng = random.Random(seed)
    cells = {}
    for i in range(1, 13):
        kind = rng.random()
        cells[f"A{i}"] = (float(rng.randint(-50, 50)) / 4 if kind < 0.7 else
                          "txt" if kind < 0.8 else True if kind < 0.9 else None)
    res = DictResolver({k: v for k, v in cells.items() if v is not None})
    a, b = sorted(rng.sample(range(1, 13), 2))
    nums = lambda lo, hi: [cells[f"A{i}"] for i in range(lo, hi + 1)  # noqa: E731
                           if isinstance(cells[f"A{i}"], float)]
    whole = math.fsum(nums(1, 12))
    got = ev(f"PERCENTOF(A{a}:A{b},A1:A12)", res)
    if whole == 0:
        assert got == ExcelError.DIV0
    else:
        assert got == pytest.approx(math.fsum(nums(a, b)) / whole, rel=1e-15)


def test_direct_arguments_convert_as_sums_do():
    assert ev('PERCENTOF(1,4)') == 0.25
    assert ev('PERCENTOF("2",{4,4})') == 0.25
    assert ev('PERCENTOF(TRUE,{2,TRUE,"x"})') == 0.5
    assert ev('PERCENTOF({1,2},{3,-3})') == ExcelError.DIV0
    assert ev('PERCENTOF({1,2},{3,#N/A})') == ExcelError.NUM
