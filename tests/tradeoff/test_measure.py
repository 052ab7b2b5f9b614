"""workbook-gen tradeoff: the 50-digit reference, the four dimensions, JSON and workbook."""

from __future__ import annotations

import json
import zipfile

import numpy as np
import pytest

from workbook_gen.cli import main
from workbook_gen.tabulate import evaluate
from workbook_gen.scene import load_scene
from workbook_gen.tradeoff import measure
from workbook_gen.tradeoff.common import floats, mp_diff, mp_floats, relative
from workbook_gen.tradeoff.methods import EPSILONS, measure_methods
from workbook_gen.tradeoff.reference50 import Precise, true_extremes
from workbook_gen.tradeoff.variants import variant

SEWING = "templates/sewing_machine.toml"
ACTUATOR = "templates/actuator_linkage.toml"


def _rows(result, dimension, prefix=""):
    return [r for r in result.rows if r.dimension == dimension and r.setting.startswith(prefix)]


@pytest.fixture(scope="module")
def sewing():
    return measure(load_scene(SEWING))


@pytest.fixture(scope="module")
def actuator_methods():
    """The method dimension alone (the whole measure of the actuator takes ~30 s)."""
    return measure_methods(load_scene(ACTUATOR), lambda label: None)


def test_reference_agrees_with_float64_table_but_is_not_a_copy():
    scene = load_scene(SEWING)
    table = evaluate(scene)
    reference = Precise(scene).table(table.inputs)
    errors = [relative(mp_diff(floats(table, n), reference, n), mp_floats(reference, n))
              for n in scene.outputs]
    assert max(errors) < 1e-12
    assert max(errors) > 0  # 50 digits differ from float64 somewhere in the last bits


def test_true_extremes_of_the_needle_are_the_dead_centres():
    # centred slider-crank: C lies l_BC - l_AB and l_BC + l_AB below A
    scene = load_scene(SEWING, step=7.0)  # a grid that misses 90 and 270 deg
    table = evaluate(scene)
    found = true_extremes(Precise(scene), "y_C", table.inputs, floats(table, "y_C"))
    p = scene.parameters
    assert found.maximum == pytest.approx(-(p["l_BC"] - p["l_AB"]), rel=1e-14)
    assert found.minimum == pytest.approx(-(p["l_BC"] + p["l_AB"]), rel=1e-14)
    assert found.at_max == pytest.approx(90.0, abs=1e-6)
    assert found.at_min == pytest.approx(270.0, abs=1e-6)


def test_extremes_error_decreases_with_finer_steps(sewing):
    rows = _rows(sewing, "step")
    assert [r.setting for r in rows] == ["10 deg", "5 deg", "2 deg", "1 deg", "0.5 deg", "0.1 deg"]
    errors = [r.max_error for r in rows]
    assert all(b <= a * (1 + 1e-9) for a, b in zip(errors, errors[1:]))
    assert errors[0] > 1e-3 and errors[-1] < 1e-5
    cells = [r.cells for r in rows]
    assert cells == sorted(cells) and all(r.bytes > 0 and r.seconds > 0 for r in rows)


def test_central_differences_converge_quadratically_forward_linearly(sewing):
    def error(scheme, step):
        (row,) = _rows(sewing, "derivative", f"{scheme}, {step} deg")
        return row.max_error
    assert error("central", 1) / error("central", 0.1) > 50     # h^2: 100
    assert 5 < error("forward", 1) / error("forward", 0.1) < 20  # h: 10
    assert all(r.max_error < 1e-13 for r in _rows(sewing, "derivative", "analytic"))


def test_float64_against_fifty_digits_near_the_extremes(sewing):
    rows = {r.setting: r for r in _rows(sewing, "precision")}
    assert 0 < rows["float64, near the extremes"].max_error < 1e-13
    assert rows["mpmath 30 digits, whole table"].max_error < 1e-27
    assert rows["mpmath 50 digits, whole table"].max_error is None


def test_sewing_machine_has_no_iterative_method(sewing):
    (row,) = _rows(sewing, "method")
    assert row.setting == "n/a" and row.max_error is None


def test_newton_error_decreases_and_is_quadratic_at_the_end(tmp_path):
    scene = load_scene("templates/five_bar.toml")
    rows = measure_methods(scene, lambda label: None)
    assert rows[0].setting == "closed form" and rows[0].max_error < 1e-14
    newton = [r.max_error for r in rows[1:]]
    assert [r.setting for r in rows[1:]] == [f"newton {k}" for k in range(1, 9)]
    for a, b in zip(newton, newton[1:]):
        assert b < a or b < 1e-14
    quadratic = [(a, b) for a, b in zip(newton, newton[1:]) if 1e-12 < a < 1e-3]
    assert quadratic, newton
    for a, b in quadratic:
        assert b < 10 * a * a
    assert newton[-1] < 1e-14


