"""Reference solution of the actuator linkage (docs/mechanisms.md, actuator_linkage).

Unknowns q = (phi_2, phi_3); closure, driven by s = s_BC with s' = v_s, s'' = 0:
    A + l_A1 (cos phi_2, sin phi_2) + l_A1C (sin phi_2, -cos phi_2) = B + s (cos phi_3, sin phi_3).
Branch: C on the left of the directed line A->B, (B - A) x (C - A) > 0.  The
start for Newton is the point of a 1/4-degree scan of phi_2 on that side
whose |C - B| is nearest s.  Rates come from the differentiated closure
(newton.rates); C's velocity and acceleration from the cylinder side,
C = B + s e_3.  Angles are reported in the windows the template's
continuity rule implies: phi_AC within pi of the direction A->B, phi_3 within
pi of the direction B->A, phi_2 within pi of phi_AC.

With ``method = "bisection"`` also the successive halving of
f(phi) = |C(phi) - B|^2 - s^2 on [phi_lo, phi_hi], by the paper's rule (keep the
half whose ends differ in sign, stop at the first midpoint with |f| < epsilon),
written here as a plain loop.
"""

from __future__ import annotations

from typing import Mapping

import numpy as np

from .newton import Jet, jcos, jsin, solve_stage

DEFAULTS = {"x_A": 0.156, "y_A": 0.437, "x_B": 0.462, "y_B": 0.0, "l_A1": 1.237,
            "l_A1C": 0.325, "v_s": 0.1, "gamma_min": 0.35, "epsilon": 1e-4,
            "phi_lo": -1.5, "phi_hi": 4.64}
LENGTHS = ("l_A1", "epsilon")
TAKES_OPTIONS = True
OPTION_DEFAULTS = {"method": "closed", "halvings": 20}


def _lever_point(p, phi):
    """C for lever angles phi (numpy)."""
    c, s = np.cos(phi), np.sin(phi)
    return (p["x_A"] + p["l_A1"] * c + p["l_A1C"] * s,
            p["y_A"] + p["l_A1"] * s - p["l_A1C"] * c)


def _closure(p):
    def closure(q, d):
        phi2, phi3 = q
        (s,) = d
        return (
            p["x_A"] + p["l_A1"] * jcos(phi2) + p["l_A1C"] * jsin(phi2) - p["x_B"] - s * jcos(phi3),
            p["y_A"] + p["l_A1"] * jsin(phi2) - p["l_A1C"] * jcos(phi2) - p["y_B"] - s * jsin(phi3),
        )
    return closure


def _left_of_ab(p, cx, cy):
    return ((p["x_B"] - p["x_A"]) * (cy - p["y_A"]) - (p["y_B"] - p["y_A"]) * (cx - p["x_A"]))


def _start(p, s):
    """Newton's start: the scanned lever angle on the branch with |C - B| nearest s."""
    grid = np.radians(np.arange(-180.0, 180.0, 0.25))
    cx, cy = _lever_point(p, grid)
    dist = np.hypot(cx - p["x_B"], cy - p["y_B"])
    miss = np.abs(dist[None, :] - s[:, None])
    miss[:, ~(_left_of_ab(p, cx, cy) > 0)] = np.inf
    phi2 = grid[np.argmin(miss, axis=1)]
    gx, gy = _lever_point(p, phi2)
    return np.stack([phi2, np.arctan2(gy - p["y_B"], gx - p["x_B"])], axis=1)


def _wrap(angle, centre):
    """angle + 2 pi k in (centre - pi, centre + pi]."""
    return centre + np.pi - np.mod(centre + np.pi - angle, 2 * np.pi)


