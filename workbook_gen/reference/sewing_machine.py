"""Reference solution of the sewing machine (docs/mechanisms.md, sewing_machine).

Two stages, each solved by Newton on its closure equations:
1. needle bar: q = (y_C, theta_2) with B + l_BC*(cos theta_2, sin theta_2) = (0, y_C);
   branch C below B (sin theta_2 < 0).
2. take-up lever: q = (theta_5, s_FE) with F + s_FE*(cos theta_5, sin theta_5) = E, where
   E = B + l_BE*(cos(theta_2 + beta_E), sin(theta_2 + beta_E)); branch s_FE > 0, and theta_5
   reported within 180 deg of the direction F->A.
"""

from __future__ import annotations

import math
from typing import Mapping

import mpmath
import numpy as np

from .newton import NOISE, Jet, jcos, jsin, solve_stage, wrap_deg

DEFAULTS = {
    "l_AB": 32.0, "l_BC": 100.0, "l_BE": 28.0, "beta_E": 0.0,
    "x_F": -60.0, "y_F": -20.0, "l_FG": 90.0, "omega_1": 2.0 * math.pi,
}
LENGTHS = ("l_AB", "l_BC")
# The rod within this fraction of l_BC of horizontal (|l_BC - |x_B|| small): a dead centre
# or reach limit near, where Newton in floats stops about sqrt(eps) from the double root
# and the float angle's rounding is a square-rooted error; those rows are solved at 50
# digits from the crank angle in degrees (``_near_dead_centre``).
NEAR_DEAD_CENTRE = 1e-4
DEAD = mpmath.mpf(10) ** -25   # h below this fraction of l_BC at 50 digits: singular
OUTPUTS = (
    "y_C", "v_C", "a_C", "theta_5", "omega_5", "alpha_5", "s_FE", "v_FE", "a_FE",
    "x_G", "y_G", "vx_G", "vy_G", "ax_G", "ay_G",
    "x_B", "y_B", "h_BC", "dh_BC", "ddh_BC", "x_E", "y_E", "vx_E", "vy_E", "ax_E", "ay_E",
    "theta_2", "omega_2", "alpha_2", "lm_BC", "lp_BC", "hr_BC", "sr_FE",
)


def _needle_closure(l_ab: float, l_bc: float):
    def closure(q, d):
        y_c, th2 = q
        (t1,) = d
        return (l_ab * jcos(t1) + l_bc * jcos(th2), l_ab * jsin(t1) + l_bc * jsin(th2) - y_c)

    return closure


def _lever_closure(x_f: float, y_f: float):
    def closure(q, d):
        th5, s = q
        x_e, y_e = d
        return (s * jcos(th5) + x_f - x_e, s * jsin(th5) + y_f - y_e)

    return closure