def test_halving_error_within_epsilons_bound(actuator_methods):
    scene = load_scene(ACTUATOR)
    closed = evaluate(variant(scene, options={"method": "closed"}, outputs=("phi_2",)))
    p, phi = scene.parameters, floats(closed, "phi_2")
    s = closed.inputs
    # f(phi) = |C(phi) - B|^2 - s^2; |phi_mid - phi| <= |f(phi_mid)| / |f'| < epsilon / |f'|
    cx = p["x_A"] + p["l_A1"] * np.cos(phi) + p["l_A1C"] * np.sin(phi)
    cy = p["y_A"] + p["l_A1"] * np.sin(phi) - p["l_A1C"] * np.cos(phi)
    dcx = -p["l_A1"] * np.sin(phi) + p["l_A1C"] * np.cos(phi)
    dcy = p["l_A1"] * np.cos(phi) + p["l_A1C"] * np.sin(phi)
    slope = np.abs(2 * ((cx - p["x_B"]) * dcx + (cy - p["y_B"]) * dcy))
    assert np.allclose((cx - p["x_B"]) ** 2 + (cy - p["y_B"]) ** 2, s ** 2)
    rows = [r for r in actuator_methods if r.setting.startswith("epsilon")]
    assert len(rows) == len(EPSILONS)
    for eps, row in zip(EPSILONS, rows):
        assert 0 < row.abs_error <= 1.5 * eps / slope.min(), (eps, row.abs_error)
    halvings = [int(r.note.split()[0]) for r in rows]
    assert halvings == sorted(halvings) and rows[-1].max_error < rows[0].max_error * 1e-6


def test_cli_json_and_workbook_with_log_charts(tmp_path, capsys):
    code = main(["tradeoff", "templates/slider_crank.toml", "--json", "--out", str(tmp_path)])
    assert code == 0
    out = capsys.readouterr().out
    data = json.loads(out)
    rows = data["rows"]
    assert {r["dimension"] for r in rows} == {"step", "method", "derivative", "precision"}
    for row in rows:
        assert {"dimension", "setting", "max_error", "seconds", "cells", "bytes"} <= set(row)
    steps = [r for r in rows if r["dimension"] == "step"]
    assert [r["setting"] for r in steps][-1] == "0.1 deg"
    assert all(r["max_error"] > 0 and r["cells"] > 0 and r["bytes"] > 0 for r in steps)
    # CPU seconds besides wall time (issue 12 item 12): process time of generate + audit
    assert all(0 < r["cpu_seconds"] for r in steps) and 0 < data["cpu_seconds"]
    path = tmp_path / "slider_crank_tradeoff.xlsx"
    with zipfile.ZipFile(path) as z:
        charts = [n for n in z.namelist() if n.startswith("xl/charts/chart")]
        assert len(charts) >= 3
        xml = z.read(charts[0]).decode()  # the step chart: error against the step, and
        assert xml.count("<c:logBase") == 3  # seconds on a second axis (issue 12 item 12)
        assert "Tradeoff!$I$" in xml and "seconds (generate + audit)" in xml
    assert main(["tradeoff", "templates/slider_crank.toml", "--out", str(tmp_path)]) == 2


def test_tradeoff_measures_the_ok_rows_only_as_the_summary_does():
    """docs/tradeoff.md, The command: the tradeoff follows the Summary's rule.  A slider-crank rod
    1e-12 longer than its tangent length has flagged rows whose rates keep 8 digits (alpha_2 1.6e-3
    of its magnitude off 50 digits); they must not set the float64 error of the table, and the ok
    rows agree with the 50-digit trees to the last digits."""
    from workbook_gen.tradeoff.common import studied
    scene = load_scene("templates/slider_crank.toml",
                       overrides={"l_AB": 40.0, "e": 10.0, "l_BC": 10.0 * (1 + 1e-12)})
    result = evaluate(scene)
    assert "dead centre" in set(result.status)
    names = studied(scene)
    reference = Precise(scene).table(result.inputs, names)
    errors = {n: relative(mp_diff(floats(result, n), reference, n), mp_floats(reference, n))
              for n in names}
    assert max(errors.values()) <= 1e-12, errors
    raw = floats(result, "alpha_2", ok_only=False)
    assert relative(mp_diff(raw, reference, "alpha_2"), mp_floats(reference, "alpha_2")) > 1e-9


def test_fifty_digits_of_a_template_with_derived_values_agree_with_mpmath_reference():
    """The four-bar's columns use named derived values (G_far, toggle angles...) from the
    Parameters sheet: the 50-digit reference computes them too (it raised KeyError 'G_far',
    so `workbook-gen tradeoff templates/four_bar.toml` crashed)."""
    import mpmath

    from mp_reference import four_bar
    scene = load_scene("templates/four_bar.toml")
    precise = Precise(scene)
    for theta in (0.0, 40.0, 137.0, 300.0):
        row = precise.row(theta)
        with mpmath.workdps(50):
            ref, _ = four_bar({k: mpmath.mpf(v) for k, v in scene.parameters.items()},
                              mpmath.mpf(theta))
        for name in ("theta_3", "theta_4", "omega_4", "alpha_4"):
            assert abs(row[name] - ref[name]) <= mpmath.mpf("1e-30") * (1 + abs(ref[name])), \
                (theta, name)
