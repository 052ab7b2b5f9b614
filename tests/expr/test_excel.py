"""The tree's printers agree with each other: the Excel text, parsed back and evaluated
cell by cell by the formula evaluator (Excel semantics, written independently of the
numpy kernel), gives what the numpy printer gives; and the mpmath printer agrees."""

from __future__ import annotations

import math

import mpmath
import numpy as np
from hypothesis import assume, given, settings, strategies as st

from workbook_gen import xlmath as xm
from workbook_gen.expr import (Param, Var, walk, abs_, acos, atan2, cos, degrees, if_, iserror, lt,
                               mod, power, radians, root, sign, sin, sqrt, wrap)
from workbook_gen.expr.excel import to_excel
from workbook_gen.expr.numeric import compile_numpy
from workbook_gen.expr.precise import compile_mpmath
from workbook_gen.formula import parse
from workbook_gen.formula.scalar import DictResolver, evaluate
from workbook_gen.mechanisms import TEMPLATES
from workbook_gen.xlerror import ExcelError

VARS = {"x": "A1", "y": "B1"}
LEAVES = st.sampled_from([Var("x"), Var("y"), Param("p"), wrap(0.0), wrap(2.0), wrap(0.5),
                          wrap(-3.0), wrap(1e-5)])


SMOOTH_UNARY = [sin, cos, sqrt, abs_, radians, degrees, acos, lambda a: -a, root]
SMOOTH_BINARY = [lambda a, b: a + b, lambda a, b: a - b, lambda a, b: a * b,
                 lambda a, b: a / b, lambda a, b: a ** b, atan2, power]
# Jumps: where float64 and 30 digits may land on different sides.
STEP_UNARY = [sign, iserror]
STEP_BINARY = [mod, lambda a, b: if_(lt(a, b), a, b)]


def _extender(unaries, binaries):
    def extend(children):
        return st.one_of(
            st.builds(lambda f, a: f(a), st.sampled_from(unaries), children),
            st.builds(lambda f, a, b: f(a, b), st.sampled_from(binaries), children, children))
    return extend


TREES = st.recursive(LEAVES, _extender(SMOOTH_UNARY + STEP_UNARY, SMOOTH_BINARY + STEP_BINARY),
                     max_leaves=8)
SMOOTH_TREES = st.recursive(LEAVES, _extender(SMOOTH_UNARY, SMOOTH_BINARY), max_leaves=8)
NUMBERS = st.sampled_from([0.0, 1.0, -1.0, 2.0, -2.5, 0.5, 3.0, -0.0, 1e-3, 7.25])


def _same(a, b) -> bool:
    if isinstance(a, ExcelError) or isinstance(b, ExcelError):
        return a == b
    return math.isclose(float(a), float(b), rel_tol=1e-12, abs_tol=1e-12)


@settings(max_examples=400, deadline=None)
@given(TREES, NUMBERS, NUMBERS, NUMBERS)
def test_excel_text_evaluates_like_the_numpy_printer(tree, x, y, p):
    text = to_excel(tree, VARS.get)
    cell = evaluate(parse(text), DictResolver({"A1": x, "B1": y}, {"p": p}))
    column = compile_numpy(tree)({"x": xm.array(np.array([x])), "y": xm.array(np.array([y]))},
                                 {"p": p}, 1)
    ours = (ExcelError.from_code(int(column.err[0])) if column.err[0] else float(column.val[0]))
    assert _same(cell, ours), f"{text}: formula evaluator {cell!r}, numpy {ours!r}"


@settings(max_examples=200, deadline=None)
@given(SMOOTH_TREES, NUMBERS, NUMBERS, NUMBERS)
def test_mpmath_printer_agrees_with_numpy_printer(tree, x, y, p):
    column = compile_numpy(tree)({"x": xm.array(np.array([x])), "y": xm.array(np.array([y]))},
                                 {"p": p}, 1)
    values = {"x": mpmath.mpf(x), "y": mpmath.mpf(y)}
    with mpmath.workdps(30):
        precise = compile_mpmath(tree)(values, {"p": p})
        # outside float64's range (an intermediate under- or overflows) they differ by right
        for sub in walk(tree):
            v = compile_mpmath(sub)(values, {"p": p})
            assume(isinstance(v, (ExcelError, str)) or v == 0 or 1e-300 < abs(v) < 1e300)
    if column.err[0] or isinstance(precise, ExcelError):
        # near a domain edge rounding may decide differently; exactly representable
        # inputs make that rare: require agreement unless float64 sits on the edge
        return
    value = float(column.val[0])
    assert math.isclose(value, float(precise), rel_tol=1e-9, abs_tol=1e-9)


def test_unary_minus_and_power_print_as_excel_reads_them():
    x = Var("x")
    assert to_excel(-(x ** 2), VARS.get) == "=-(A1^2)"
    assert to_excel((-x) ** 2, VARS.get) == "=(-A1)^2"
    assert to_excel((x ** 2) ** 3, VARS.get) == "=A1^2^3"
    assert to_excel(x ** (wrap(2.0) ** 3), VARS.get) == "=A1^(2^3)"
    assert to_excel(x - (x - 1), VARS.get) == "=A1-(A1-1)"
    assert to_excel(atan2(x, 1e-5), VARS.get) == "=ATAN2(A1,1E-05)"


def test_every_template_formula_round_trips_through_the_parser():
    from workbook_gen.formula import render
    for template in TEMPLATES.values():
        for quantity in template.quantities:
            text = to_excel(quantity.expr, lambda n: "Z9")
            assert "=" + render(parse(text)) == text


def test_cached_node_hashes_are_not_pickled():
    """Nodes cache their hash; string hashes differ between processes (a batch sends
    scenes to workers), so a pickled node must hash afresh."""
    import pickle
    import subprocess
    import sys
    from workbook_gen.expr.tree import Bin, Call, Neg, Num
    tree = Call("SIN", (Neg(Bin("+", Var("x"), Num(1.0))),))
    assert hash(tree) == hash(Call("SIN", (Neg(Bin("+", Var("x"), Num(1.0))),)))
    code = ("import pickle, sys\nfrom workbook_gen.expr import Var, Num\n"
            "from workbook_gen.expr.tree import Bin, Call, Neg\n"
            "tree = pickle.loads(sys.stdin.buffer.read())\n"
            "fresh = Call('SIN', (Neg(Bin('+', Var('x'), Num(1.0))),))\n"
            "print(hash(tree) == hash(fresh) and {fresh: 1}.get(tree) == 1)")
    out = subprocess.run([sys.executable, "-c", code], input=pickle.dumps(tree),
                         capture_output=True, check=True).stdout
    assert out.decode().strip() == "True"
