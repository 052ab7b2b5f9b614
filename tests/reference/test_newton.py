"""reference/newton.py, the reference solver's generic machinery, against mpmath: jets
carry the first and second time derivatives (mpmath.diff at 30 digits); a two-link arm
whose tip is driven along a path is solved for its joint angles (the law of cosines in
closed form) with velocities and accelerations (mpmath's numerical derivatives of that
closed form); singular rows are NaN; wrap_deg wraps into (low, low + 360]."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from workbook_gen.reference.newton import Jet, jcos, jsin, solve_batched, solve_stage, wrap_deg

L1, L2 = 1.3, 0.8


@pytest.fixture(autouse=True)
def thirty_digits():
    """mpmath at 30 digits here only (a global setting would leak into other modules)."""
    with mpmath.workdps(30):
        yield


def test_jets_carry_two_derivatives():
    a, b = (0.3, 1.1, -0.7), (-1.2, 0.4, 2.0)   # value, first, second at t = 0
    x, y = Jet(*a), Jet(*b)

    def f(t):
        xt = a[0] + a[1] * t + a[2] * t * t / 2
        yt = b[0] + b[1] * t + b[2] * t * t / 2
        return mpmath.sin(xt) * yt + mpmath.cos(xt * yt) - 3 * xt

    got = jsin(x) * y + jcos(x * y) - 3 * x
    for order, part in ((0, got.v), (1, got.d), (2, got.dd)):
        assert float(part) == pytest.approx(float(mpmath.diff(f, 0, order)), rel=1e-13)


def tip(t):
    """The tip's path, mpmath or numpy alike: an ellipse inside the arm's reach."""
    sin, cos = (mpmath.sin, mpmath.cos) if isinstance(t, mpmath.mpf) else (np.sin, np.cos)
    return 1.2 + 0.5 * cos(t), 0.3 + 0.4 * sin(t)


def closed_form(t):
    x, y = tip(t)
    c2 = (x * x + y * y - L1 * L1 - L2 * L2) / (2 * L1 * L2)
    q2 = mpmath.acos(c2)                                   # elbow down: q2 in (0, pi)
    q1 = mpmath.atan2(y, x) - mpmath.atan2(L2 * mpmath.sin(q2), L1 + L2 * mpmath.cos(q2))
    return q1, q2


def arm(q, d):
    q1, q2 = q
    x, y = d
    return [L1 * jcos(q1) + L2 * jcos(q1 + q2) - x, L1 * jsin(q1) + L2 * jsin(q1 + q2) - y]


def test_a_driven_arm_positions_and_rates():
    ts = np.linspace(0, 2 * np.pi, 41)
    x, y = tip(ts)
    drivers = [Jet(x, -0.5 * np.sin(ts), -0.5 * np.cos(ts)),      # d/dt of the path, rate 1
               Jet(y, 0.4 * np.cos(ts), -0.4 * np.sin(ts))]
    guess = np.array([[float(v) + 0.05 for v in closed_form(mpmath.mpf(t))] for t in ts])
    motion = solve_stage(arm, guess, drivers, scale=2.0)
    assert motion.assembled.all() and not motion.singular.any()
    for i, t in enumerate(ts):
        t = mpmath.mpf(t)
        for k in range(2):
            fk = (lambda s, k=k: closed_form(s)[k])
            assert motion.q[i, k] == pytest.approx(float(fk(t)), abs=1e-13)
            assert motion.dq[i, k] == pytest.approx(float(mpmath.diff(fk, t, 1)), abs=1e-11)
            assert motion.ddq[i, k] == pytest.approx(float(mpmath.diff(fk, t, 2)), abs=1e-9)


def test_singular_rows_are_nan():
    a = np.array([[[1.0, 2.0], [2.0, 4.0]], [[2.0, 0.0], [0.0, 3.0]]])
    x, singular = solve_batched(a, np.array([[1.0, 1.0], [4.0, 9.0]]))
    assert singular.tolist() == [True, False]
    assert np.isnan(x[0]).all() and x[1].tolist() == [2.0, 3.0]


def test_wrap_deg():
    rng = np.random.default_rng(5)
    angles = rng.uniform(-20, 20, 500)
    for low in (-180.0, 0.0, 37.5):
        got = wrap_deg(angles, low)
        assert ((got > low) & (got <= low + 360)).all()
        turns = (got - np.degrees(angles)) / 360
        assert np.allclose(turns, np.round(turns), atol=1e-12)
    assert wrap_deg(np.array([math.pi]), -180.0).tolist() == [180.0]
