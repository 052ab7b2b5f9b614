"""expr.magnitude: the magnitudes a tree's arithmetic cancels, against the rules of the
module's docstring (docs/workbook.md, Summary) derived by hand per row in plain Python:

    m(a +- b) = m(a) + m(b)     m(a * b) = |b| m(a) + |a| m(b)
    m(a / b)  = m(a) / |b| + |a| m(b) / b^2     m(f(a)) = |f'(a)| m(a) + |f(a)|
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbook_gen import xlmath as xm
from workbook_gen.expr import Param, Var, atan2, cos, if_, lt, max_, sin, sqrt, wrap
from workbook_gen.expr.magnitude import magnitude, scope
from workbook_gen.expr.tree import Num

X = [0.5, -2.0, 3.0, 1e-3]
Y = [2.0, 4.0, -1.5, 7.0]
P = 1.25


def _cols():
    return {"x": xm.array(np.array(X)), "y": xm.array(np.array(Y))}


def _check(tree, ref, shared=None):
    got = magnitude(tree, _cols(), {"p": P}, len(X), shared)
    want = [ref(x, y) for x, y in zip(X, Y)]
    np.testing.assert_allclose(got, want, rtol=1e-14, atol=0)


x, y, p = Var("x"), Var("y"), Param("p")


def test_leaves_count_at_their_own_size():
    _check(x, lambda a, b: abs(a))
    _check(p + 0.0 * x, lambda a, b: P + 0.0 + abs(a) * 0.0)


def test_a_cancelling_sum_keeps_the_size_of_its_terms():
    # x - x is 0 but cancels 2|x|: its rounding noise is eps times that
    _check(x - x, lambda a, b: 2 * abs(a))
    _check(x * y - p, lambda a, b: abs(b) * abs(a) + abs(a) * abs(b) + P)


def test_quotient_and_power():
    _check(x / y, lambda a, b: abs(a) / abs(b) + abs(a) * abs(b) / (b * b))
    # a^n with a literal n: |n a^(n-1)| m(a) + |a^n|
    _check(y ** 2.0, lambda a, b: abs(2 * b) * abs(b) + b * b)


def test_functions_by_their_derivative():
    _check(sin(x * y), lambda a, b: abs(math.cos(a * b)) * 2 * abs(a * b) + abs(math.sin(a * b)))
    _check(cos(x), lambda a, b: abs(math.sin(a)) * abs(a) + abs(math.cos(a)))
    _check(sqrt(y * y), lambda a, b: 0.5 / abs(b) * 2 * b * b + abs(b))
    # ATAN2(x, y) = angle of (x, y): d/dx = -y/r^2, d/dy = x/r^2
    _check(atan2(x, y), lambda a, b: (abs(b) * abs(a) + abs(a) * abs(b)) / (a * a + b * b)
           + abs(math.atan2(b, a)))


def test_if_takes_the_chosen_branch_and_max_the_largest():
    _check(if_(lt(x, y), x - y, x * 2.0),
           lambda a, b: abs(a) + abs(b) if a < b else 4 * abs(a))  # the literal 2 counts too
    _check(max_(x + y, x), lambda a, b: max(abs(a) + abs(b), abs(a)))


def test_an_error_row_is_nan():
    got = magnitude(sqrt(x), _cols(), {}, len(X))
    assert np.isnan(got[1]) and not np.isnan(got[0])


def test_a_negative_zero_literal_takes_the_node_by_node_path():
    # -0 equals 0 as a key, so the generated path is skipped; the rules still hold
    tree = Num(-0.0) + x * y
    _check(tree, lambda a, b: 0.0 + 2 * abs(a * b))


@pytest.mark.parametrize("measure_first", [False, True])
def test_a_shared_scope_gives_each_tree_its_own_magnitude(measure_first):
    t1, t2 = x * y - p, (x * y - p) / y
    shared = scope(_cols(), {"p": P}, len(X))
    if measure_first:
        shared.measure((t1, t2))
    m1 = lambda a, b: 2 * abs(a * b) + P
    _check(t1, m1, shared)
    _check(t2, lambda a, b: m1(a, b) / abs(b) + abs(a * b - P) * abs(b) / (b * b), shared)
