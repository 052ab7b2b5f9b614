"""evaluator.ops: operators and functions over blocks of rows. References: Microsoft's
documented operator semantics (calculation operators and precedence:
https://support.microsoft.com/en-us/office/calculation-operators-and-precedence-in-excel-48be406d-4975-4d31-b2b8-7af9e0e2878a
-- numeric text is converted in arithmetic, "&" joins text, comparisons order numbers <
text < logical, text case-insensitively), Python's math for the numbers, and the same
rows taken by the fast path (NumBlock) and the per-element path (ObjBlock) agreeing."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from workbook_gen.evaluator.ops import (Const, as_num, binary, call, choose, clean, items,
                                        to_bool_mask, unary)
from workbook_gen.evaluator.store import NumBlock, ObjBlock
from workbook_gen.xlerror import ExcelError

E = ExcelError
ROW = [3.0, -2.0, 0.0, 0.5, E.NA, True, "4", "a", None, "", False]
N = len(ROW)


def _items(v):
    return items(v, N)


def _cell(op, a, b):
    """Excel's binary operators on two values, written out here from Microsoft's page."""
    if op in "+-*/^":
        return _arith(op, a, b)
    for v in (a, b):
        if isinstance(v, ExcelError):
            return v
    if op == "&":
        def text(v):
            return "" if v is None else ("TRUE" if v is True else "FALSE" if v is False
                                         else v if isinstance(v, str) else f"{v:g}")
        return text(a) + text(b)
    if op in ("=", "<>", "<", ">", "<=", ">="):
        def key(v):  # an empty cell compares as 0 against a number, "" against text
            if v is None:
                other = b if v is a else a
                v = "" if isinstance(other, str) else False if isinstance(other, bool) else 0.0
            if isinstance(v, bool):
                return (2, float(v))
            if isinstance(v, str):
                return (1, v.casefold())
            return (0, v)
        ka, kb = key(a), key(b)
        return {"=": ka == kb, "<>": ka != kb, "<": ka < kb, ">": ka > kb,
                "<=": ka <= kb, ">=": ka >= kb}[op]


def _arith(op, a, b):
    """Left to right: the left operand (its error, or its text not a number: #VALUE!)
    decides before the right one ("a"+NA() is #VALUE!)."""

    def num(v):
        if v is None:
            return 0.0
        if isinstance(v, str):
            try:
                return float(v)
            except ValueError:
                return E.VALUE
        return float(v)
    x = a if isinstance(a, ExcelError) else num(a)
    if isinstance(x, ExcelError):
        return x
    y = b if isinstance(b, ExcelError) else num(b)
    if isinstance(y, ExcelError):
        return y
    if op == "/" and y == 0:
        return E.DIV0
    if op == "^":
        if x == 0 and y == 0:
            return E.NUM
        if x == 0 and y < 0:
            return E.DIV0
        if x < 0 and y != int(y):
            return E.NUM
        try:
            return math.pow(x, y)
        except OverflowError:
            return E.NUM
    return {"+": x + y, "-": x - y, "*": x * y, "/": x / y if y else 0}[op] + 0.0


def _same(a, b):
    if isinstance(a, float) and isinstance(b, float):
        return a == b or math.isclose(a, b, rel_tol=1e-15)
    return type(a) is type(b) and a == b


@pytest.mark.parametrize("op", ["+", "-", "*", "/", "^", "&", "=", "<>", "<", ">", "<=", ">="])
def test_binary_over_every_pair_of_kinds(op):
    pairs = list(itertools.product(ROW, ROW))
    left, right = [p for p, _ in pairs], [q for _, q in pairs]
    n = len(pairs)
    got = items(binary(op, ObjBlock(left), ObjBlock(right), n), n)
    for a, b, g in zip(left, right, got):
        assert _same(g, _cell(op, a, b)), (a, op, b, g)
    # one side constant: the memoised path gives the same
    for const in (2.0, "A", True, E.DIV0):
        got = items(binary(op, Const(const), ObjBlock(ROW), N), N)
        assert all(_same(g, _cell(op, const, b)) for g, b in zip(got, ROW)), (const, op)


NUMS = [3.0, -2.0, 0.0, 0.5, E.NA, 1e308, -7.25, E.DIV0]


@pytest.mark.parametrize("op", ["+", "-", "*", "/", "^", "=", "<", ">="])
def test_the_fast_numeric_path_equals_the_per_element_one(op):
    pairs = list(itertools.product(NUMS, NUMS))
    a, b = ObjBlock([p for p, _ in pairs]), ObjBlock([q for _, q in pairs])
    n = len(pairs)
    fast = binary(op, as_num(a, n), as_num(b, n), n)
    assert isinstance(fast, NumBlock)
    slow = [_cell(op, p, q) for p, q in pairs]
    for g, w, (p, q) in zip(items(fast, n), slow, pairs):
        if isinstance(w, float) and not math.isfinite(w):
            w = E.NUM  # Excel has no infinities: an overflow is #NUM!
        assert _same(g, w), (p, op, q, g, w)


def test_unary_minus_and_percent():
    got = items(unary("-", ObjBlock(ROW), N), N)
    assert got[:4] == [-3.0, 2.0, 0.0, -0.5] and math.copysign(1, got[2]) == 1  # no -0
    assert got[4] == E.NA and got[5] == -1.0 and got[6] == -4.0 and got[7] == E.VALUE
    assert items(unary("%", ObjBlock([50.0, "25", E.REF]), 3), 3) == [0.5, 0.25, E.REF]
    assert unary("-", Const("x"), 2).value == E.VALUE
    assert unary("+", Const("x"), 2).value == "x"  # + leaves its operand as it is


def test_calls_fast_and_per_row():
    # SQRT: #NUM! for negatives (https://support.microsoft.com/en-us/office/sqrt-function-654975c2-05c4-4831-9a24-2c65e4040fdf)
    got = items(call("SQRT", [ObjBlock([4.0, -1.0, E.NA, "9"])], [False], 4), 4)
    assert got == [2.0, E.NUM, E.NA, 3.0]
    # LEN of each row (text functions go per row)
    assert items(call("LEN", [ObjBlock(["abc", 12.0, True, None])], [False], 4), 4) == \
        [3.0, 2.0, 4.0, 0.0]
    assert call("PI", [], [], 3).value == math.pi


def test_if_mask_and_choose():
    pick, err = to_bool_mask(ObjBlock([1.0, 0.0, "TRUE", "no", E.NA, True]), 6)
    assert pick.tolist() == [True, False, True, False, False, True]
    assert err.tolist() == [0, 0, 0, E.VALUE.code, E.NA.code, 0]
    out = items(choose(pick, err, Const("yes"), ObjBlock([1.0] * 6), 6), 6)
    assert out == ["yes", 1.0, "yes", E.VALUE, E.NA, "yes"]
    nums = choose(np.array([True, False]), np.zeros(2, np.uint8),
                  NumBlock(np.array([1.0, 2.0]), np.zeros(2, np.uint8)), Const(9.0), 2)
    assert isinstance(nums, NumBlock) and nums.val.tolist() == [1.0, 9.0]


def test_clean_and_as_num():
    assert clean(math.inf) == E.NUM and math.copysign(1, clean(-0.0)) == 1 and clean("x") == "x"
    assert as_num(ObjBlock(["x", 1.0]), 2) is None
    flags = as_num(ObjBlock([True, False]), 2)
    assert flags.boolean and flags.val.tolist() == [1.0, 0.0]
    assert as_num(Const(E.NA), 2).err.tolist() == [E.NA.code] * 2


@pytest.mark.parametrize("op", ["=", "<>", "<", ">", "<=", ">="])
def test_booleans_against_numbers_on_the_fast_path(op):
    # TRUE/FALSE are above every number (FALSE > 1e308); as NumBlocks both sides
    flags, numbers = [True, False, True], [1.0, 1e308, -5.0]
    a, b = as_num(ObjBlock(flags), 3), as_num(ObjBlock(numbers), 3)
    assert a.boolean and not b.boolean
    assert items(binary(op, a, b, 3), 3) == [_cell(op, p, q) for p, q in zip(flags, numbers)]
    assert items(binary(op, b, a, 3), 3) == [_cell(op, q, p) for p, q in zip(flags, numbers)]
