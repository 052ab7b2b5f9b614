"""walking_beam template (docs/mechanisms.md, walking_beam): every Table cell against the
independent reference (the eight-bar's closure solved by Newton: the four-bar, the parallelogram
copy and the beam), the beam's translation, Hoekens' straight line, the audit and LibreOffice."""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbook_gen.reference import solve
from workbook_gen.scene import load_scene
from workbook_cells import as_float, column_error, table_columns

TOLERANCE = 1e-9  # of the column's magnitude
SCENE = "templates/walking_beam.toml"
ALWAYS_DEFINED = {"theta_2r", "x_A", "y_A", "d_AO2", "phi_AO2", "f_B"}


@pytest.fixture(scope="module")
def crossed(tmp_path_factory):
    path = tmp_path_factory.mktemp("scenes") / "walking_beam_crossed.toml"
    text = open(SCENE, encoding="utf-8").read()
    path.write_text(text.replace('branch = "open"', 'branch = "crossed"'), encoding="utf-8")
    return str(path)


def _reference(path, scene_path, overrides, step):
    scene = load_scene(scene_path, overrides=overrides, step=step)
    cells = table_columns(path)
    inputs = as_float(cells.pop("theta_2"))
    status = np.array(cells.pop("status"))
    return scene, cells, status, solve("walking_beam", scene.parameters, inputs, scene.options)


CASES = [
    (False, {}, None),
    (False, {}, 1.0),
    (True, {}, 5.0),
    (False, {"l_CD": 75.0, "delta_C": 12.0, "l_AC": 80.0, "omega_2": -4.0}, 3.0),
    (False, {"l_O1A": 30.0}, 5.0),  # a crank too long for part of the turn: #NUM! rows
]


@pytest.mark.parametrize("use_crossed, overrides, step", CASES)
def test_every_table_cell_matches_the_reference(generate, crossed, use_crossed, overrides,
                                                step):
    scene_path = crossed if use_crossed else SCENE
    path = generate(scene_path, overrides=overrides, step=step)
    _, cells, status, reference = _reference(path, scene_path, overrides, step)
    assembled = status != "cannot assemble"
    assert np.array_equal(assembled, np.isfinite(reference["x_D"]))
    assert "toggle" not in status
    for name, values in cells.items():
        error = column_error(name, as_float(values), reference[name], assembled, ALWAYS_DEFINED)
        assert error <= TOLERANCE, f"{name}: {error:.3g} of its magnitude"


@pytest.mark.parametrize("use_crossed", [False, True])
def test_the_beam_keeps_its_orientation(generate, crossed, use_crossed):
    """In the workbook D - C = (l_CD, 0) in every row; in the reference's eight-bar the
    beam found by Newton from a tilted, stretched guess has angle 0, no angular velocity
    or acceleration, and length l_CD."""
    scene_path = crossed if use_crossed else SCENE
    path = generate(scene_path, step=2.0)
    scene, cells, status, ref = _reference(path, scene_path, {}, 2.0)
    l_cd = scene.parameters["l_CD"]
    dx = as_float(cells["x_D"]) - as_float(cells["x_C"])
    dy = as_float(cells["y_D"]) - as_float(cells["y_C"])
    assert np.all(np.abs(dx - l_cd) <= 1e-12 * l_cd) and np.all(dy == 0.0)
    assert np.nanmax(np.abs(ref["theta_7"])) < 1e-10
    assert np.nanmax(np.abs(ref["omega_7"])) < 1e-10
    assert np.nanmax(np.abs(ref["alpha_7"])) < 1e-9
    assert np.nanmax(np.abs(ref["l_beam"] - l_cd)) < 1e-10 * l_cd
    assert np.all(np.isfinite(ref["theta_7"]))


def test_hoekens_flat_stroke(generate):
    """Hoekens' linkage (1 : 2.5 : 2.5 : 2, point at 5 on A->B extended), scaled by 20 mm:
    C passes through (80, 80), (40, 80), (0, 80) mm at crank angles 90, 180, 270 deg and
    stays within 0.2 mm of y = 80 mm in between (the flat stroke)."""
    cells = table_columns(generate(SCENE, step=5.0))
    theta = as_float(cells["theta_2"])
    x, y = as_float(cells["x_C"]), as_float(cells["y_C"])
    for angle, expected in ((90.0, 80.0), (180.0, 40.0), (270.0, 0.0)):
        i = int(np.flatnonzero(theta == angle)[0])
        assert x[i] == pytest.approx(expected, abs=1e-9)
        assert y[i] == pytest.approx(80.0, abs=1e-9)
    flat = (theta >= 90.0) & (theta <= 270.0)
    assert np.max(np.abs(y[flat] - 80.0)) < 0.2
    assert np.max(y) - 80.0 > 15.0  # the beam lifts on the return


def test_audit_is_clean(generate):
    from workbook_gen import audit
    report = audit(generate(SCENE))
    assert report.ok and not report.mismatches


def _tied_positions(path) -> dict[str, set[float]]:
    """Summary 'at' cells whose extreme the Table holds, to 1e-12, at more than one row
    (Hoekens' coupler curve is symmetric): which row MATCH finds then depends on the
    last bit each engine computes, so any of the tied inputs is right."""
    import openpyxl
    book = openpyxl.load_workbook(path, data_only=True)
    table = table_columns(path)
    inputs = as_float(table["theta_2"])
    tied = {}
    for row in book["Summary"].iter_rows(min_row=2):
        name = row[0].value
        if name not in table or not isinstance(row[2].value, float):
            continue
        values = as_float(table[name])
        scale = np.max(np.abs(values))
        for value_cell, at_cell in ((row[2], row[3]), (row[4], row[5])):
            near = np.abs(values - value_cell.value) <= 1e-12 * scale
            if near.sum() > 1:
                tied[at_cell.coordinate] = set(inputs[near].tolist())
    return tied


@pytest.mark.parametrize("options", [{}, {"overrides": {"l_O1A": 30.0}, "step": 5.0}])
def test_libreoffice_agrees_with_every_cached_value(libreoffice, generate, options,
                                                    monkeypatch):
    """As tests/engines/test_libreoffice_recalc.py, with tied Summary positions accepted when
    LibreOffice names another of the tied inputs."""
    from tests.engines import test_libreoffice_recalc as recalc
    path = generate(SCENE, **options)
    tied = _tied_positions(path)
    theirs = recalc.recalculated_values(path)
    for ref, inputs in tied.items():
        assert theirs["Summary"][ref] in inputs, ref
    ours = recalc.read_formula_values(path)
    for ref in tied:
        theirs["Summary"][ref] = ours["Summary"][ref]
    monkeypatch.setattr(recalc, "recalculated_values", lambda _path: theirs)
    cells, worst = recalc.compare_with_libreoffice(path)
    assert cells > 100 and math.isfinite(worst)
