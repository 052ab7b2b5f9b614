"""tabulate/checks.py: the Checks' residual cells against the loop closure recomputed
with numpy from the Table's columns (a corrupted angle must FAIL), the "n/a" guard and
the row flags against the status, MAX's rules (support.microsoft.com, "MAX function":
text in a reference is ignored, no numbers gives 0; an error in the range is the
result), and the design conditions against their formula written out by hand
(docs: m_i1 u_i1 + m_i2 l_i1 (l_i2 - xi_i)/l_i2 + m_ci u_ci = 0)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import mp_reference
from workbook_gen import xlmath as xm
from workbook_gen.scene import load_scene
from workbook_gen.tabulate.checks import (SKIPPED, TOLERANCE, check_values,
                                          condition_values, guarded_cells, is_flagged,
                                          max_abs, verdict)
from workbook_gen.tabulate.table import CANNOT_ASSEMBLE, evaluate_table

NORTON = {"l_O1O2": 100.0, "l_O1A": 40.0, "l_AB": 120.0, "l_O2B": 80.0, "l_AC": 60.0,
          "delta_C": 30.0, "omega_2": 10.0}
INPUTS = [0.0, 40.0, 100.0, 170.0, 230.0, 300.0]


@pytest.fixture(scope="module")
def table():
    return evaluate_table(mp_reference.scene_at("four_bar", NORTON, INPUTS))


def _closure(t2, t3, t4):
    """|O1A + AB - O1O2 - O2B| / l_O1O2, the loop's position residual, by numpy."""
    r = np.radians
    dx = 40 * np.cos(r(t2)) + 120 * np.cos(r(t3)) - 100 - 80 * np.cos(r(t4))
    dy = 40 * np.sin(r(t2)) + 120 * np.sin(r(t3)) - 80 * np.sin(r(t4))
    return np.hypot(dx, dy) / 100


def _with(table, **changes):
    columns = dict(table.columns)
    for name, values in changes.items():
        columns[name] = xm.array(np.asarray(values, float))
    return dataclasses.replace(table, columns=columns)


def test_a_correct_table_passes_with_residuals_at_rounding(table):
    values = check_values(table)
    assert values.overall == "PASS"
    assert set(values.verdicts.values()) == {"PASS"}
    assert all(0 <= m <= 1e-13 for m in values.maxima.values())


def test_a_corrupted_angle_fails_with_the_numpy_residual(table):
    theta_3 = table.columns["theta_3"].val.copy()
    theta_3[2] += 0.01                      # one row off by a hundredth of a degree
    values = check_values(_with(table, theta_3=theta_3))
    expected = _closure(np.array(INPUTS), theta_3, table.columns["theta_4"].val)
    got = np.array(values.cells["loop_position"], float)
    assert np.allclose(got, expected, rtol=1e-9, atol=1e-14)
    assert expected[2] > 1e-5 and values.maxima["loop_position"] == pytest.approx(expected[2])
    assert values.verdicts["loop_position"] == "FAIL" and values.overall == "FAIL"


def test_rows_not_ok_hold_n_a_and_their_flags(table):
    status = np.array(["ok", "dead centre", CANNOT_ASSEMBLE, "ok", "not converged", "ok"],
                      dtype=object)
    theta_3 = table.columns["theta_3"].val.copy()
    theta_3[1] += 1.0   # a flagged row's wrong angle: skipped, so the checks still pass
    values = check_values(dataclasses.replace(_with(table, theta_3=theta_3), status=status))
    for cells in values.cells.values():
        assert [c == SKIPPED for c in cells] == [s != "ok" for s in status]
    assert values.cannot_assemble == [0, 0, 1, 0, 0, 0]
    assert values.flagged == [0, 1, 0, 0, 1, 0]
    assert values.overall == "PASS"
    assert [is_flagged(s) for s in status] == [False, True, False, False, True, False]


def test_max_abs_follows_excels_max():
    none = np.zeros(3, np.uint8)
    assert max_abs([1e-3, SKIPPED, -2e-3], none) == 2e-3          # -MIN wins, text skipped
    assert max_abs([SKIPPED, SKIPPED], np.zeros(2, np.uint8)) == 0.0   # no numbers: 0
    err = np.array([0, xm.NUM, xm.DIV0], np.uint8)                 # the first error
    assert max_abs([1.0, "#NUM!", "#DIV/0!"], err) == "#NUM!"


def test_verdict_at_the_tolerance():
    assert TOLERANCE == 1e-9
    assert verdict(1e-9) == "PASS" and verdict(1.0000001e-9) == "FAIL"
    assert verdict(0.0) == "PASS" and verdict("#VALUE!") == "#VALUE!"


def test_guarded_cells_by_hand():
    ok = xm.array(np.array([1.0, 0.0, 1.0, 1.0]))
    column = xm.XArray(np.array([0.5, 7.0, -2.0, 0.0]),
                       np.array([0, xm.DIV0, 0, xm.NUM], np.uint8))
    cells, err = guarded_cells(column, ok)
    assert cells == [0.5, SKIPPED, -2.0, "#NUM!"]
    assert list(err) == [0, 0, 0, xm.NUM]
    text = xm.XArray(np.array(["a", "b"], dtype=object), np.zeros(2, np.uint8))
    cells, err = guarded_cells(text, xm.array(np.array([0.0, 1.0])))
    assert cells == [SKIPPED, "b"] and not err.any()


def test_design_conditions_by_their_formula():
    scene = load_scene("templates/parallel_4dof_balanced.toml")
    balanced = evaluate_table(scene)
    found = condition_values(balanced)
    assert found.overall == "PASS" and len(found.items) == 12
    p = dict(balanced.params)
    p["u_c1"] += 0.05                     # leg 1's counterweight moved 5 cm out
    moved = condition_values(dataclasses.replace(balanced, params=p))
    terms = [p["m_11"] * p["u_11"], p["m_12"] * p["l_11"] * (p["l_12"] - p["xi_1"]) / p["l_12"],
             p["m_c1"] * p["u_c1"]]
    first = moved.items[0]
    assert first.value == pytest.approx(sum(terms), rel=1e-12)
    assert abs(sum(terms)) == pytest.approx(p["m_c1"] * 0.05, rel=1e-9)
    assert first.scale == pytest.approx(sum(abs(t) for t in terms), rel=1e-12)
    assert first.relative == pytest.approx(abs(sum(terms)) / first.scale, rel=1e-12)
    assert first.verdict == "FAIL" and moved.overall == "FAIL"
    assert [c.verdict for c in moved.items[1:]] == ["PASS"] * 11
