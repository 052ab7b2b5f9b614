"""Every template at its legal extremes audits clean (issue 12 item 3): what our own
formulas leave as rounding noise of their operands is not a disagreement, and rows
the workbook flags singular (dead centre, toggle) are not compared with the model."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from workbook_gen import audit, load_scene, write_workbook
from workbook_gen.auditor.mechanics import REFERENCE_TOLERANCE, _check_column
from workbook_gen.errors import SceneError

TEMPLATES = Path(__file__).resolve().parents[2] / "templates"

EXTREMES = [
    # (scene, parameter overrides): the repros first
    ("slider_crank", {"l_BC": 40.0, "e": 0.0}),           # rod = crank: dead centres, alpha_2 = 0
    ("slider_crank", {"l_AB": 1e-75}),                    # smallest legal crank
    ("slider_crank", {"l_BC": 1e20}),                     # rod 1e18 cranks long
    ("slider_crank", {"l_AB": 1e74, "l_BC": 2e74, "e": 0.0}),
    ("slider_crank", {"l_AB": 1e-75, "l_BC": 1e75}),
    ("slider_crank", {"l_BC": 50.0, "e": 10.0, "phi_slide": 90.0}),  # rod = crank + offset
    ("slider_crank", {"omega_1": 1e6}),
    ("slider_crank", {"phi_slide": 8.8e-249, "e": 1e-300}),  # tiny angle and offset
    ("sewing_machine", {"l_AB": 100.0, "l_BC": 10.0}),    # assembles only at 90 and 270 deg
    ("sewing_machine", {"l_BC": 32.0}),                   # rod = crank
    ("sewing_machine", {"l_AB": 1e-6}),                   # h_BC: the model cancels y_B - y_C
    ("sewing_machine", {"x_F": 1e-3, "y_F": -1e-3}),
    ("four_bar", {"l_O1O2": 100.0, "l_O1A": 40.0, "l_AB": 100.0, "l_O2B": 40.0}),  # change point
    ("four_bar", {"l_O1O2": 100.0, "l_O1A": 50.0, "l_AB": 80.0, "l_O2B": 70.0}),   # Grashof boundary
    ("four_bar", {"l_O1A": 1e-6}),
    ("four_bar", {"l_AC": 0.0, "delta_C": 0.0}),
    ("walking_beam", {"l_O1A": 1e-6}),
    ("walking_beam", {"l_O1O2": 40.0, "l_O1A": 20.0, "l_AB": 50.0, "l_O2B": 30.0}),  # boundary
    ("actuator_linkage", {"epsilon": 1e-12}),
    ("actuator_linkage", {"y_B": 1e-9}),
    ("five_bar", {"r_clear": 1e-12}),
    ("five_bar", {"R_path": 1e-9}),
]


@pytest.mark.parametrize("template, overrides", EXTREMES,
                         ids=[f"{t}-{'-'.join(f'{k}={v:g}' for k, v in o.items())}"
                              for t, o in EXTREMES])
def test_template_at_a_legal_extreme_audits_clean(tmp_path, template, overrides):
    scene = load_scene(TEMPLATES / f"{template}.toml", overrides=overrides)
    report = audit(write_workbook(scene, tmp_path))
    failing = [q for q in report.mechanics.quantities if not q.ok]
    assert not failing, [(q.name, q.max_error, q.worst_row_input) for q in failing]
    assert not report.mismatches, report.mismatches[:3]
    assert report.ok


@pytest.mark.parametrize("value", [5e-324, 1e-300, 1e300])
def test_lengths_without_relative_precision_are_refused(value):
    with pytest.raises(SceneError, match=r"parameters\.l_AB must be of magnitude 1e-75\.\."):
        load_scene(TEMPLATES / "slider_crank.toml", overrides={"l_AB": value})


def test_a_tiny_angle_or_offset_is_legal_and_a_huge_one_is_not():
    scene = load_scene(TEMPLATES / "slider_crank.toml",
                       overrides={"phi_slide": 8.8e-249, "e": 1e-300})
    assert scene.parameters["phi_slide"] == 8.8e-249
    with pytest.raises(SceneError, match=r"parameters\.e must be of magnitude at most 1e\+75"):
        load_scene(TEMPLATES / "slider_crank.toml", overrides={"e": -1e80})


def test_rounding_noise_of_the_operands_is_not_an_error():
    """alpha_2 of a rod as long as the crank is 0: 1e-13 against 0 from terms near 100."""
    rows = 5
    ref = np.zeros(rows)
    ours = np.array([1e-13, -2e-13, 0.0, 5e-14, 1e-13])
    inputs = np.arange(rows, dtype=float)
    flat = np.zeros(rows, dtype=bool)
    bare = _check_column("alpha_2", ours, ref, inputs, 13, flat, None, "rad/s^2")
    assert not bare.ok  # without the noise, 1e-13 over a column of zeros is a relative 1
    noisy = _check_column("alpha_2", ours, ref, inputs, 13, flat, np.full(rows, 400.0),
                          "rad/s^2")
    assert noisy.ok and noisy.max_error < REFERENCE_TOLERANCE
    wrong = ours.copy()
    wrong[2] = 1e-5  # a real error stays one, noise or not
    assert not _check_column("alpha_2", wrong, ref, inputs, 13, flat, np.full(rows, 400.0),
                             "rad/s^2").ok


def test_flagged_rows_are_counted_not_compared():
    ref = np.array([1.0, 2.0, 3.0])
    ours = np.array([1.0, 2.0 + 1e-7, 3.0])  # half the digits at a dead centre
    flagged = np.array([False, True, False])
    check = _check_column("h_BC", ours, ref, np.arange(3.0), 5, flagged, None, "mm")
    assert check.ok and check.flagged_rows == 1 and check.rows == 2
    assert not _check_column("h_BC", ours, ref, np.arange(3.0), 5, ~flagged & False,
                             None, "mm").ok


def test_extremes_of_a_column_zero_to_rounding_are_a_tie_and_libreoffice_agrees(
        libreoffice, tmp_path):
    """The shipped balanced four-bar (issue 12 item 4): the shaking force and the still
    centre of mass are rounding noise; their Summary extremes are a tie, not a row that
    depends on the engine's rounding, and the LibreOffice audit passes."""
    import openpyxl
    path = write_workbook(load_scene(TEMPLATES / "four_bar_balanced.toml"), tmp_path)
    summary = {row[0]: row for row in openpyxl.load_workbook(path, data_only=True)[
        "Summary"].iter_rows(values_only=True) if row[0]}
    for name in ("F_x", "F_y", "x_S", "y_S"):
        assert summary[name][3] == "tie" and summary[name][5] == "tie", summary[name]
    assert isinstance(summary["theta_4"][3], (int, float))  # a real extreme keeps its row
    report = audit(path, engine="libreoffice")
    assert report.ok, [m for m in report.engine.mismatches][:3] if report.engine else report
    unbalanced = write_workbook(load_scene(TEMPLATES / "four_bar_balanced.toml",
                                           overrides={"balance": False}, name="plain"),
                                tmp_path)
    plain = {row[0]: row for row in openpyxl.load_workbook(unbalanced, data_only=True)[
        "Summary"].iter_rows(values_only=True) if row[0]}
    assert isinstance(plain["F_x"][3], (int, float)) and isinstance(plain["F_x"][5], (int, float))
