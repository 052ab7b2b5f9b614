"""The independent reference solver against things independent of it.

Checks: closure residuals of the returned geometry, central differences of the positions,
a 50-digit mpmath solution (1-D root finding + mpmath numerical differentiation), published
facts of the slider-crank, branch and continuity, unassemblable and singular rows.
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from workbook_gen.errors import WorkbookGenError
from workbook_gen.reference import MECHANISMS, solve

SC = {"l_AB": 40.0, "l_BC": 120.0, "e": 10.0, "phi_slide": 0.0, "omega_1": 10.0}
SEW = {"l_AB": 32.0, "l_BC": 100.0, "l_BE": 28.0, "beta_E": 0.0, "x_F": -60.0, "y_F": -20.0,
       "l_FG": 90.0, "omega_1": 2 * math.pi}
GRID = np.arange(0.0, 361.0, 10.0)
FINE = np.linspace(0.0, 360.0, 3601)
ANGLES = [0.0, 90.0, 180.0, 270.0, 360.0, 37.0]


# ---------------------------------------------------------------- mpmath 50-digit model
def _mp_slider(p, t):
    """Slider-crank at time t (theta_1 = omega_1 t, rad): (s_C, theta_2 rad)."""
    phi = mp.radians(p["phi_slide"])
    th1 = p["_t0"] + p["omega_1"] * t
    bx, by = p["l_AB"] * mp.cos(th1), p["l_AB"] * mp.sin(th1)
    b_n = -bx * mp.sin(phi) + by * mp.cos(phi)
    b_u = bx * mp.cos(phi) + by * mp.sin(phi)
    # normal component of the closure: b_n + l_BC sin(theta_2 - phi) = e, slider ahead: |x| < pi/2
    x = mp.findroot(lambda x: b_n + p["l_BC"] * mp.sin(x) - p["e"], mp.mpf(0))
    assert mp.cos(x) > 0
    return b_u + p["l_BC"] * mp.cos(x), x + phi


def _mp_sewing(p, t):
    """Sewing machine at time t: dict of positions (mm, rad) at 50 digits."""
    th1 = p["_t0"] + p["omega_1"] * t
    bx, by = p["l_AB"] * mp.cos(th1), p["l_AB"] * mp.sin(th1)
    th2 = mp.findroot(lambda a: bx + p["l_BC"] * mp.cos(a), -mp.pi / 2)
    assert mp.sin(th2) < 0
    y_c = by + p["l_BC"] * mp.sin(th2)
    beta = mp.radians(p["beta_E"])
    ex = bx + p["l_BE"] * mp.cos(th2 + beta)
    ey = by + p["l_BE"] * mp.sin(th2 + beta)
    dx, dy = ex - p["x_F"], ey - p["y_F"]
    th_fa = mp.atan2(0 - mp.mpf(p["y_F"]), 0 - mp.mpf(p["x_F"]))
    # lever direction: (E - F) x (cos th5, sin th5) = 0, starting from the direction F->A
    th5 = mp.findroot(lambda a: dx * mp.sin(a) - dy * mp.cos(a), th_fa)
    s = dx * mp.cos(th5) + dy * mp.sin(th5)
    if s < 0:
        th5, s = th5 + mp.pi, -s
    return {
        "y_C": y_c, "theta_2": th2, "theta_5": th5, "s_FE": s, "x_E": ex, "y_E": ey,
        "x_G": p["x_F"] + p["l_FG"] * mp.cos(th5), "y_G": p["y_F"] + p["l_FG"] * mp.sin(th5),
        "h_BC": by - y_c, "x_B": bx, "y_B": by,
    }


def _diffs(f, p, theta_deg):
    """(value, d/dt, d2/dt2) of f(p, t) at theta_1 = theta_deg, by mpmath differentiation."""
    q = dict(p, _t0=mp.radians(mp.mpf(theta_deg)))
    return f(q, mp.mpf(0)), mp.diff(lambda t: f(q, t), 0, 1), mp.diff(lambda t: f(q, t), 0, 2)


def _close(got, want, scale, rel=1e-12):
    assert abs(got - float(want)) <= rel * scale, (got, float(want), scale)


def _angle_close(got_deg, want_rad):
    want = float(mp.degrees(want_rad))
    diff = (got_deg - want + 180.0) % 360.0 - 180.0
    assert abs(diff) <= 1e-12 * 360.0, (got_deg, want)


@pytest.mark.parametrize("params", [SC, dict(SC, e=-25.0, phi_slide=30.0, omega_1=-3.0),
                                    dict(SC, phi_slide=200.0, l_BC=55.0, e=5.0)])
def test_slider_crank_agrees_with_mpmath_50_digits(params):
    mp.mp.dps = 50
    got = solve("slider_crank", params, np.array(ANGLES))
    w, lsum = abs(params["omega_1"]), params["l_AB"] + params["l_BC"]
    for i, ang in enumerate(ANGLES):
        s = _diffs(lambda q, t: _mp_slider(q, t)[0], params, ang)
        th = _diffs(lambda q, t: _mp_slider(q, t)[1], params, ang)
        _close(got["s_C"][i], s[0], lsum)
        _close(got["v_C"][i], s[1], w * lsum)
        _close(got["a_C"][i], s[2], w * w * lsum)
        _angle_close(got["theta_2"][i], th[0])
        _close(got["omega_2"][i], th[1], w)
        _close(got["alpha_2"][i], th[2], w * w)


@pytest.mark.parametrize("params", [SEW, dict(SEW, beta_E=15.0, x_F=60.0, omega_1=-5.0),
                                    dict(SEW, l_BC=40.0, y_F=0.0)])
def test_sewing_machine_agrees_with_mpmath_50_digits(params):
    mp.mp.dps = 50
    got = solve("sewing_machine", params, np.array(ANGLES))
    w = abs(params["omega_1"])
    lsum = params["l_AB"] + params["l_BC"] + params["l_FG"] + abs(params["x_F"])
    rate_names = {"y_C": ("v_C", "a_C"), "s_FE": ("v_FE", "a_FE"), "x_G": ("vx_G", "ax_G"),
                  "y_G": ("vy_G", "ay_G"), "x_E": ("vx_E", "ax_E"), "y_E": ("vy_E", "ay_E"),
                  "h_BC": ("dh_BC", "ddh_BC"), "x_B": (None, None), "y_B": (None, None),
                  "theta_2": ("omega_2", "alpha_2"), "theta_5": ("omega_5", "alpha_5")}
    for i, ang in enumerate(ANGLES):
        for name, (rate, acc) in rate_names.items():
            val, d1, d2 = _diffs(lambda q, t: _mp_sewing(q, t)[name], params, ang)
            unit = 1.0 if name.startswith("theta") else lsum
            if name.startswith("theta"):
                _angle_close(got[name][i], val)
            else:
                _close(got[name][i], val, unit)
            if rate:
                _close(got[rate][i], d1, w * unit)
                _close(got[acc][i], d2, w * w * unit)


# ---------------------------------------------------------------- geometry and closure
def test_slider_crank_closure_residual_and_branch():
    p = dict(SC, phi_slide=25.0, e=-12.0)
    r = solve("slider_crank", p, FINE)
    t, phi = np.radians(FINE), np.radians(p["phi_slide"])
    u, n = np.array([np.cos(phi), np.sin(phi)]), np.array([-np.sin(phi), np.cos(phi)])
    b = p["l_AB"] * np.stack([np.cos(t), np.sin(t)], axis=1)
    c = r["s_C"][:, None] * u + p["e"] * n
    assert np.max(np.abs(np.linalg.norm(c - b, axis=1) - p["l_BC"])) < 1e-12 * p["l_BC"]
    assert np.all((c - b) @ u > 0)
    th2 = np.radians(r["theta_2"])
    rod = p["l_BC"] * np.stack([np.cos(th2), np.sin(th2)], axis=1)
    assert np.max(np.abs(b + rod - c)) < 1e-12 * p["l_BC"]
    assert np.all(np.abs(r["theta_2"] - p["phi_slide"]) < 90.0)


@pytest.mark.parametrize("params", [SEW, dict(SEW, x_F=60.0, beta_E=-20.0)])
def test_sewing_machine_closure_residuals(params):
    r = solve("sewing_machine", params, FINE)
    t = np.radians(FINE)
    bx, by = params["l_AB"] * np.cos(t), params["l_AB"] * np.sin(t)
    tol = 1e-12 * 200.0
    assert np.max(np.abs(np.hypot(bx, by - r["y_C"]) - params["l_BC"])) < tol
    assert np.all(r["y_C"] < by)
    assert np.max(np.abs(np.hypot(r["x_E"] - bx, r["y_E"] - by) - params["l_BE"])) < tol
    # E is on the line F->G, at s_FE from F, on G's side
    fe = np.stack([r["x_E"] - params["x_F"], r["y_E"] - params["y_F"]], axis=1)
    fg = np.stack([r["x_G"] - params["x_F"], r["y_G"] - params["y_F"]], axis=1)
    assert np.max(np.abs(np.linalg.norm(fg, axis=1) - params["l_FG"])) < tol
    assert np.max(np.abs(fe - r["s_FE"][:, None] * fg / params["l_FG"])) < tol
    assert np.all(r["s_FE"] > 0)
    assert np.max(np.abs(r["h_BC"] - (by - r["y_C"]))) < tol


# ---------------------------------------------------------------- rates by finite differences
def _check_rates(pos, vel, acc, omega, step_deg, rel=1e-4):
    dt = math.radians(step_deg) / omega
    v_fd = (pos[2:] - pos[:-2]) / (2 * dt)
    a_fd = (pos[2:] - 2 * pos[1:-1] + pos[:-2]) / dt**2
    assert np.max(np.abs(v_fd - vel[1:-1])) <= rel * np.max(np.abs(vel))
    assert np.max(np.abs(a_fd - acc[1:-1])) <= rel * np.max(np.abs(acc))


def test_slider_crank_rates_match_central_differences():
    r = solve("slider_crank", SC, FINE)
    _check_rates(r["s_C"], r["v_C"], r["a_C"], SC["omega_1"], 0.1)
    _check_rates(np.radians(r["theta_2"]), r["omega_2"], r["alpha_2"], SC["omega_1"], 0.1)


def test_sewing_machine_rates_match_central_differences():
    p = dict(SEW, beta_E=10.0)
    r = solve("sewing_machine", p, FINE)
    w = p["omega_1"]
    for pos, vel, acc in [("y_C", "v_C", "a_C"), ("s_FE", "v_FE", "a_FE"), ("x_G", "vx_G", "ax_G"),
                          ("y_G", "vy_G", "ay_G"), ("x_E", "vx_E", "ax_E"), ("y_E", "vy_E", "ay_E"),
                          ("h_BC", "dh_BC", "ddh_BC")]:
        _check_rates(r[pos], r[vel], r[acc], w, 0.1)
    for ang, vel, acc in [("theta_5", "omega_5", "alpha_5"), ("theta_2", "omega_2", "alpha_2")]:
        _check_rates(np.unwrap(np.radians(r[ang])), r[vel], r[acc], w, 0.1)


# ---------------------------------------------------------------- published facts
def test_centred_slider_crank_textbook_values():
    r_, l_, w = 40.0, 120.0, 10.0
    p = dict(SC, e=0.0, l_AB=r_, l_BC=l_)
    r = solve("slider_crank", p, np.array([0.0, 90.0, 180.0]))
    assert r["s_C"][0] - r["s_C"][2] == pytest.approx(2 * r_, rel=1e-15)  # stroke = 2 l_AB
    assert r["s_C"][0] == pytest.approx(r_ + l_, rel=1e-15)
    assert r["v_C"][1] == pytest.approx(-w * r_, rel=1e-13)
    assert r["a_C"][0] == pytest.approx(-w * w * r_ * (1 + r_ / l_), rel=1e-13)
    assert r["a_C"][1] == pytest.approx(w * w * r_**2 / math.sqrt(l_**2 - r_**2), rel=1e-13)
    assert r["omega_2"][0] == pytest.approx(-w * r_ / l_, rel=1e-13)
    assert abs(r["theta_2"][0]) < 1e-13


def test_needle_stroke_and_top_position():
    r = solve("sewing_machine", SEW, GRID)
    assert r["y_C"][GRID == 90.0][0] == pytest.approx(SEW["l_AB"] - SEW["l_BC"], rel=1e-15)
    assert r["y_C"][GRID == 270.0][0] == pytest.approx(-SEW["l_AB"] - SEW["l_BC"], rel=1e-15)
    assert np.max(r["y_C"]) - np.min(r["y_C"]) == pytest.approx(2 * SEW["l_AB"], rel=1e-14)
    assert abs(r["v_C"][GRID == 90.0][0]) < 1e-12 * SEW["l_AB"] * SEW["omega_1"]


# ---------------------------------------------------------------- branches and continuity
@pytest.mark.parametrize("x_f", [-60.0, 60.0])
def test_lever_angle_continuous_across_180(x_f):
    p = dict(SEW, x_F=x_f)
    r = solve("sewing_machine", p, FINE)
    th5 = r["theta_5"]
    assert np.max(np.abs(np.diff(th5))) < 1.0
    th_fa = math.degrees(math.atan2(-p["y_F"], -x_f))
    assert np.all((th5 > th_fa - 180.0) & (th5 <= th_fa + 180.0))
    if x_f > 0:
        assert np.min(th5) < 180.0 < np.max(th5)  # the sweep does cross 180 deg


def test_slider_rod_angle_continuous_and_in_range():
    p = dict(SC, phi_slide=170.0, e=30.0)
    th2 = solve("slider_crank", p, FINE)["theta_2"]
    assert np.max(np.abs(np.diff(th2))) < 1.0
    assert np.all((th2 > 80.0) & (th2 < 260.0))


@settings(max_examples=40, deadline=None)
@given(l_ab=st.floats(1.0, 100.0), ratio=st.floats(1.01, 20.0), ecc=st.floats(-0.99, 0.99),
       phi=st.floats(-360.0, 360.0))
def test_random_slider_cranks_close_without_branch_jump(l_ab, ratio, ecc, phi):
    l_bc = l_ab * ratio
    e = ecc * (l_bc - l_ab)
    p = {"l_AB": l_ab, "l_BC": l_bc, "e": e, "phi_slide": phi, "omega_1": 1.0}
    r = solve("slider_crank", p, FINE)
    assert np.all(np.isfinite(r["a_C"]))
    th2, t = np.radians(r["theta_2"]), np.radians(FINE)
    n = np.array([-math.sin(math.radians(phi)), math.cos(math.radians(phi))])
    # the rod end reaches the slide line: normal component of B + rod equals e
    reach = l_ab * (np.cos(t) * n[0] + np.sin(t) * n[1]) + l_bc * (np.cos(th2) * n[0] + np.sin(th2) * n[1])
    assert np.max(np.abs(reach - e)) < 1e-11 * (l_ab + l_bc)
    assert np.max(np.abs(np.diff(r["theta_2"]))) < 90.0 * 0.1 * ratio  # no jump to the mirror branch
    assert np.all(np.cos(th2 - math.radians(phi)) > 0)


# ---------------------------------------------------------------- unassemblable and singular rows
def test_rod_shorter_than_crank_gives_nan_rows():
    p = dict(SEW, l_BC=20.0)
    r = solve("sewing_machine", p, FINE)
    x_b = p["l_AB"] * np.cos(np.radians(FINE))
    cannot = np.abs(x_b) > p["l_BC"]
    assert cannot.any() and (~cannot).any()
    for name, values in r.items():
        if name.removesuffix("~noise") in ("theta_1r", "lm_BC", "lp_BC"):  # defined anyway
            continue
        assert np.all(np.isnan(values[cannot])), name
        assert np.all(np.isfinite(values[~cannot & (np.abs(np.abs(x_b) - p["l_BC"]) > 1e-3)])), name
    ok = ~cannot
    assert np.max(np.abs(np.hypot(x_b[ok], p["l_AB"] * np.sin(np.radians(FINE[ok])) - r["y_C"][ok])
                         - p["l_BC"])) < 1e-12 * 100


def test_rod_horizontal_is_singular_but_placed():
    p = dict(SEW, l_BC=32.0)  # at theta_1 = 0 the rod is horizontal: C = A, needle speed undefined
    r = solve("sewing_machine", p, np.array([0.0, 45.0]))
    assert r["y_C"][0] == pytest.approx(0.0, abs=1e-6)
    assert r["x_B"][0] == 32.0
    for name in ("v_C", "a_C", "omega_2", "alpha_5", "vx_G", "ddh_BC"):
        assert np.isnan(r[name][0]) and np.isfinite(r[name][1]), name


def test_slider_crank_that_never_assembles_is_all_nan():
    r = solve("slider_crank", dict(SC, l_BC=20.0, e=100.0), GRID)
    assert all(np.all(np.isnan(v)) for name, v in r.items() if name != "psi")  # psi: the input


# ---------------------------------------------------------------- API
def test_all_documented_outputs_returned_with_row_shape():
    assert set(MECHANISMS) >= {"slider_crank", "sewing_machine"}
    want = {"slider_crank": {"s_C", "v_C", "a_C", "theta_2", "omega_2", "alpha_2", "u_B", "n_B", "f_BC", "g_BC", "h_BC", "dh_BC", "ddh_BC", "psi"},
            "sewing_machine": {"y_C", "v_C", "a_C", "theta_5", "omega_5", "alpha_5", "s_FE", "v_FE", "a_FE",
                               "x_G", "y_G", "vx_G", "vy_G", "ax_G", "ay_G", "x_B", "y_B", "h_BC", "dh_BC",
                               "ddh_BC", "x_E", "y_E", "vx_E", "vy_E", "ax_E", "ay_E", "theta_2", "omega_2",
                               "alpha_2", "theta_1r", "lm_BC", "lp_BC", "hr_BC", "sr_FE"}}
    for mech, names in want.items():
        r = solve(mech, {}, GRID)
        # "<q>~noise": the rounding noise the model's own formula for q cancels (auditor/noise.py)
        noise = {k for k in r if k.endswith("~noise")}
        assert set(r) - noise == names
        assert {k.removesuffix("~noise") for k in noise} <= names
        assert all(v.shape == GRID.shape and np.all(np.isfinite(v)) for v in r.values())
        assert all(np.all(r[k] >= 0) for k in noise)


@pytest.mark.parametrize("mech, params", [("four_bar_typo", {}), ("slider_crank", {"l_Ab": 3.0}),
                                          ("slider_crank", {"l_BC": -1.0}),
                                          ("sewing_machine", {"x_F": float("nan")})])
def test_bad_requests_raise(mech, params):
    with pytest.raises(WorkbookGenError):
        solve(mech, params, GRID)
