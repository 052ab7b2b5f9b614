"""Reference solution of the four-bar with a coupler point (docs/mechanisms.md, four_bar).

Unknowns q = (theta_3, theta_4); closure
l_O1A e(theta_2) + l_AB e(theta_3) - (l_O1O2, 0) - l_O2B e(theta_4) = 0,
solved by batched Newton from a few crude guesses; branch: B left of the
directed line A->O2 (open) or right of it (crossed), wrong rows re-solved from
their mirror image in that line.  Rates from the differentiated closure.

Reporting conventions (not formulas): the direction of A->O2 is taken within
90 deg of the ground direction when the crank is shorter than the ground, else
within 90 deg of theta_2 + 180; theta_3 and theta_4 are reported within
[0, 180] deg of it on the branch's side.  mu is Norton's transmission angle,
the acute angle between the lines of coupler and rocker.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np

import mpmath

from .newton import NOISE, Jet, Motion, jcos, jsin, newton, rates, solve_stage

DEFAULTS = {"l_O1O2": 100.0, "l_O1A": 40.0, "l_AB": 120.0, "l_O2B": 80.0, "l_AC": 60.0,
            "delta_C": 30.0, "omega_2": 10.0}
LENGTHS = ("l_O1O2", "l_O1A", "l_AB", "l_O2B")
TAKES_OPTIONS = True
GUESSES_DEG = (60.0, 20.0, 100.0, 140.0, 170.0, 5.0)  # theta_3 - phi, crude
TOGGLE_NEAR = 1e-5       # |sin(theta_3 - theta_4)| below this: polish in mpmath
TOGGLE_SINGULAR = 1e-14  # ... and below this after polishing: a toggle, no rates


@dataclass
class Loop:
    """A solved four-bar: crank pin, angles (jets, radians) and conventions."""

    motion: Motion
    crank: Jet
    x_a: Jet
    y_a: Jet
    theta_3: Jet
    theta_4: Jet
    phi: np.ndarray        # continuous direction of A->O2 (rad)
    sign: float            # +1 open, -1 crossed


def _closure(p: Mapping[str, float]):
    g, l1, l3, l4 = p["l_O1O2"], p["l_O1A"], p["l_AB"], p["l_O2B"]

    def closure(q, d):
        th3, th4 = q
        (t2,) = d
        return (l1 * jcos(t2) + l3 * jcos(th3) - g - l4 * jcos(th4),
                l1 * jsin(t2) + l3 * jsin(th3) - l4 * jsin(th4))

    return closure


def _wrap_pi(x: np.ndarray) -> np.ndarray:
    return x - 2.0 * np.pi * np.round(x / (2.0 * np.pi))


def direction_a_o2(p: Mapping[str, float], t2: np.ndarray,
                   turns: np.ndarray | None = None) -> np.ndarray:
    """The reporting convention's continuous direction of A->O2 (rad); ``turns``: the
    crank angle ``t2`` is (rad) with its whole turns, where t2 was reduced."""
    x_a, y_a = p["l_O1A"] * np.cos(t2), p["l_O1A"] * np.sin(t2)
    principal = np.arctan2(0.0 - y_a, p["l_O1O2"] - x_a)
    principal = np.where((x_a == p["l_O1O2"]) & (y_a == 0.0), np.nan, principal)  # A on O2
    if p["l_O1A"] < p["l_O1O2"]:
        return principal
    anchor = (t2 if turns is None else turns) + np.pi
    return anchor + _wrap_pi(principal - anchor)


def solve_loop(p: Mapping[str, float], t2: Jet, branch: str,
               theta_deg: np.ndarray | None = None) -> Loop:
    """Solve the four-bar for crank jets ``t2`` (rad) on ``branch``; ``theta_deg``: the
    crank angles in degrees, for the rows near a toggle solved at 50 digits."""
    sign = 1.0 if branch == "open" else -1.0
    turns = t2.v
    if theta_deg is not None:   # A from the angle reduced to (-180, 180] deg, as the
        deg = np.asarray(theta_deg, dtype=float)   # templates: exactly on O2 at 0 mod 360
        deg = np.where(np.abs(deg) <= 180.0, deg, deg - 360.0 * np.ceil((deg - 180.0) / 360.0))
        t2 = Jet(np.radians(deg), t2.d, t2.dd)
    rows = t2.v.shape[0]
    l1, l3, l4, g = p["l_O1A"], p["l_AB"], p["l_O2B"], p["l_O1O2"]
    x_a, y_a = l1 * jcos(t2), l1 * jsin(t2)
    phi = np.arctan2(-y_a.v, g - x_a.v)
    closure, scale = _closure(p), g + l1 + l3 + l4

    def guess(offset_deg: float) -> np.ndarray:
        th3 = phi + sign * math.radians(offset_deg)
        bx, by = x_a.v + l3 * np.cos(th3), y_a.v + l3 * np.sin(th3)
        return np.stack([th3, np.arctan2(by, bx - g)], axis=1)

    def on_branch(q: np.ndarray, idx=slice(None)) -> np.ndarray:
        gx, ya = g - x_a.v[idx], y_a.v[idx]
        return sign * (gx * np.sin(q[:, 0]) + ya * np.cos(q[:, 0])) > 0.0  # (O2 - A) x e_3

    # crude guesses until every row that can be assembled is, on the branch
    q = np.full((rows, 2), np.nan)
    todo = np.ones(rows, bool)
    for offset in GUESSES_DEG:
        idx = np.flatnonzero(todo)
        if idx.size == 0:
            break
        q_try, ok = newton(closure, guess(offset)[idx], [t2.v[idx]], scale)
        ok &= on_branch(q_try, idx)
        q[idx[ok]] = q_try[ok]
        todo[idx[ok]] = False

    def fix_branch(qq):
        wrong = ~on_branch(qq) & np.isfinite(qq[:, 0])
        return wrong, np.stack([2.0 * phi - qq[:, 0], 2.0 * phi - qq[:, 1]], axis=1)

    # unassembled rows start from a guess again (they stay unassembled)
    start = np.where(np.isfinite(q), q, guess(GUESSES_DEG[0]))
    motion = solve_stage(closure, start, [t2], scale, fix_branch)
    _polish_toggles(p, t2, motion, closure,
                    np.degrees(t2.v) if theta_deg is None else np.asarray(theta_deg, float))
    th3, th4 = motion.jets()
    return Loop(motion, t2, x_a, y_a, th3, th4, direction_a_o2(p, t2.v, turns), sign)


def _polish_toggles(p: Mapping[str, float], t2: Jet, motion: Motion, closure,
                    theta_deg: np.ndarray) -> None:
    """Near a toggle (coupler and rocker in line) Newton in floats stops about sqrt(eps)
    from the double root: polish those rows with mpmath Newton at 50 digits from the crank
    angle in degrees, and call a row singular (no rates) where coupler and rocker are in
    line to rounding, not assembled where |O2 - A| is beyond l_AB + l_O2B or short of
    |l_AB - l_O2B| at 50 digits (Newton in floats closes such a loop to its tolerance)."""
    q = motion.q
    g, l1, l3, l4 = p["l_O1O2"], p["l_O1A"], p["l_AB"], p["l_O2B"]
    d = np.hypot(g - l1 * np.cos(t2.v), l1 * np.sin(t2.v))
    reach = np.minimum(np.abs(d - (l3 + l4)), np.abs(d - abs(l3 - l4))) <= TOGGLE_NEAR * (l3 + l4)
    near = np.flatnonzero(motion.assembled & (reach | (np.abs(np.sin(q[:, 0] - q[:, 1]))
                                                       < TOGGLE_NEAR)))
    if near.size == 0:
        return
    g, l1, l3, l4 = (mpmath.mpf(p[k]) for k in ("l_O1O2", "l_O1A", "l_AB", "l_O2B"))
    with mpmath.workdps(50):
        for i in near:
            t = mpmath.radians(mpmath.mpf(float(theta_deg[i])))
            d2 = g ** 2 + l1 ** 2 - 2 * g * l1 * mpmath.cos(t)
            if d2 > (l3 + l4) ** 2 or d2 < (l3 - l4) ** 2:
                q[i] = np.nan
                motion.assembled[i] = False
                continue
            th = mpmath.matrix([mpmath.mpf(float(q[i, 0])), mpmath.mpf(float(q[i, 1]))])
            for _ in range(200):
                r = mpmath.matrix([l1 * mpmath.cos(t) + l3 * mpmath.cos(th[0]) - g
                                   - l4 * mpmath.cos(th[1]),
                                   l1 * mpmath.sin(t) + l3 * mpmath.sin(th[0])
                                   - l4 * mpmath.sin(th[1])])
                jac = mpmath.matrix([[-l3 * mpmath.sin(th[0]), l4 * mpmath.sin(th[1])],
                                     [l3 * mpmath.cos(th[0]), -l4 * mpmath.cos(th[1])]])
                if mpmath.norm(r) < mpmath.mpf(10) ** -45 or mpmath.det(jac) == 0:
                    break
                th = th - mpmath.lu_solve(jac, r)
            if mpmath.norm(r) > mpmath.mpf(10) ** -30 * (g + l1 + l3 + l4):
                # no root at 50 digits: the loop does not close (a hair beyond a toggle,
                # which the float Newton accepted at its tolerance)
                motion.assembled[i] = False
                q[i] = [np.nan, np.nan]
                continue
            q[i] = [float(th[0]), float(th[1])]
            if abs(mpmath.sin(th[0] - th[1])) < TOGGLE_SINGULAR:
                motion.singular[i] = True
    dq, ddq, sing = rates(closure, q, [t2])
    bad = ~motion.assembled | sing | motion.singular
    motion.singular |= sing & motion.assembled
    motion.singular &= motion.assembled
    dq[bad], ddq[bad] = np.nan, np.nan
    motion.dq, motion.ddq = dq, ddq


def _report_angle(angle: np.ndarray, phi: np.ndarray, sign: float) -> np.ndarray:
    """Degrees, within [0, 180] of phi on the branch's side."""
    low = np.degrees(phi) - (90.0 if sign > 0 else 270.0)
    deg = np.degrees(angle)
    return low + 360.0 - np.mod(low + 360.0 - deg, 360.0)


