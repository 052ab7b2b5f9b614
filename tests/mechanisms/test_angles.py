"""mechanisms/angles.py: the reduction of an angle to [-180, 180] is exact, and the sines
and cosines of degrees built on it keep full relative accuracy near every multiple of
90 deg (where SIN(RADIANS(x)) keeps only pi's absolute rounding), against mpmath at 50
digits. The trees are evaluated by the numpy printer that makes the cached values."""

from __future__ import annotations

import random
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from workbook_gen import xlmath as xm
from workbook_gen.expr import Var
from workbook_gen.expr.numeric import compile_numpy
from workbook_gen.mechanisms.angles import (cos_deg, cos_half_squared, reduced, sin_deg,
                                            sin_half_squared, sin_half_squared_90)

RNG = random.Random(23)
U = Var("u")


@pytest.fixture(autouse=True)
def fifty_digits():
    """mpmath at 50 digits here only (a global setting would leak into other modules)."""
    with mpmath.workdps(50):
        yield


def values(tree, xs: list[float]) -> np.ndarray:
    out = compile_numpy(tree)({"u": xm.array(np.array(xs, dtype=float))}, {}, len(xs))
    assert not out.err.any()
    return out.val


def near(multiples, offsets) -> list[float]:
    return [m + s * d for m in multiples for d in offsets for s in (1, -1)]


OFFSETS = [0.0, 1e-13, 1e-9, 1e-6, 1e-3, 0.37, 7.5]


def exact_reduced(theta: float) -> Fraction:
    t = Fraction(theta)
    return (t + 180) % 360 - 180 if abs(t) > 180 else t


def test_the_reduction_is_exact():
    xs = near([0, 180, 360, 540, -180, -360, -540], OFFSETS) + \
        [RNG.uniform(-540, 540) for _ in range(300)]
    got = values(reduced(U), xs)
    for x, r in zip(xs, got):
        want = exact_reduced(x)
        if abs(want) == 180:
            assert abs(Fraction(r)) == 180, x
        else:
            assert Fraction(r) == want, x        # to the bit


def rel_err(got: float, want) -> float:
    if abs(want) < mpmath.mpf(10) ** -40:    # a zero, to mpmath's 50 digits
        return abs(got)
    return float(abs(mpmath.mpf(got) - want) / abs(want))


@pytest.mark.parametrize("name, tree, fn", [
    ("sin", sin_deg(U), lambda u: mpmath.sin(u * mpmath.pi / 180)),
    ("cos", cos_deg(U), lambda u: mpmath.cos(u * mpmath.pi / 180)),
])
def test_sine_and_cosine_of_degrees_keep_their_digits(name, tree, fn):
    xs = near([0, 90, 180, -90, -180], OFFSETS) + [RNG.uniform(-180, 180) for _ in range(300)]
    xs = [x for x in xs if -180 <= x <= 180]
    for x, got in zip(xs, values(tree, xs)):
        want = fn(mpmath.mpf(x))
        assert rel_err(got, want) < 4e-16, (name, x, got)


def test_exact_at_multiples_of_90():
    assert values(sin_deg(U), [0, 90, 180, -90, -180]).tolist() == [0, 1, 0, -1, 0]
    assert values(cos_deg(U), [0, 90, 180, -90, -180]).tolist() == [1, 0, -1, 0, -1]
    assert values(sin_half_squared_90(U), [90, -90]).tolist() == [0.5, 0.5]


def test_half_angle_squares_near_their_zeros():
    xs = near([0], OFFSETS[1:]) + [RNG.uniform(-180, 180) for _ in range(200)]
    for x, got in zip(xs, values(sin_half_squared(U), xs)):
        want = mpmath.sin(mpmath.mpf(x) * mpmath.pi / 360) ** 2
        assert rel_err(got, want) < 8e-16, x
    xs = near([180, -180], OFFSETS[1:])
    xs = [x for x in xs if -180 <= x <= 180]
    for x, got in zip(xs, values(cos_half_squared(U), xs)):
        want = mpmath.cos(mpmath.mpf(x) * mpmath.pi / 360) ** 2
        assert rel_err(got, want) < 8e-16, x
