"""docs/stability.md, Numerical soundness at the extremes, for slider_crank and sewing_machine:
float64 cells against 50-digit mpmath over families: rods barely longer than the crank, link ratios
1e-6..1e6, very large lengths with offset and inclined slides, angles exactly 0/90/180/270/360, dead
centres."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from extremes_common import EXACT, assert_sound, grid
from mp_reference import measure


@pytest.mark.parametrize("excess", [1e-9, 1e-6, 1e-3])
@pytest.mark.parametrize("e, phi", [(0.0, 0.0), (5.0, 30.0), (-7.5, 200.0)])
def test_slider_rod_barely_longer_than_crank_plus_offset(excess, e, phi):
    crank = 100.0
    params = dict(l_AB=crank, l_BC=(crank + abs(e)) * (1 + excess), e=e, phi_slide=phi)
    assert_sound("slider_crank", params, grid(90 + phi, 270 + phi, phi, 180 + phi))


@pytest.mark.parametrize("crank", [1e-6, 1e-3, 1.0, 1e3, 1e6])
@pytest.mark.parametrize("ratio", [1 + 1e-9, 1e3, 1e6])
def test_slider_link_ratios_and_magnitudes(crank, ratio):
    params = dict(l_AB=crank, l_BC=crank * ratio, e=0.0, phi_slide=17.0)
    assert_sound("slider_crank", params, grid(107.0, 287.0, every=30.0))


@settings(max_examples=25, deadline=None)
@given(log_crank=st.floats(-6, 6), log_excess=st.floats(-9, 6),
       offset=st.floats(-0.99, 0.99), phi=st.floats(-360, 360))
def test_slider_family_property(log_crank, log_excess, offset, phi):
    crank = 10.0 ** log_crank
    room = crank * 10.0 ** log_excess            # l_BC - l_AB - |e| > 0
    e = offset * room
    params = dict(l_AB=crank, l_BC=crank + abs(e) + room, e=e, phi_slide=phi)
    assert_sound("slider_crank", params, grid(phi + 90, phi + 270, every=45.0))


def test_slider_exact_dead_centre_is_flagged():
    worst, unflagged, status = measure("slider_crank", dict(l_AB=100.0, l_BC=100.0, e=0.0),
                                       EXACT + [89.0, 91.0])
    assert list(status[:5]) == ["ok", "dead centre", "ok", "dead centre", "ok"]
    assert not unflagged and max(w for w, _ in worst.values()) <= 1e-8


@pytest.mark.parametrize("excess", [1e-9, 1e-6])
def test_sewing_rod_barely_longer_than_crank(excess):
    assert_sound("sewing_machine", dict(l_AB=32.0, l_BC=32.0 * (1 + excess)), grid(0, 180))


@pytest.mark.parametrize("x_F, y_F", [(-60.0, -20.0), (-1e6, 3e5), (-1e-3, 1e-3),
                                      (0.0, -200.0), (-33.0, -28.0)])
def test_sewing_lever_pivot_near_and_far(x_F, y_F):
    assert_sound("sewing_machine", dict(x_F=x_F, y_F=y_F), grid(0, 180, every=30.0))


def test_sewing_very_large_and_tiny_cranks():
    assert_sound("sewing_machine", dict(l_AB=3.2e6, l_BC=1e7, l_BE=2.8e6, x_F=-6e6, y_F=-2e6,
                                        l_FG=9e6, beta_E=12.0), grid(0, 180, every=30.0))
    assert_sound("sewing_machine", dict(l_AB=1e-4, l_BC=100.0), grid(0, 180, every=30.0))


def test_exact_angles_give_exact_zeros():
    """At 0/90/180/270/360 deg the crank pin's small coordinate is exactly 0 (not 1e-16)."""
    from mp_reference import scene_at
    from workbook_gen.tabulate import evaluate
    ev = evaluate(scene_at("sewing_machine", {}, EXACT))
    assert np.array_equal(ev.columns["x_B"].val[[1, 3]], [0.0, 0.0])
    assert np.array_equal(ev.columns["y_B"].val[[0, 2, 4]], [0.0, 0.0, 0.0])


@pytest.mark.parametrize("l_AB, e, phi", [(40.0, 10.0, 0.0), (40.0, -10.0, 0.0),
                                          (0.3, 0.1, 33.0), (4e5, 1e5, -720.0)])
def test_slider_rod_exactly_tangent_to_the_slide_line_is_flagged(l_AB, e, phi):
    """l_BC = |e| < l_AB + |e|: the rod reaches the slide line on part of the turn and is
    exactly tangent to it at psi = 0, 180 and where l_AB sin psi = 2 e (issue 21 item 1:
    `batch --vary l_BC=0:60:10` at l_BC = 10).  The tangent rows are dead centres with
    error rates, never the square root of rounding (h_BC 3.8e-7, v_C -1e10); every
    other row is within TOL of 50 digits."""
    l_BC = abs(e)
    inputs = [phi + 10.0 * k for k in range(37)]
    worst, status = assert_sound("slider_crank", dict(l_AB=l_AB, l_BC=l_BC, e=e,
                                                       phi_slide=phi), inputs)
    at_tangent = {s for s, x in zip(status, inputs) if (x - phi) % 180 == 0}
    assert at_tangent == {"dead centre"}, at_tangent


@pytest.mark.parametrize("stretch", [0.0, 1e-12, -1e-12, 1e-9])
@pytest.mark.parametrize("phi", [1e-6, -1e-6, 1e-4, 0.0])
def test_slider_rows_next_to_a_tangent_point_are_sound_or_flagged(stretch, phi):
    """A row 1e-6 deg from a tangent point, or a rod 1e-12 longer than the tangent length:
    the reach factor's terms cancel and round to a few ulps of the lengths, which left the
    rates with 8 digits (alpha_2 1.6e-3 off 1e-11 from the tangent) in a row marked ok.
    Every ok row is within TOL of 50 digits, and the rows next to the tangent are flagged."""
    inputs = [phi + 10.0 * k for k in range(37)]
    worst, status = assert_sound("slider_crank", dict(l_AB=40.0, l_BC=10.0 * (1 + stretch),
                                                       e=10.0, phi_slide=0.0), inputs)
    assert status[0] in ("dead centre", "cannot assemble"), status[:3]
