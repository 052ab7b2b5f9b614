"""evaluator.vector: a formula compiled for a block of rows gives, row by row, what the
scalar evaluator (formula.scalar, an independent cell-by-cell path) gives on the same
formula shifted to that row: random formulas over numbers, text, booleans, errors and
empty cells (hypothesis). Excel's implicit intersection (a multi-row range where one
value is expected) and relative ranges are refused, for the cell-by-cell path."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, reject, settings, strategies as st

from workbook_gen.evaluator.ops import Const
from workbook_gen.evaluator.store import Names, NumBlock, SheetResolver, Store, to_items
from workbook_gen.evaluator.tasks import cell_scale
from workbook_gen.evaluator.vector import (Env, NotVectorizable, compile_block, intersects,
                                           row_invariant)
from workbook_gen.formula import ast, parse
from workbook_gen.formula.scalar import Evaluator, evaluate
from workbook_gen.xlerror import ExcelError

FIRST, LAST = 2, 13
A = [None, 3.0, -2.0, 0.0, 0.5, "7", "abc", True, ExcelError.NA, None, 1e10, -0.25, ""]
B = [None, 1.0, 4.0, -3.0, 0.0, 2.0, False, 9.0, 2.5, ExcelError.DIV0, 6.0, "x", 8.0]


@pytest.fixture(scope="module")
def store():
    s = Store(["S"])
    values = {("S", 1, 3): 10.0, ("S", 2, 3): "k"}
    for r in range(FIRST, LAST + 1):
        for col, column in ((1, A), (2, B)):
            if column[r - 1] is not None:
                values[("S", r, col)] = column[r - 1]
    s.put_constants(values)
    return s


NAMES = Names({"Ten": "S!$C$1"})

LEAVES = st.sampled_from(["A2", "B2", "$C$1", "Ten", "2", "0.5", '"t"', "TRUE", "-1",
                          "ROW()", "$C$2"])
UNARY = ["-{}", "{}%", "ABS({})", "SIN({})", "SQRT({})", "LEN({})", "ROUND({},1)",
         "ISNUMBER({})", "NOT({})", "INT({})", "IFERROR({},-9)", "N({})"]
BINARY = ["{}+{}", "{}-{}", "{}*{}", "{}/{}", "{}^{}", "{}&{}", "{}={}", "{}<{}",
          "MAX({},{})", "MIN({},{})", "IF({},{},0)", "IF({}>1,{})", "MOD({},{})",
          "ATAN2({},{})", "SUM({},{})", "AND({},{})"]


def _extend(children):
    return st.one_of(
        st.builds(lambda f, a: f.format(a), st.sampled_from(UNARY), children),
        st.builds(lambda f, a, b: f.format(a, b), st.sampled_from(BINARY), children, children))


FORMULAS = st.recursive(LEAVES, _extend, max_leaves=6)


def _run(node, store, col=4):
    block = compile_block(node, "S", col, FIRST, LAST)
    resolver = SheetResolver(store, NAMES, "S")
    reference = Evaluator(resolver, "excel", None, ("S", FIRST, col))
    reference.ctx.intersect = False
    env = Env(LAST - FIRST + 1, store.block, reference.arg)
    value = block.run(env)
    n = env.n
    if isinstance(value, Const):
        got = [value.value] * n
    elif isinstance(value, NumBlock):
        got = to_items(value)
    else:
        got = value.items
    return got, block.scale(env).tolist()


def _same(a, b):
    if isinstance(a, float) and isinstance(b, float):
        return a == b or (math.isnan(a) and math.isnan(b))
    return type(a) is type(b) and a == b


@settings(max_examples=300, deadline=None)
@given(text=FORMULAS)
def test_each_row_is_what_the_scalar_evaluator_gives(text, store):
    node = parse(text)
    try:
        got, scales = _run(node, store)
    except NotVectorizable:   # evaluated cell by cell instead (evaluate_task), e.g. N(IF(..))
        reject()
    resolver = SheetResolver(store, NAMES, "S")
    for i, (g, scale) in enumerate(zip(got, scales)):
        row = FIRST + i
        shifted = ast.shift(node, i, 0)
        want = evaluate(shifted, resolver, cell=("S", row, 4))
        if g is None:  # an empty cell read alone: the formula cell shows 0 (evaluate_task)
            g = 0.0
        assert _same(g, want), (text, row, g, want)
        assert scale == cell_scale(shifted, resolver), (text, row)


def test_row_gives_each_rows_number():
    got, _ = _run(parse("ROW()*10+ROW(B2)"), Store(["S"]))
    assert got == [r * 10.0 + r for r in range(FIRST, LAST + 1)]


@pytest.mark.parametrize("text, why", [
    ("D1+1", "reads its own block"),         # D2 reads D1, D3 reads D2 ...
    ("SUM(A2:A3)", "relative range"),
    ("A2:A5*2", "implicit intersection"),     # one value per row from a column
    ('INDIRECT("A"&ROW())', "gives a reference"),
    ("MYUDF(A2)", "not a built-in"),
    ("SUBTOTAL(9,A2)", "layout"),
])
def test_what_the_cell_by_cell_path_takes(text, why):
    with pytest.raises(NotVectorizable, match=why):
        compile_block(parse(text), "S", 4, FIRST, LAST)


def test_row_invariance_and_intersection():
    assert row_invariant(parse("$A$1+SUM($B$1:$B$9)+Ten"))
    assert not row_invariant(parse("A$1+A1"))
    assert not row_invariant(parse("ROW()"))
    assert intersects(parse("A1:A9+1")) and intersects(parse("ABS(A1:A9)"))
    assert not intersects(parse("SUM(A1:A9)")) and not intersects(parse("A1:C1+1"))