def _closed(p, s):
    rows = s.shape[0]
    q0 = _start(p, s)

    def fix_branch(q):
        cx, cy = _lever_point(p, q[:, 0])
        return ~(_left_of_ab(p, cx, cy) > 0) & np.isfinite(q[:, 0]), q0

    drive = Jet(s, np.full(rows, p["v_s"]), np.zeros(rows))
    scale = p["l_A1"] + abs(p["l_A1C"]) + float(np.max(s)) + np.hypot(
        p["x_B"] - p["x_A"], p["y_B"] - p["y_A"])
    m = solve_stage(_closure(p), q0, [drive], scale, fix_branch)
    phi2, phi3 = m.q[:, 0], m.q[:, 1]
    w2, a2, w3, a3 = m.dq[:, 0], m.ddq[:, 0], m.dq[:, 1], m.ddq[:, 1]
    cx, cy = _lever_point(p, phi2)
    bax, bay = p["x_B"] - p["x_A"], p["y_B"] - p["y_A"]
    acx, acy = cx - p["x_A"], cy - p["y_A"]
    # C from the cylinder side: C = B + s e3, C' = v e3 + s w3 n3, C'' = -s w3^2 e3 + (2 v w3 + s a3) n3
    e3x, e3y, v = np.cos(phi3), np.sin(phi3), p["v_s"]
    vx, vy = v * e3x - s * w3 * e3y, v * e3y + s * w3 * e3x
    tang = 2 * v * w3 + s * a3
    ax, ay = -s * w3 ** 2 * e3x - tang * e3y, -s * w3 ** 2 * e3y + tang * e3x
    # transmission angle between C->A and C->B
    cax, cay, cbx, cby = -acx, -acy, p["x_B"] - cx, p["y_B"] - cy
    gamma = np.arctan2(np.abs(cax * cby - cay * cbx), cax * cbx + cay * cby)
    dir_ab = np.arctan2(bay, bax)
    phi_ac = _wrap(np.arctan2(acy, acx), dir_ab)
    below = np.where(np.minimum(gamma, np.pi - gamma) < p["gamma_min"], 1.0, 0.0)
    below[~np.isfinite(gamma)] = np.nan
    return {
        "cross_A": 2 * (bax * acy - bay * acx),
        "phi_2": phi_ac + _wrap(phi2 - phi_ac, 0.0),
        "phi_AC": phi_ac,
        "phi_3": _wrap(phi3, np.arctan2(-bay, -bax)),
        "gamma": gamma,
        "below_gamma_min": below,
        "x_C": cx, "y_C": cy,
        "omega_2": w2, "alpha_2": a2,
        "vx_C": vx, "vy_C": vy, "ax_C": ax, "ay_C": ay,
        "omega_3": w3, "alpha_3": a3,
    }


def bisect(p, s, halvings: int) -> dict[str, np.ndarray]:
    """The paper's successive halving, every column of it, for all rows at once."""
    def f(phi):
        cx, cy = _lever_point(p, phi)
        return (cx - p["x_B"]) ** 2 + (cy - p["y_B"]) ** 2 - s ** 2

    lo = np.full(s.shape, p["phi_lo"])
    hi = np.full(s.shape, p["phi_hi"])
    f_lo = f(lo)
    out = {"f_lo": f_lo}
    stopped_at = np.zeros(s.shape, dtype=int)
    for k in range(1, halvings + 1):
        mid = 0.5 * (lo + hi)
        fk = f(mid)
        out |= {f"lo_{k}": lo, f"hi_{k}": hi, f"mid_{k}": mid, f"f_{k}": fk}
        done = np.abs(fk) < p["epsilon"]
        stopped_at = np.where((stopped_at == 0) & done, k, stopped_at)
        upper = ~done & (f_lo * fk < 0)        # root in the lower half
        lower = ~done & ~(f_lo * fk < 0)       # root in the upper half
        lo, hi = np.where(lower, mid, lo), np.where(upper, mid, hi)
    out["halvings_used"] = np.where(stopped_at > 0, stopped_at, halvings).astype(float)
    out["phi_2_iter"] = np.where(stopped_at > 0, out[f"mid_{halvings}"], np.nan)
    return out


def solve(p: Mapping[str, float], s_bc: np.ndarray,
          options: Mapping[str, object]) -> dict[str, np.ndarray]:
    """Every Table column of the actuator linkage for cylinder lengths s_bc."""
    options = {**OPTION_DEFAULTS, **options}
    s = np.asarray(s_bc, dtype=float)
    out = _closed(p, s)
    if options["method"] == "bisection":
        out |= bisect(p, s, int(options["halvings"]))
    return out