def _foot(p: Mapping[str, float], x_a: np.ndarray, y_a: np.ndarray) -> np.ndarray:
    """Where the line A->O2 meets the radical line of the circles about A (l_AB) and
    O2 (l_O2B): the zero of the power difference, linear along the line."""
    d = np.hypot(p["l_O1O2"] - x_a, y_a)

    def power_difference(t):
        return t * t - p["l_AB"] ** 2 - ((t - d) ** 2 - p["l_O2B"] ** 2)

    f0, f1 = power_difference(0.0), power_difference(d)
    return -f0 * d / (f1 - f0)


def columns(p: Mapping[str, float], loop: Loop) -> dict[str, np.ndarray]:
    """Every Table column of the four-bar from a solved loop."""
    m, x_a, y_a = loop.motion, loop.x_a, loop.y_a
    l3, g = p["l_AB"], p["l_O1O2"]
    ok, sing = m.assembled, m.singular
    th3, th4 = loop.theta_3, loop.theta_4
    delta = math.radians(math.remainder(p["delta_C"], 360.0))
    x_c = x_a + p["l_AC"] * jcos(th3 + delta)
    y_c = y_a + p["l_AC"] * jsin(th3 + delta)
    bx, by = l3 * np.cos(th3.v), l3 * np.sin(th3.v)      # B - A
    d = np.hypot(g - x_a.v, y_a.v)
    ex, ey = (g - x_a.v) / d, -y_a.v / d
    rel = np.mod(np.abs(th3.v - th4.v), np.pi)
    rates = ok & ~sing
    out = {
        "x_A": x_a.v, "y_A": y_a.v, "d_AO2": d, "phi_AO2": loop.phi,
        "f_B": np.where(ok, bx * ex + by * ey, _foot(p, x_a.v, y_a.v)),
        "h_B": np.where(ok, np.abs(bx * ey - by * ex), np.nan),
        "theta_3": _report_angle(th3.v, loop.phi, loop.sign),
        "theta_4": _report_angle(th4.v, loop.phi, loop.sign),
        "x_B": x_a.v + bx, "y_B": y_a.v + by,
        "omega_3": th3.d, "omega_4": th4.d, "alpha_3": th3.dd, "alpha_4": th4.dd,
        "x_C": x_c.v, "y_C": y_c.v, "vx_C": x_c.d, "vy_C": y_c.d,
        "ax_C": x_c.dd, "ay_C": y_c.dd,
        "mu": np.degrees(np.minimum(rel, np.pi - rel)),
    }
    # the factors of the half chord's square, defined whether or not B closes the loop
    # (0 with coupler and rocker in line); they cancel the squares of their terms
    out["p2_d2"] = (l3 + p["l_O2B"]) ** 2 - d * d
    out["d2_q2"] = d * d - (l3 - p["l_O2B"]) ** 2
    out["p2_d2" + NOISE] = out["d2_q2" + NOISE] = (l3 + p["l_O2B"]) ** 2 + d * d
    out["hr_B"] = np.where(sing, 0.0, out["h_B"])     # h_B where the rates exist
    for name in ("omega_3", "omega_4", "alpha_3", "alpha_4", "vx_C", "vy_C", "ax_C", "ay_C"):
        out[name] = np.where(rates, out[name], np.nan)
    for name in ("theta_3", "theta_4", "x_B", "y_B", "x_C", "y_C", "mu"):
        out[name] = np.where(ok, out[name], np.nan)
    return out


def crank(p: Mapping[str, float], theta_2_deg: np.ndarray) -> Jet:
    t2 = np.radians(np.asarray(theta_2_deg, dtype=float))
    return Jet(t2, np.full(t2.shape, p["omega_2"]), np.zeros(t2.shape))


def solve(p: Mapping[str, float], theta_2_deg: np.ndarray,
          options: Mapping[str, object]) -> dict[str, np.ndarray]:
    """All columns of the four-bar for crank angles theta_2 (deg)."""
    branch = str(options.get("branch", "open"))
    return columns(p, solve_loop(p, crank(p, theta_2_deg), branch, theta_2_deg))
