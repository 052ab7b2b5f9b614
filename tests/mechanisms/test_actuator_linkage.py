"""actuator_linkage (docs/mechanisms.md, actuator_linkage): every Table cell against the independent
reference, the successive halving against the closed form and an independent scalar bisection,
LibreOffice's recalculation, the audit."""

from __future__ import annotations

import math

import numpy as np
import openpyxl
import pytest

from tests.engines.test_libreoffice_recalc import compare_with_libreoffice
from workbook_cells import as_float, column_error, table_columns
from workbook_gen.errors import SceneError
from workbook_gen.reference import solve
from workbook_gen.scene import load_scene
from workbook_gen.workbook import write_workbook

SCENE = "templates/actuator_linkage.toml"
TOLERANCE = 1e-9  # of the column's magnitude
PAPER = {"x_A": 0.156, "y_A": 0.437, "x_B": 0.462, "y_B": 0.0, "l_A1": 1.237, "l_A1C": 0.325}


def _toml(value) -> str:
    return f'"{value}"' if isinstance(value, str) else repr(value)


def write_scene(tmp_path, name="act", parameters=None, options=None, sweep=None, outputs=None):
    """A scene file for the actuator linkage with the given sections."""
    lines = [f'name = "{name}"', 'mechanism = "actuator_linkage"', "[parameters]"]
    lines += [f"{k} = {_toml(v)}" for k, v in (parameters or {}).items()]
    if sweep:
        lines += ["[sweep]", f"start = {sweep[0]!r}", f"stop = {sweep[1]!r}", f"step = {sweep[2]!r}"]
    if outputs:
        lines += ["[outputs]", "quantities = [" + ", ".join(f'"{q}"' for q in outputs) + "]"]
    lines += ["[options]"] + [f"{k} = {_toml(v)}" for k, v in (options or {}).items()]
    path = tmp_path / f"{name}.toml"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def build(tmp_path, **sections):
    path = write_scene(tmp_path, **sections)
    scene = load_scene(path)
    return scene, write_workbook(scene, tmp_path)


CASES = {
    "paper, halving": {"options": {"method": "bisection", "halvings": 20}},
    "closed form only": {"options": {"method": "closed"}},
    "beyond the stroke": {"options": {"method": "bisection", "halvings": 60},
                          "sweep": (0.6, 1.95, 0.05)},
    "other pivots": {"parameters": {"x_B": -0.3, "y_B": 0.2, "l_A1": 0.8, "l_A1C": -0.1,
                                    "v_s": -0.2, "epsilon": 1e-9},
                     "options": {"method": "bisection", "halvings": 45},
                     "sweep": (0.7, 1.2, 0.05)},
}


@pytest.mark.parametrize("case", list(CASES))
def test_every_table_cell_matches_the_reference_model(tmp_path, case):
    scene, path = build(tmp_path, **CASES[case])
    cells = table_columns(path)
    inputs = as_float(cells.pop("s_BC"))
    status = np.array(cells.pop("status"))
    reference = solve("actuator_linkage", scene.parameters, inputs, scene.options)
    assembled = status != "cannot assemble"
    assert np.array_equal(assembled, np.isfinite(reference["phi_2"]))
    checked = 0
    for name, values in cells.items():
        error = column_error(name, as_float(values), reference[name])
        assert error <= TOLERANCE, f"{name}: {error:.3g} of its magnitude"
        checked += int(np.isfinite(reference[name]).sum())
    assert checked > 100


def test_sweep_has_eleven_rows_with_the_stop_value():
    scene = load_scene(SCENE)
    assert scene.sweep.values()[0] == 1.0 and scene.sweep.values()[-1] == 1.687
    assert len(scene.sweep.values()) == 11
    assert scene.template.length_unit_m == 1.0


def _lever_point(phi):
    p = PAPER
    return (p["x_A"] + p["l_A1"] * math.cos(phi) + p["l_A1C"] * math.sin(phi),
            p["y_A"] + p["l_A1"] * math.sin(phi) - p["l_A1C"] * math.cos(phi))


