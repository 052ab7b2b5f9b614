"""tradeoff.reference50: the scene's trees at 50 digits agree with the independent
50-digit mechanisms of tests/mp_reference.py to 40 digits; the true extremes of the
offset slider-crank's stroke are its dead centres, derived by hand (A, B, C collinear)."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from tests import mp_reference
from workbook_gen.scene import load_scene
from workbook_gen.tabulate import evaluate
from workbook_gen.tradeoff.common import floats
from workbook_gen.tradeoff.reference50 import Extremes, Precise, true_extremes
from workbook_gen.xlerror import ExcelError

SLIDER = "templates/slider_crank.toml"


@pytest.fixture(scope="module")
def slider():
    scene = load_scene(SLIDER, step=7.0)  # a grid that misses the dead centres
    return scene, Precise(scene), evaluate(scene)


@pytest.mark.parametrize("x", [0.0, 33.3, 181.0, 305.5])
def test_columns_agree_with_the_independent_model_to_40_digits(slider, x):
    scene, precise, _ = slider
    row = precise.row(x)
    with mpmath.workdps(50):
        ref, singular = mp_reference.slider_crank(scene.parameters, x)
        assert not singular
        for name in scene.outputs:
            scale = max(1, abs(ref[name]))
            assert abs(row[name] - ref[name]) < mpmath.mpf(10) ** -40 * scale, name


def test_only_the_needed_columns_are_evaluated(slider):
    scene, precise, _ = slider
    row = precise.row(10.0, ("s_C",))
    assert "s_C" in row and "alpha_2" not in row and "a_C" not in row


def test_derived_values_and_errors_four_bar():
    scene = load_scene("templates/four_bar.toml")
    assert scene.template.derived  # the four-bar's length gaps are derived values
    precise = Precise(scene)
    name = "theta_4" if "theta_4" in scene.outputs else scene.outputs[0]
    for x in (20.0, 200.0):
        with mpmath.workdps(50):
            ref, _ = mp_reference.four_bar(scene.parameters, x,
                                           scene.options.get("branch", "open"))
            got = precise.row(x, (name,))[name]
            assert abs(got - ref[name]) < mpmath.mpf(10) ** -40 * max(1, abs(ref[name]))
    assert name == "theta_4"


def test_an_error_column_is_none_where_the_model_does_not_assemble():
    scene = load_scene("templates/five_bar.toml", {"R_path": 0.7})
    precise = Precise(scene)
    for x in (0.0, 60.0, 90.0, 250.0):
        with mpmath.workdps(50):
            ref, _ = mp_reference.five_bar(scene.parameters, x)
        value = precise.row(x, ("theta_4",))["theta_4"]
        if ref is None:
            assert isinstance(value, ExcelError) and precise.column("theta_4")(x) is None
        else:
            assert abs(value - ref["theta_4"]) < 1e-40 * abs(ref["theta_4"])
    with mpmath.workdps(50):
        assert mp_reference.five_bar(scene.parameters, 60.0)[0] is None  # the case is met


def test_true_extremes_of_the_stroke_are_the_dead_centres(slider):
    scene, precise, table = slider
    p = {k: mpmath.mpf(v) for k, v in scene.parameters.items()}
    found = true_extremes(precise, "s_C", table.inputs, floats(table, "s_C"))
    with mpmath.workdps(50):
        # C runs on the line y = e (phi_slide = 0); at the dead centres |AC| = l_BC +- l_AB
        far, near = p["l_BC"] + p["l_AB"], p["l_BC"] - p["l_AB"]
        s_max, s_min = mpmath.sqrt(far ** 2 - p["e"] ** 2), mpmath.sqrt(near ** 2 - p["e"] ** 2)
        at_max = mpmath.degrees(mpmath.atan2(p["e"], s_max))
        at_min = 180 + mpmath.degrees(mpmath.atan2(p["e"], s_min))
    assert abs(found.maximum - float(s_max)) <= 1e-13 * float(s_max)
    assert abs(found.minimum - float(s_min)) <= 1e-13 * float(s_max)
    assert found.at_max == pytest.approx(float(at_max), abs=1e-6)
    assert found.at_min == pytest.approx(float(at_min), abs=1e-6)
    assert found.magnitude == found.maximum
    # the grid alone is off by far more: the refinement is what finds them
    grid = floats(table, "s_C")
    assert float(s_max) - np.nanmax(grid) > 1e-4


def test_no_defined_value_no_extremes(slider):
    _, precise, table = slider
    assert true_extremes(precise, "s_C", table.inputs, np.full(table.rows, np.nan)) is None
    assert Extremes(-3.0, -5.0, 0, 0).magnitude == 5.0
