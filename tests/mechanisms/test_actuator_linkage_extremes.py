"""docs/stability.md, Numerical soundness at the extremes, for actuator_linkage (assembly limits,
the halving bracket's ends) and five_bar (paths touching the edge of the workspace), against
50-digit mpmath; and one extreme workbook (a change-point four-bar) through the audit, LibreOffice
and the Summary count."""

from __future__ import annotations

import math

import openpyxl
import pytest

from extremes_common import EXACT, assert_sound, near
from mp_reference import measure

P = dict(x_A=0.156, y_A=0.437, x_B=0.462, y_B=0.0, l_A1=1.237, l_A1C=0.325)
AB = math.hypot(P["x_B"] - P["x_A"], P["y_B"] - P["y_A"])
AC = math.hypot(P["l_A1"], P["l_A1C"])


@pytest.mark.parametrize("rel", [1e-12, 1e-9, 1e-7, 1e-6, 1e-3])
def test_actuator_near_both_assembly_limits(rel):
    lo, hi = AC - AB, AC + AB
    inputs = [lo * (1 + rel), lo * (1 + 10 * rel), 1.0, 1.3, hi * (1 - 10 * rel), hi * (1 - rel)]
    worst, status = assert_sound("actuator_linkage", {}, inputs)
    if rel < 1e-8:   # within rounding of AB and AC of a limit: flagged
        assert status[0] == "dead centre" and status[-1] == "dead centre"


def _lever_point(phi):
    return (P["x_A"] + P["l_A1"] * math.cos(phi) + P["l_A1C"] * math.sin(phi),
            P["y_A"] + P["l_A1"] * math.sin(phi) - P["l_A1C"] * math.cos(phi))


@pytest.mark.parametrize("root", [-1.5, -1.5 + 1e-9, -1.5 + 1e-4, 4.64, 4.64 - 1e-9, 4.64 - 1e-4])
def test_halving_with_the_root_at_a_bracket_end(root):
    """s_BC chosen so that f has a root at (or a hair inside) phi_lo / phi_hi: the halving
    column agrees with the same rule run at 50 digits, or the row says why not."""
    cx, cy = _lever_point(root)
    s = math.hypot(cx - P["x_B"], cy - P["y_B"])
    options = {"method": "bisection", "halvings": 40}
    worst, unflagged, status = measure("actuator_linkage", {}, [s, 1.0, 1.687], options)
    assert worst["phi_2_iter"][0] <= 1e-12 and worst["phi_2"][0] <= 1e-12
    assert set(status) <= {"ok", "not converged", "other branch"}


@pytest.mark.parametrize("short", [0.0, 1e-12, 1e-9, 1e-6])
def test_five_bar_path_touching_the_workspace_edge(short):
    """R_path such that |AC| (and |EC|) reach l_1 + l_2 at one phi: the path touches the
    edge of both dyads' workspaces (default centre, |centre| = sqrt(3.2))."""
    centre = math.hypot(0.8, 1.6)
    touch_a = math.degrees(math.atan2(1.6, 0.8))
    touch_e = math.degrees(math.atan2(1.6, -0.8))
    inputs = sorted(set(near(touch_a) + near(touch_e) + EXACT))
    assert_sound("five_bar", dict(R_path=(2.2 - centre) * (1 - short)), inputs)


def test_five_bar_newton_at_exact_angles():
    assert_sound("five_bar", {}, EXACT + [45.0, 135.0], {"method": "newton", "iterations": 8})


def test_change_point_workbook_counts_flagged_rows_and_audits(tmp_path, libreoffice):
    from tests.engines.test_libreoffice_recalc import compare_with_libreoffice
    from workbook_gen import audit
    from workbook_gen.scene import parse_scene
    from workbook_gen.workbook import write_workbook

    text = ('name = "change_point"\nmechanism = "four_bar"\n[parameters]\nl_O1O2 = 100.0\n'
            'l_O1A = 50.0\nl_AB = 80.0\nl_O2B = 70.0\n[sweep]\nstart = 0.0\nstop = 360.0\n'
            'step = 5.0\n')
    scene = parse_scene(text, "change_point.toml")
    path = write_workbook(scene, tmp_path)
    report = audit(path)
    assert report.ok and report.mechanics.flagged == {"toggle": 1}
    book = openpyxl.load_workbook(path, data_only=True)
    rows = {r[0]: r[2] for r in book["Summary"].iter_rows(values_only=True) if r[0]}
    assert rows["rows flagged singular or not converged"] == 1
    cells, worst = compare_with_libreoffice(path)
    assert cells > 1000 and worst <= 1e-9
