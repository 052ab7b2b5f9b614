"""tradeoff.precision: the float64 table's error recomputed row by row against
tests/mp_reference.py's slider-crank at 50 digits (whole table, and the rows of the finest
grid around each extreme, relative to the hand-derived dead centres' magnitude); the
30-digit evaluation lands near 1e-30."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from tests import mp_reference
from workbook_gen.scene import load_scene
from workbook_gen.tabulate import evaluate
from workbook_gen.tradeoff.common import Cost, studied
from workbook_gen.tradeoff.precision import NEAR, measure_precision
from workbook_gen.tradeoff.reference50 import Extremes, Precise
from workbook_gen.tradeoff.steps import StepRun
from workbook_gen.tradeoff.variants import variant

FINE = 7.0


@pytest.fixture(scope="module")
def measured():
    scene = load_scene("templates/slider_crank.toml", step=20.0)
    p = scene.parameters
    s_max = math.sqrt((p["l_BC"] + p["l_AB"]) ** 2 - p["e"] ** 2)
    s_min = math.sqrt((p["l_BC"] - p["l_AB"]) ** 2 - p["e"] ** 2)
    extremes = {"s_C": Extremes(s_max, s_min, 0.0, 180.0)}
    fine = StepRun(FINE, evaluate(variant(scene, step=FINE)), Cost(0, 0, 0, 0, 0, True, 0))
    calls = []
    rows = measure_precision(scene, Precise(scene), extremes, fine, calls.append)
    return scene, extremes, fine, rows, calls


def _mp(p, xs, name):
    with mpmath.workdps(50):
        return [mp_reference.slider_crank(p, float(x))[0][name] for x in xs]


def _err(table, ref):
    with mpmath.workdps(60):
        return [abs(mpmath.mpf(float(a)) - b) for a, b in zip(table, ref)]


def test_the_rows_and_their_counts(measured):
    scene, _, fine, rows, calls = measured
    assert [r.setting for r in rows] == ["float64, whole table", "float64, near the extremes",
                                         "mpmath 30 digits, whole table",
                                         "mpmath 50 digits, whole table"]
    names = studied(scene)
    assert rows[0].cells == 19 * len(names) and rows[0].rows == 19
    assert rows[1].rows == fine.result.rows and calls == ["precision"]
    assert rows[3].max_error is None and rows[3].note == "the reference"


def test_whole_table_error_against_the_independent_model(measured):
    scene, _, _, rows, _ = measured
    table = evaluate(scene)
    for name in studied(scene):
        ref = _mp(scene.parameters, table.inputs, name)
        err = _err(table.columns[name].val, ref)
        expected = float(max(err) / max(abs(r) for r in ref))
        assert rows[0].errors[name] == pytest.approx(expected, rel=1e-9, abs=0), name
        assert expected < 1e-13


def test_near_the_extremes_the_rows_either_side_of_each_grid_extreme(measured):
    scene, extremes, fine, rows, _ = measured
    y = fine.result.columns["s_C"].val
    hi, lo = int(np.argmax(y)), int(np.argmin(y))
    idx = sorted({i for c in (hi, lo) for i in range(max(0, c - NEAR),
                                                      min(len(y), c + NEAR + 1))})
    assert hi < NEAR and len(idx) == (2 * NEAR + 1) + (hi + NEAR + 1)  # clipped at row 0
    ref = _mp(scene.parameters, fine.result.inputs[idx], "s_C")
    expected = float(max(_err(y[idx], ref))) / extremes["s_C"].magnitude
    assert rows[1].errors == {"s_C": pytest.approx(expected, rel=1e-9, abs=0)}
    assert rows[1].cells == len(idx)


def test_thirty_digits_are_thirty_digits(measured):
    _, _, _, rows, _ = measured
    assert all(1e-33 < e < 1e-28 for e in rows[2].errors.values())
