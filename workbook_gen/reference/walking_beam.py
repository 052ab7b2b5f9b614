"""Reference solution of the walking beam (docs/mechanisms.md, walking_beam).

Stage 1: the four-bar (reference.four_bar) gives C.  Stage 2 solves the rest of
the eight-bar by Newton: the copy, a second four-bar with ground pivots at
(l_CD, 0) and (l_O1O2 + l_CD, 0) whose crank turns in phase with the first,
with unknowns (theta_3', theta_4'), and the beam from C to the copy's coupler
point D, with unknowns (theta_7, L):  C + L e(theta_7) = D.  The beam translates
when theta_7, omega_7 and alpha_7 vanish and L = l_CD; those are returned too
(``theta_7`` in deg, ``l_beam``) for the tests.
"""

from __future__ import annotations

import math
from typing import Mapping

import numpy as np

from . import four_bar
from .newton import jcos, jsin, solve_stage

DEFAULTS = {"l_O1O2": 40.0, "l_O1A": 20.0, "l_AB": 50.0, "l_O2B": 50.0, "l_AC": 100.0,
            "delta_C": 0.0, "omega_2": 10.0, "l_CD": 160.0}
LENGTHS = ("l_O1O2", "l_O1A", "l_AB", "l_O2B", "l_CD")
TAKES_OPTIONS = True


def _copy_and_beam(p: Mapping[str, float]):
    g, l1, l3, l4, l_ac = p["l_O1O2"], p["l_O1A"], p["l_AB"], p["l_O2B"], p["l_AC"]
    shift, delta = p["l_CD"], math.radians(math.remainder(p["delta_C"], 360.0))

    def closure(q, d):
        th3, th4, th7, length = q
        t2, x_c, y_c = d
        ax, ay = shift + l1 * jcos(t2), l1 * jsin(t2)        # the copy's crank pin
        return (
            ax + l3 * jcos(th3) - (shift + g) - l4 * jcos(th4),
            ay + l3 * jsin(th3) - l4 * jsin(th4),
            x_c + length * jcos(th7) - (ax + l_ac * jcos(th3 + delta)),
            y_c + length * jsin(th7) - (ay + l_ac * jsin(th3 + delta)),
        )

    return closure


def solve(p: Mapping[str, float], theta_2_deg: np.ndarray,
          options: Mapping[str, object]) -> dict[str, np.ndarray]:
    """All Table columns of the walking beam, plus theta_7 (deg), omega_7, alpha_7, l_beam."""
    branch = str(options.get("branch", "open"))
    t2 = four_bar.crank(p, theta_2_deg)
    loop = four_bar.solve_loop(p, t2, branch)
    out = four_bar.columns(p, loop)
    delta = math.radians(math.remainder(p["delta_C"], 360.0))
    x_c = loop.x_a + p["l_AC"] * jcos(loop.theta_3 + delta)
    y_c = loop.y_a + p["l_AC"] * jsin(loop.theta_3 + delta)

    # the copy from a guess of its own (the first loop's angles turned by a little),
    # the beam from a tilted, stretched guess
    rows = t2.v.shape[0]
    q0 = np.stack([loop.theta_3.v + 0.05, loop.theta_4.v - 0.05, np.full(rows, 0.3),
                   np.full(rows, 1.2 * p["l_CD"])], axis=1)
    side = loop.sign

    def fix_branch(q):
        x_a, y_a = p["l_O1A"] * np.cos(t2.v), p["l_O1A"] * np.sin(t2.v)
        cross = (p["l_O1O2"] - x_a) * np.sin(q[:, 0]) + y_a * np.cos(q[:, 0])
        wrong = ~((side * cross > 0.0) & (q[:, 3] > 0.0)) & np.isfinite(q[:, 0])
        phi = np.arctan2(-y_a, p["l_O1O2"] - x_a)
        return wrong, np.stack([2 * phi - q[:, 0], 2 * phi - q[:, 1], q[:, 2] + np.pi,
                                -q[:, 3]], axis=1)

    scale = p["l_O1O2"] + p["l_O1A"] + p["l_AB"] + p["l_O2B"] + p["l_AC"] + p["l_CD"]
    start = np.where(loop.motion.assembled[:, None], q0, np.nan)
    m = solve_stage(_copy_and_beam(p), np.nan_to_num(start), [t2, x_c, y_c], scale,
                    fix_branch)
    ok = m.assembled & loop.motion.assembled
    th3c = m.jets()[0]
    x_d = p["l_CD"] + loop.x_a + p["l_AC"] * jcos(th3c + delta)
    y_d = loop.y_a + p["l_AC"] * jsin(th3c + delta)
    out["x_D"] = np.where(ok, x_d.v, np.nan)
    out["y_D"] = np.where(ok, y_d.v, np.nan)
    th7 = np.where(ok, m.q[:, 2], np.nan)
    out["theta_7"] = np.degrees(th7 - 2 * np.pi * np.round(th7 / (2 * np.pi)))
    out["omega_7"], out["alpha_7"] = m.dq[:, 2], m.ddq[:, 2]
    out["l_beam"] = np.where(ok, m.q[:, 3], np.nan)
    return out
