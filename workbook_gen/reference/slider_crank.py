"""Reference solution of the offset slider-crank (docs/mechanisms.md, slider_crank).

Unknowns q = (s_C, theta_2); closure: B + l_BC*(cos theta_2, sin theta_2) = s_C*u + e*n,
with B = l_AB*(cos theta_1, sin theta_1). Branch: slider ahead of the pin, (C - B).u > 0,
i.e. cos(theta_2 - phi_slide) > 0.
"""

from __future__ import annotations

from typing import Mapping

import numpy as np

from .newton import Jet, jcos, jsin, solve_stage, wrap_deg

DEFAULTS = {"l_AB": 40.0, "l_BC": 120.0, "e": 10.0, "phi_slide": 0.0, "omega_1": 10.0}
LENGTHS = ("l_AB", "l_BC")
OUTPUTS = ("s_C", "v_C", "a_C", "theta_2", "omega_2", "alpha_2")


def _closure(p: Mapping[str, float]):
    phi = np.radians(p["phi_slide"])
    ux, uy = np.cos(phi), np.sin(phi)
    nx, ny = -uy, ux
    e, l_ab, l_bc = p["e"], p["l_AB"], p["l_BC"]

    def closure(q, d):
        s, th2 = q
        (t1,) = d
        return (
            l_ab * jcos(t1) + l_bc * jcos(th2) - s * ux - e * nx,
            l_ab * jsin(t1) + l_bc * jsin(th2) - s * uy - e * ny,
        )

    return closure


def solve(p: Mapping[str, float], theta_1_deg: np.ndarray) -> dict[str, np.ndarray]:
    """All outputs of the slider-crank for crank angles theta_1 (deg)."""
    t1 = np.radians(np.asarray(theta_1_deg, dtype=float))
    rows = t1.shape[0]
    phi = np.radians(p["phi_slide"])
    scale = p["l_AB"] + p["l_BC"] + abs(p["e"])
    # guess: rod along the slide, slider one rod length ahead of the pin's projection
    b_u = p["l_AB"] * (np.cos(t1) * np.cos(phi) + np.sin(t1) * np.sin(phi))
    q0 = np.stack([b_u + p["l_BC"], np.full(rows, phi)], axis=1)

    def fix_branch(q):
        wrong = ~(np.cos(q[:, 1] - phi) > 0.0) & np.isfinite(q[:, 1])
        return wrong, np.stack([b_u + p["l_BC"], 2.0 * phi + np.pi - q[:, 1]], axis=1)

    drive = Jet(t1, np.full(rows, p["omega_1"]), np.zeros(rows))
    m = solve_stage(_closure(p), q0, [drive], scale, fix_branch)
    # Auxiliary columns: the crank pin in slide coordinates, and the rod's projection on
    # the slide with its rates, from the solved rod angle (l_BC cos of the relative angle).
    rel, w2, a2 = m.q[:, 1] - phi, m.dq[:, 1], m.ddq[:, 1]
    assembled = np.where(np.isfinite(m.q[:, 0]), 1.0, np.nan)
    aux = {
        "u_B": p["l_AB"] * np.cos(t1 - phi) * assembled,
        "n_B": p["l_AB"] * np.sin(t1 - phi) * assembled,
        # l_BC -+ q, q = l_BC sin(rel) the rod's reach across the slide: h_BC^2's factors
        "f_BC": p["l_BC"] * (1.0 - np.sin(rel)),
        "g_BC": p["l_BC"] * (1.0 + np.sin(rel)),
        "h_BC": p["l_BC"] * np.cos(rel),
        "dh_BC": -p["l_BC"] * np.sin(rel) * w2,
        "ddh_BC": -p["l_BC"] * (np.cos(rel) * w2 ** 2 + np.sin(rel) * a2),
    }
    return aux | {
        "s_C": m.q[:, 0],
        "v_C": m.dq[:, 0],
        "a_C": m.ddq[:, 0],
        "theta_2": wrap_deg(m.q[:, 1], p["phi_slide"] - 180.0),
        "omega_2": m.dq[:, 1],
        "alpha_2": m.ddq[:, 1],
    }
