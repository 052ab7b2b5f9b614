"""Five-bar joint clearance by component (issue 12 item 13, docs/mechanisms.md, five_bar): dx_C,
dy_C of each joint and direction against a 50-digit circle-circle intersection, the issue's sign
convention, and the extremes over a 0.1 deg sweep (what the paper's Table 2 prints)."""

from __future__ import annotations

from pathlib import Path

import mpmath as mp
import numpy as np
import pytest

from workbook_gen.tabulate import compute
from workbook_gen.scene import load_scene

SCENE = Path(__file__).resolve().parents[2] / "templates" / "five_bar.toml"
JOINTS, ANGLES = "ABCDE", (0, 90, 180, 270)
mp.mp.dps = 50


def _mp_displacement(p, phi_deg, joint: str, alpha: int) -> tuple[mp.mpf, mp.mpf]:
    """C' - C at 50 digits: inputs held, the issue's convention, same assembly mode."""
    phi = mp.radians(phi_deg)
    cx, cy = p["x_0"] + p["R_path"] * mp.cos(phi), p["y_0"] + p["R_path"] * mp.sin(phi)

    def elbow(px, l_a, l_b, left: bool):
        """Crank pin of the dyad pivot (px, 0) -> C with the elbow left/right of pivot->C."""
        dx, dy = cx - px, cy
        d = mp.sqrt(dx ** 2 + dy ** 2)
        a = (l_a ** 2 - l_b ** 2 + d ** 2) / (2 * d)
        h = mp.sqrt(l_a ** 2 - a ** 2)
        s = 1 if left else -1
        return px + a * dx / d - s * h * dy / d, a * dy / d + s * h * dx / d

    bx, by = elbow(mp.mpf(0), p["l_1"], p["l_2"], True)
    dx_, dy_ = elbow(p["l_5"], p["l_4"], p["l_3"], False)
    r = p["r_clear"]
    u = {0: (1, 0), 90: (0, 1), 180: (-1, 0), 270: (0, -1)}[alpha]
    sign = {"A": 1, "B": -1, "C": -1, "D": -1, "E": 1}[joint]
    if joint in "AB":
        bx, by = bx + sign * r * u[0], by + sign * r * u[1]
    else:
        dx_, dy_ = dx_ + sign * r * u[0], dy_ + sign * r * u[1]
    # circle (B', l_2) and circle (D', l_3): the intersection on C's side of B'D'
    gx, gy = dx_ - bx, dy_ - by
    g = mp.sqrt(gx ** 2 + gy ** 2)
    a = (p["l_2"] ** 2 - p["l_3"] ** 2 + g ** 2) / (2 * g)
    h = mp.sqrt(p["l_2"] ** 2 - a ** 2)
    side = mp.sign(gx * (cy - by) - gy * (cx - bx))
    x = bx + a * gx / g - side * h * gy / g
    y = by + a * gy / g + side * h * gx / g
    return x - cx, y - cy


@pytest.fixture(scope="module")
def fine():
    """The shipped scene at a 0.1 deg step: 3601 rows."""
    scene = load_scene(SCENE, step=0.1)
    table = compute(scene)
    params = {k: mp.mpf(repr(v)) for k, v in scene.parameters.items()}
    return scene, table, params


def _column(table, name: str) -> np.ndarray:
    return table[f"{name} [m]"].to_numpy(dtype=float)


def test_signed_components_match_a_50_digit_circle_intersection(fine):
    _, table, p = fine
    phis = table["phi [deg]"].to_numpy()
    r = float(p["r_clear"])
    worst = 0.0
    for i in range(0, len(phis), 173):  # 21 rows spread over the sweep
        for joint in JOINTS:
            for alpha in ANGLES:
                ex, ey = _mp_displacement(p, mp.mpf(repr(float(phis[i]))), joint, alpha)
                for axis, want in (("x", ex), ("y", ey)):
                    got = _column(table, f"d{axis}_C_{joint}_{alpha}")[i]
                    worst = max(worst, abs(got - float(want)) / r)
    assert worst < 1e-9, worst


def test_extremes_over_a_tenth_degree_sweep_match_50_digits(fine):
    """Table 2's min and max of dx_C, dy_C per joint: each extreme of the 0.1 deg table
    equals the 50-digit value at that row to far more digits than the paper prints."""
    _, table, p = fine
    phis = table["phi [deg]"].to_numpy()
    r = float(p["r_clear"])
    for joint in JOINTS:
        for axis in "xy":
            for alpha in ANGLES:
                column = _column(table, f"d{axis}_C_{joint}_{alpha}")
                for i in (int(np.argmin(column)), int(np.argmax(column))):
                    ex, ey = _mp_displacement(p, mp.mpf(repr(float(phis[i]))), joint, alpha)
                    want = float(ex if axis == "x" else ey)
                    assert abs(column[i] - want) <= 1e-9 * r, (joint, axis, alpha, phis[i])


def test_sign_convention_of_the_issue(fine):
    """B at alpha is A at alpha + 180 (B moves by -r u), C equals D (D moves by -r u), E at
    alpha is D at alpha + 180; and the magnitude is the components' length."""
    _, table, _ = fine
    for axis in "xy":
        for alpha in ANGLES:
            turned = (alpha + 180) % 360
            a, b = _column(table, f"d{axis}_C_A_{turned}"), _column(table, f"d{axis}_C_B_{alpha}")
            np.testing.assert_array_equal(a, b)
            c, d = _column(table, f"d{axis}_C_C_{alpha}"), _column(table, f"d{axis}_C_D_{alpha}")
            np.testing.assert_array_equal(c, d)
            e, d2 = _column(table, f"d{axis}_C_E_{alpha}"), _column(table, f"d{axis}_C_D_{turned}")
            np.testing.assert_array_equal(e, d2)
    for joint in JOINTS:
        for alpha in ANGLES:
            x, y = (_column(table, f"d{ax}_C_{joint}_{alpha}") for ax in "xy")
            np.testing.assert_allclose(np.hypot(x, y), _column(table, f"dC_{joint}_{alpha}"),
                                       rtol=1e-12)


def test_joint_a_at_zero_moves_c_like_the_linearised_sensitivity(fine):
    """An independent first-order check of the sign: B moved by +r along x moves C by
    -A^-1 (dF/dB) r e_x, from the closure |C - B|^2 = l_2^2, |C - D|^2 = l_3^2."""
    _, table, p = fine
    r = float(p["r_clear"])
    i = 900  # phi = 90 deg
    ex, ey = _mp_displacement(p, mp.mpf(90), "A", 0)
    # a second, different displacement (r/1000) scaled up must agree to first order
    small = {k: (v / 1000 if k == "r_clear" else v) for k, v in p.items()}
    sx, sy = _mp_displacement(small, mp.mpf(90), "A", 0)
    assert abs(float(sx) * 1000 - float(ex)) < 1e-3 * r
    assert abs(float(sy) * 1000 - float(ey)) < 1e-3 * r
    assert _column(table, "dx_C_A_0")[i] == pytest.approx(float(ex), abs=1e-9 * r)
