"""tradeoff.steps: the step dimension's errors against the offset slider-crank's
hand-derived dead centres (stroke: |AC| = l_BC +- l_AB; rod angle: asin((e +- l_AB)/l_BC)),
the grid maxima taken from tests/mp_reference.py at 50 digits; the derivative dimension's
finite-difference errors recomputed from mp_reference's positions and rates; the cost
columns read back from each workbook's row count."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from tests import mp_reference
from workbook_gen.scene import load_scene
from workbook_gen.tradeoff import steps
from workbook_gen.tradeoff.reference50 import Extremes, Precise

SLIDER = "templates/slider_crank.toml"
STEPS = (10.0, 7.0)


def _hand_extremes(p):
    l_ab, l_bc, e = p["l_AB"], p["l_BC"], p["e"]
    s_max, s_min = math.sqrt((l_bc + l_ab) ** 2 - e ** 2), math.sqrt((l_bc - l_ab) ** 2 - e ** 2)
    th_max, th_min = math.degrees(math.asin((e + l_ab) / l_bc)), math.degrees(
        math.asin((e - l_ab) / l_bc))
    return {"s_C": Extremes(s_max, s_min, math.degrees(math.atan2(e, s_max)),
                            180 + math.degrees(math.atan2(e, s_min))),
            "theta_2": Extremes(th_max, th_min, 270.0, 90.0)}


def _mp_column(p, xs, name):
    with mpmath.workdps(50):
        return [mp_reference.slider_crank(p, x)[0][name] for x in xs]


@pytest.fixture(scope="module")
def measured():
    scene = load_scene(SLIDER)
    extremes = _hand_extremes(scene.parameters)
    mp = pytest.MonkeyPatch()
    mp.setattr(steps, "step_settings", lambda scene: STEPS)
    try:
        rows, runs = steps.measure_steps(scene, extremes, lambda label: None)
        derivatives = steps.measure_derivatives(scene, Precise(scene), runs, lambda label: None)
    finally:
        mp.undo()
    return scene, extremes, rows, runs, derivatives


def test_settings_and_labels():
    scene = load_scene(SLIDER)
    assert steps.step_settings(scene) == (10.0, 5.0, 2.0, 1.0, 0.5, 0.1)
    assert steps.step_label(scene, 0.5) == "0.5 deg"
    actuator = load_scene("templates/actuator_linkage.toml")  # input step 0.0687 (unitless)
    assert steps.step_settings(actuator) == (0.0687, 0.03435, 0.01374, 0.00687, 0.003435,
                                             0.000687)
    assert steps.derivative_progress_steps(scene) == 6
    assert steps.derivative_progress_steps(load_scene("templates/five_bar.toml")) == 0


def test_step_errors_are_the_grid_extremes_against_the_dead_centres(measured):
    scene, extremes, rows, _, _ = measured
    assert [r.setting for r in rows] == ["10 deg", "7 deg"]
    for row, h in zip(rows, STEPS):
        xs = [i * h for i in range(int(360 / h + 1e-9) + 1)]
        s = [float(v) for v in _mp_column(scene.parameters, xs, "s_C")]
        true = extremes["s_C"]
        expected = max(true.maximum - max(s), min(s) - true.minimum) / true.magnitude
        assert row.errors["s_C"] == pytest.approx(expected, rel=1e-9, abs=0), row.setting
        assert row.rows == len(xs) and row.cells > 0 and row.bytes > 0
    # the rod's extremes sit at 90 and 270 deg, on both grids: only rounding is left
    assert rows[0].errors["theta_2"] < 1e-14 and rows[1].errors["theta_2"] > 1e-6
    assert rows[0].max_error == max(rows[0].errors.values())


def test_finite_differences_against_the_independent_rates(measured):
    scene, _, _, runs, rows = measured
    by = {r.setting: r for r in rows}
    assert set(by) == {f"{s}, {h:g} deg" for s in ("analytic", "central", "forward")
                       for h in STEPS}
    assert by["analytic, 10 deg"].max_error < 1e-13
    w = scene.parameters["omega_1"] * 180 / math.pi  # d/dt per d/d(theta in deg)
    for h in STEPS:
        xs = [i * h for i in range(int(360 / h + 1e-9) + 1)]
        s = np.array([float(v) for v in _mp_column(scene.parameters, xs, "s_C")])
        v = np.array([float(v) for v in _mp_column(scene.parameters, xs, "v_C")])
        central = (s[2:] - s[:-2]) / (2 * h) * w - v[1:-1]
        forward = (s[1:] - s[:-1]) / h * w - v[:-1]
        expected_c = np.max(np.abs(central)) / np.max(np.abs(v[1:-1]))
        expected_f = np.max(np.abs(forward)) / np.max(np.abs(v[:-1]))
        assert by[f"central, {h:g} deg"].errors["v_C"] == pytest.approx(expected_c, rel=1e-6, abs=0)
        assert by[f"forward, {h:g} deg"].errors["v_C"] == pytest.approx(expected_f, rel=1e-6, abs=0)
    # positions-only workbook plus a difference column per rate and row
    run = runs[0]
    assert by["central, 10 deg"].cells > 2 * 2 * run.result.rows


def test_find_extremes_refines_the_finest_grid():
    scene = load_scene(SLIDER)
    found = steps.find_extremes(scene, Precise(scene))
    hand = _hand_extremes(scene.parameters)
    for name in ("s_C", "theta_2"):
        assert found[name].maximum == pytest.approx(hand[name].maximum, rel=1e-13, abs=0)
        assert found[name].minimum == pytest.approx(hand[name].minimum, rel=1e-13, abs=0)
        assert found[name].at_max == pytest.approx(hand[name].at_max, abs=1e-5)


def test_no_chain_no_derivative_rows():
    scene = load_scene("templates/five_bar.toml")
    (row,) = steps.measure_derivatives(scene, Precise(scene), [], lambda label: None)
    assert row.setting == "n/a" and row.max_error is None and "five_bar" in row.note


@pytest.mark.parametrize("side", ["max", "min"])
def test_each_side_of_the_range_counts(monkeypatch, side):
    """True extremes placed on the grid's own maximum (or minimum): only the other side's
    miss is left (workbooks not written: the cost is not what is measured here)."""
    from workbook_gen.tradeoff.common import Cost
    scene = load_scene(SLIDER)
    monkeypatch.setattr(steps, "step_settings", lambda scene: (7.0,))
    monkeypatch.setattr(steps, "cost", lambda scene: Cost(0, 0, 0, 0, 0, True, 0))
    xs = [i * 7.0 for i in range(52)]
    s = [float(v) for v in _mp_column(scene.parameters, xs, "s_C")]
    hand = _hand_extremes(scene.parameters)["s_C"]
    if side == "max":
        true = Extremes(max(s), hand.minimum, 0, 0)
        expected = (min(s) - hand.minimum) / max(s)
    else:
        true = Extremes(hand.maximum, min(s), 0, 0)
        expected = (hand.maximum - max(s)) / hand.maximum
    (row,), _ = steps.measure_steps(scene, {"s_C": true}, lambda label: None)
    assert expected > 1e-6
    assert row.errors["s_C"] == pytest.approx(expected, rel=1e-9, abs=0)