def _f(phi, s):
    cx, cy = _lever_point(phi)
    return (cx - PAPER["x_B"]) ** 2 + (cy - PAPER["y_B"]) ** 2 - s * s


def _df(phi):
    """f'(phi) = 2 (C - B) . dC/dphi."""
    cx, cy = _lever_point(phi)
    dx = -PAPER["l_A1"] * math.sin(phi) + PAPER["l_A1C"] * math.cos(phi)
    dy = PAPER["l_A1"] * math.cos(phi) + PAPER["l_A1C"] * math.sin(phi)
    return 2 * ((cx - PAPER["x_B"]) * dx + (cy - PAPER["y_B"]) * dy)


def _scalar_bisection(s, eps, n, lo=-1.5, hi=4.64):
    """The paper's rule, one row at a time: (accepted midpoint or None, halvings)."""
    f_lo = _f(lo, s)
    for k in range(1, n + 1):
        mid = (lo + hi) / 2
        fm = _f(mid, s)
        if abs(fm) < eps:
            return mid, k
        if f_lo * fm < 0:
            hi = mid
        else:
            lo = mid
    return None, n


@pytest.mark.parametrize("eps, halvings", [(1e-4, 20), (1e-7, 30), (1e-10, 60)])
def test_halving_lands_on_the_closed_form_within_what_epsilon_implies(tmp_path, eps, halvings):
    _, path = build(tmp_path, parameters={"epsilon": eps},
                    options={"method": "bisection", "halvings": halvings})
    cells = table_columns(path)
    groups = [n for n in cells if n.startswith("mid_")]
    assert len(groups) == halvings
    assert all(f"{c}_{k}" in cells for c in ("lo", "hi", "mid", "f") for k in (1, halvings))
    for s, phi, phi_iter, used, status in zip(cells["s_BC"], cells["phi_2"],
                                                cells["phi_2_iter"], cells["halvings_used"],
                                                cells["status"]):
        assert status == "ok"
        bound = eps / abs(_df(phi)) * 1.01 + 1e-14
        assert abs(phi_iter - phi) <= bound, (s, phi_iter, phi, bound)
        expected, k = _scalar_bisection(s, eps, halvings)
        assert used == k and phi_iter == pytest.approx(expected, abs=1e-13)
    # the tolerance is not vacuous: the paper's epsilon leaves a visible difference
    if eps == 1e-4:
        assert max(abs(a - b) for a, b in zip(cells["phi_2"], cells["phi_2_iter"])) > 1e-6


def test_a_row_stops_at_the_first_accepted_midpoint(tmp_path):
    _, path = build(tmp_path, options={"method": "bisection", "halvings": 20})
    cells = table_columns(path)
    for row in range(len(cells["s_BC"])):
        used = int(cells["halvings_used"][row])
        f = [cells[f"f_{k}"][row] for k in range(1, 21)]
        mids = [cells[f"mid_{k}"][row] for k in range(1, 21)]
        assert all(abs(v) >= 1e-4 for v in f[:used - 1]) and abs(f[used - 1]) < 1e-4
        assert all(m == mids[used - 1] for m in mids[used - 1:])   # carried unchanged
        assert cells["phi_2_iter"][row] == mids[used - 1]


def test_too_few_halvings_give_num_and_say_so(tmp_path):
    _, path = build(tmp_path, options={"method": "bisection", "halvings": 8})
    cells = table_columns(path)
    assert set(cells["phi_2_iter"]) == {"#NUM!"}
    assert set(cells["status"]) == {"not converged"}
    assert set(cells["halvings_used"]) == {8}
    assert all(isinstance(v, float) for v in cells["phi_2"])


