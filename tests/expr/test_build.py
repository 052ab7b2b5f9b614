"""expr/build.py: every builder makes the Excel call its name says, with Excel's argument
order (ATAN2 takes x first): each tree, printed as Excel text, is parsed and evaluated by
the formula evaluator (Excel's semantics, written without the trees) and gives what
Python's math gives for the function at random arguments."""

from __future__ import annotations

import math
import random

import pytest

from workbook_gen.expr import Var
from workbook_gen.expr import build as b
from workbook_gen.expr.excel import to_excel
from workbook_gen.formula import DictResolver, evaluate, parse

RNG = random.Random(23)
X, Y, Z = Var("x"), Var("y"), Var("z")
CELLS = {"x": "A1", "y": "B1", "z": "C1"}


def excel(tree, x, y=0.0, z=0.0):
    text = to_excel(tree, CELLS.__getitem__)
    return evaluate(parse(text), DictResolver({"A1": x, "B1": y, "C1": z}))


CASES = [
    (b.sin(X), lambda x: math.sin(x)), (b.cos(X), lambda x: math.cos(x)),
    (b.tan(X), lambda x: math.tan(x)),
    (b.asin(X), lambda x: math.asin(x)), (b.acos(X), lambda x: math.acos(x)),
    (b.atan(X), lambda x: math.atan(x)),
    (b.sqrt(X), lambda x: math.sqrt(abs(x))), (b.abs_(X), lambda x: abs(x)), (b.sign(X), lambda x: (x > 0) - (x < 0)),
    (b.radians(X), lambda x: math.radians(x)), (b.degrees(X), lambda x: math.degrees(x)),
    (b.root(X), lambda x: math.sqrt(abs(x))), (b.mod(X, Y), lambda x, y: x - y * math.floor(x / y)),
    (b.power(X, Y), lambda x, y: math.pow(x, y)), (b.atan2(X, Y), lambda x, y: math.atan2(y, x)),
    (b.min_(X, Y, Z), lambda x, y, z: min(x, y, z)),
    (b.max_(X, Y, Z), lambda x, y, z: max(x, y, z)),
    (b.if_(b.gt(X, Y), X, Y), lambda x, y: x if x > y else y),
    (b.if_(b.le(X, Y), 1, 0), lambda x, y: float(x <= y)),
    (b.and_(b.lt(X, Y), b.ge(Y, Z)), lambda x, y, z: x < y and y >= z),
    (b.or_(b.eq(X, Y), b.ne(Y, Z)), lambda x, y, z: x == y or y != z),
    (b.not_(b.gt(X, 0)), lambda x: not x > 0),
    (b.iferror(b.sqrt(X), -1), lambda x: math.sqrt(x) if x >= 0 else -1.0),
    (b.iserror(b.sqrt(X)), lambda x: x < 0),
]


@pytest.mark.parametrize("index", range(len(CASES)))
def test_each_builder_is_its_excel_function(index):
    tree, fn = CASES[index]
    arity = fn.__code__.co_argcount
    text = to_excel(tree, str)
    for _ in range(30):
        args = [round(RNG.uniform(0.05, 0.95) if text.startswith(("=ASIN", "=ACOS"))
                      else RNG.uniform(-3, 3), 3) for _ in range(3)]
        if text.startswith(("=SQRT", "=x^0.5")):
            args[0] = abs(args[0])                  # (the domain errors: test_xlmath.py)
        if text.startswith("=POWER"):
            args[0] = abs(args[0]) + 0.1
        want = fn(*args[:arity])
        got = excel(tree, *args)
        assert got == pytest.approx(want, rel=1e-14, abs=1e-15), (to_excel(tree, str), args)


def test_pi_concat_and_text():
    assert excel(b.pi(), 0.0) == math.pi
    assert excel(b.concat("a", X), 2.0) == "a2"
    assert to_excel(b.if_(b.gt(X, 1), "a", "b"), str) == '=IF(x>1,"a","b")'