def _mask(jet: Jet, assembled: np.ndarray, singular: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    v = np.where(assembled, jet.v, np.nan)
    d = np.where(assembled & ~singular, jet.d, np.nan)
    dd = np.where(assembled & ~singular, jet.dd, np.nan)
    return v, d, dd


def _near_dead_centre(p: Mapping[str, float], theta_deg: np.ndarray, reach: np.ndarray,
                      rod) -> None:
    """Rows with the rod near horizontal: y_C = y_B - sqrt(l_BC^2 - x_B^2) and the rod's
    angle at 50 digits (rates by mpmath.diff in the crank angle); not assembled where
    x_B^2 > l_BC^2 there, singular where the rod is horizontal to 25 digits."""
    l_bc = p["l_BC"]
    near = np.flatnonzero(np.abs(l_bc - reach) <= NEAR_DEAD_CENTRE * l_bc)
    if near.size == 0:
        return
    la, lb, w = mpmath.mpf(p["l_AB"]), mpmath.mpf(l_bc), mpmath.mpf(p["omega_1"])
    with mpmath.workdps(50):
        def y_c(t):
            return la * mpmath.sin(t) - mpmath.sqrt(lb ** 2 - (la * mpmath.cos(t)) ** 2)

        def theta_2(t):
            return mpmath.atan2(y_c(t) - la * mpmath.sin(t), -la * mpmath.cos(t))

        for i in near:
            t = mpmath.radians(mpmath.mpf(float(theta_deg[i])))
            h2 = lb ** 2 - (la * mpmath.cos(t)) ** 2
            rod.dq[i], rod.ddq[i] = np.nan, np.nan
            if h2 < 0:
                rod.q[i], rod.assembled[i], rod.singular[i] = np.nan, False, False
                continue
            rod.assembled[i] = True
            if h2 <= (DEAD * lb) ** 2:
                rod.q[i] = [float(la * mpmath.sin(t)), float(mpmath.atan2(0, -la * mpmath.cos(t)))]
                rod.singular[i] = True
                continue
            rod.singular[i] = False
            rod.q[i] = [float(y_c(t)), float(theta_2(t))]
            rod.dq[i] = [float(w * mpmath.diff(y_c, t)), float(w * mpmath.diff(theta_2, t))]
            rod.ddq[i] = [float(w ** 2 * mpmath.diff(y_c, t, 2)),
                          float(w ** 2 * mpmath.diff(theta_2, t, 2))]


def solve(p: Mapping[str, float], theta_1_deg: np.ndarray) -> dict[str, np.ndarray]:
    """All outputs (and auxiliaries) of the sewing machine for crank angles theta_1 (deg)."""
    t1v = np.radians(np.asarray(theta_1_deg, dtype=float))
    rows = t1v.shape[0]
    l_ab, l_bc, l_be, l_fg = p["l_AB"], p["l_BC"], p["l_BE"], p["l_FG"]
    x_f, y_f = p["x_F"], p["y_F"]
    t1 = Jet(t1v, np.full(rows, p["omega_1"]), np.zeros(rows))
    x_b, y_b = l_ab * jcos(t1), l_ab * jsin(t1)

    # stage 1: needle bar; guess rod vertical, C one rod length below B
    q0 = np.stack([y_b.v - l_bc, np.full(rows, -0.5 * np.pi)], axis=1)

    def needle_branch(q):
        wrong = ~(np.sin(q[:, 1]) < 0.0) & np.isfinite(q[:, 1])
        return wrong, np.stack([y_b.v - l_bc, -q[:, 1]], axis=1)

    rod = solve_stage(_needle_closure(l_ab, l_bc), q0, [t1], l_ab + l_bc, needle_branch)
    _near_dead_centre(p, np.asarray(theta_1_deg, dtype=float), np.abs(x_b.v), rod)
    y_c, th2 = rod.jets()
    beta = math.radians(p["beta_E"])
    x_e = x_b + l_be * jcos(th2 + beta)
    y_e = y_b + l_be * jsin(th2 + beta)

    # stage 2: lever; guess lever pointing at A
    theta_fa = math.atan2(0.0 - y_f, 0.0 - x_f)  # no negative zero, as in Excel
    q0 = np.stack([np.full(rows, theta_fa), np.full(rows, math.hypot(x_f, y_f))], axis=1)

    def lever_branch(q):
        wrong = ~(q[:, 1] > 0.0) & np.isfinite(q[:, 1])
        return wrong, np.stack([q[:, 0] + np.pi, -q[:, 1]], axis=1)

    scale = math.hypot(x_f, y_f) + l_ab + l_be
    lever = solve_stage(_lever_closure(x_f, y_f), q0, [x_e, y_e], scale, lever_branch)
    th5, s_fe = lever.jets()
    x_g = x_f + l_fg * jcos(th5)
    y_g = y_f + l_fg * jsin(th5)

    ok = rod.assembled & lever.assembled
    sing = rod.singular | lever.singular
    out: dict[str, np.ndarray] = {}
    for names, jet, singular in (
        (("y_C", "v_C", "a_C"), y_c, rod.singular),
        (("s_FE", "v_FE", "a_FE"), s_fe, sing),
        (("x_G", "vx_G", "ax_G"), x_g, sing),
        (("y_G", "vy_G", "ay_G"), y_g, sing),
        (("x_B", None, None), x_b, np.zeros(rows, bool)),
        (("y_B", None, None), y_b, np.zeros(rows, bool)),
        (("h_BC", "dh_BC", "ddh_BC"), y_b - y_c, rod.singular),
        (("x_E", "vx_E", "ax_E"), x_e, rod.singular),
        (("y_E", "vy_E", "ay_E"), y_e, rod.singular),
    ):
        for name, arr in zip(names, _mask(jet, ok, singular)):
            if name is not None:
                out[name] = arr
    th5_v, out["omega_5"], out["alpha_5"] = _mask(th5, ok, sing)
    out["theta_5"] = wrap_deg(th5_v, math.degrees(theta_fa) - 180.0)
    th2_v, out["omega_2"], out["alpha_2"] = _mask(th2, ok, rod.singular)
    out["theta_2"] = wrap_deg(th2_v, -180.0)
    # the reach factors l_BC -+ x_B (defined whether or not the rod reaches), and h_BC and
    # s_FE where their rates exist (0 at a dead centre)
    out["lm_BC"], out["lp_BC"] = l_bc - x_b.v, l_bc + x_b.v
    out["hr_BC"] = np.where(rod.singular, 0.0, out["h_BC"])
    out["sr_FE"] = np.where(sing, 0.0, out["s_FE"])
    result = {name: out[name] for name in OUTPUTS}
    result["lm_BC" + NOISE] = result["lp_BC" + NOISE] = l_bc + np.abs(x_b.v)
    # h_BC = y_B - y_C cancels two values near l_BC when the crank is short: its rounding
    # is that of the terms, and its rates' that of the rate solve, whose terms are of
    # the order of omega^k times the positions (NOISE: the audit allows them).
    w, size = abs(p["omega_1"]), np.abs(y_b.v) + np.abs(y_c.v)
    result["h_BC" + NOISE] = size
    result["dh_BC" + NOISE] = np.abs(y_b.d) + np.abs(y_c.d) + w * size
    result["ddh_BC" + NOISE] = np.abs(y_b.dd) + np.abs(y_c.dd) + w * w * size
    # E = B + l_BE (cos, sin)(theta_2 + beta): with the rod near vertical, cos of an angle
    # near -90 deg keeps the angle's absolute rounding, l_BE |theta_2| eps, and so on.
    size = l_ab + l_be * (1.0 + np.abs(th2.v + beta))
    for axis in ("x", "y"):
        for k, prefix in enumerate(("", "v", "a")):
            result[f"{prefix}{axis}_E" + NOISE] = w ** k * size
    return result