def test_rows_beyond_the_stroke_cannot_be_assembled(tmp_path):
    _, path = build(tmp_path, options={"method": "bisection", "halvings": 60},
                    sweep=(0.6, 1.95, 0.05))
    cells = table_columns(path)
    a = math.hypot(PAPER["x_B"] - PAPER["x_A"], PAPER["y_B"] - PAPER["y_A"])
    r = math.hypot(PAPER["l_A1"], PAPER["l_A1C"])
    for s, status, phi, phi_iter in zip(cells["s_BC"], cells["status"], cells["phi_2"],
                                        cells["phi_2_iter"]):
        if not r - a <= s <= r + a:
            assert status == "cannot assemble" and phi == "#NUM!" and phi_iter == "#NUM!"
        else:
            assert status != "cannot assemble" and isinstance(phi, float)


def test_lever_branch_transmission_angle_and_dead_zone(tmp_path):
    """C right of A at the shortest cylinder, the lever rising; gamma from the law of
    cosines (math.acos, independent of the ATAN2 form); the flag against gamma_min."""
    _, path = build(tmp_path, options={"method": "closed"})
    cells = table_columns(path)
    a = math.hypot(PAPER["x_B"] - PAPER["x_A"], PAPER["y_B"] - PAPER["y_A"])
    r = math.hypot(PAPER["l_A1"], PAPER["l_A1C"])
    assert cells["x_C"][0] > PAPER["x_A"] and cells["y_C"][0] < PAPER["y_A"]
    assert np.all(np.diff(cells["phi_2"]) > 0) and np.all(np.diff(cells["phi_3"]) > 0)
    for s, g, flag in zip(cells["s_BC"], cells["gamma"], cells["below_gamma_min"]):
        assert g == pytest.approx(math.acos((r * r + s * s - a * a) / (2 * r * s)), abs=1e-12)
        assert flag == (1 if min(g, math.pi - g) < 0.35 else 0)
    assert cells["below_gamma_min"] == [0] * 8 + [1] * 3


def test_summary_gives_the_minimum_transmission_angle_and_where(tmp_path):
    _, path = build(tmp_path, options={"method": "closed"})
    rows = {r[0]: r for r in openpyxl.load_workbook(path, data_only=True)["Summary"]
            .iter_rows(values_only=True) if r[0]}
    assert rows["gamma"][4] == pytest.approx(min(table_columns(path)["gamma"]), abs=0)
    assert rows["gamma"][5] == 1.687
    assert rows["below_gamma_min"][2] == 1 and rows["below_gamma_min"][3] == 1.5496


def test_mirror_root_is_flagged_other_branch(tmp_path):
    _, path = build(tmp_path, **CASES["other pivots"])
    cells = table_columns(path)
    assert cells["status"][:3] == ["other branch"] * 3
    assert abs(cells["phi_2_iter"][0] - cells["phi_2"][0]) > 1


@pytest.mark.parametrize("options, key", [
    ({"method": "bisection", "halvings": 61}, "options.halvings"),
    ({"method": "newton"}, "options.method"),
])
def test_bad_options_are_refused(tmp_path, options, key):
    with pytest.raises(SceneError, match=key):
        load_scene(write_scene(tmp_path, options=options))


def test_iterative_columns_only_when_the_scene_asks(tmp_path):
    with pytest.raises(SceneError, match="phi_2_iter"):
        load_scene(write_scene(tmp_path, outputs=["phi_2_iter"], options={"method": "closed"}))
    _, path = build(tmp_path, options={"method": "closed"})
    assert not any(n.startswith(("mid_", "f_")) for n in table_columns(path))
    with pytest.raises(SceneError, match="phi_hi"):
        load_scene(write_scene(tmp_path, parameters={"phi_hi": -2.0}))


def test_default_scene_audits_clean(generate):
    from workbook_gen import audit
    report = audit(generate(SCENE))
    assert report.ok


@pytest.mark.parametrize("case", ["paper, halving", "beyond the stroke"])
def test_libreoffice_agrees_with_every_cached_value(libreoffice, tmp_path, case):
    _, path = build(tmp_path, **CASES[case])
    cells, worst = compare_with_libreoffice(path)
    assert cells > 500 and math.isfinite(worst)
