"""Reference solution of the five-bar (docs/mechanisms.md, five_bar), by Newton on the loops.

Inverse kinematics: each dyad separately, unknowns (theta_1, theta_2) with
l_1 u(theta_1) + l_2 u(theta_2) = C, and (theta_4, theta_3) with
E + l_4 u(theta_4) + l_3 u(theta_3) = C; branch B left of A->C, D right of E->C.
``method = "newton"``: the iterates th1_0 .. th1_k the workbook shows, from the same
start (crank perpendicular to pivot->C), each step t <- t - f/f' with
f = |C - B(t)|^2 - l_2^2; theta_1 / theta_4 stay the exact angles where the model's own
k-th step moved by at most CONVERGED_DEG, and are NaN elsewhere (the workbook's #NUM!,
"not converged"), with everything computed from them.

Sensitivity: the vector loop l_1 u_1 + l_2 u_2 = l_5 e_x + l_4 u_4 + l_3 u_3 in the
coupler angles (theta_2, theta_3) with the crank angles held, differentiated along
each link length by the jets of ``newton.rates``; C = l_1 u_1 + l_2 u_2.

Clearance: for each joint and direction the displaced geometry (pivot A or E moved,
pin B or D moved, or coupler 3's eye offset from C) is re-solved by Newton for the
coupler-angle increments; C' - C = moved end + l_2 (u(theta_2 + d) - u(theta_2)),
the difference written as 2 sin(d/2) u'(theta_2 + d/2), free of cancellation.
"""

from __future__ import annotations

from typing import Mapping

import numpy as np

from .newton import Jet, jcos, jsin, newton, rates, solve_stage, wrap_deg

CONVERGED_DEG = 1e-9   # as the template's five_bar_newton (a rule, not a formula)
ITERATIONS = 8         # the template's default (About lists only the options a scene sets)

DEFAULTS = {"l_1": 1.2, "l_2": 1.0, "l_3": 1.0, "l_4": 1.2, "l_5": 1.6,
            "x_0": 0.8, "y_0": 1.6, "R_path": 0.3, "r_clear": 1e-5}
LENGTHS = ("l_1", "l_2", "l_3", "l_4", "l_5", "R_path", "r_clear")
TAKES_OPTIONS = True
ANGLES = (0, 90, 180, 270)
JOINTS = "ABCDE"


def _dyad(c_x, c_y, pivot_x, crank, coupler, left: bool):
    """Crank and coupler angles (rad) of a dyad from pivot (pivot_x, 0) to C."""
    rows = c_x.shape[0]
    rel_x, rel_y = c_x - pivot_x, c_y
    psi = np.arctan2(rel_y, rel_x)
    side = 1.0 if left else -1.0

    def closure(q, d):
        t_crank, t_coupler = q
        cx, cy = d
        return (crank * jcos(t_crank) + coupler * jcos(t_coupler) - (cx - pivot_x),
                crank * jsin(t_crank) + coupler * jsin(t_coupler) - cy)

    def elbow_cross(q):
        return rel_x * np.sin(q[:, 0]) - rel_y * np.cos(q[:, 0])   # (C - pivot) x u

    def fix_branch(q):
        wrong = ~(side * elbow_cross(q) > 0.0) & np.isfinite(q[:, 0])
        return wrong, np.stack([2 * psi - q[:, 0], 2 * psi - q[:, 1]], axis=1)

    q0 = np.stack([psi + side * np.pi / 3, psi - side * np.pi / 3], axis=1)
    drivers = [Jet(c_x, np.zeros(rows)), Jet(c_y, np.zeros(rows))]
    motion = solve_stage(closure, q0, drivers, crank + coupler + abs(pivot_x), fix_branch)
    return motion.q[:, 0], motion.q[:, 1]


def _newton_iterates(c_x, c_y, pivot_x, crank, coupler, start_deg, steps):
    """The workbook's Newton iterates (deg), written from f = |C - B(t)|^2 - coupler^2."""
    out = [start_deg]
    t = start_deg
    with np.errstate(invalid="ignore", divide="ignore"):
        for _ in range(steps):
            r = np.radians(t)
            b_x, b_y = pivot_x + crank * np.cos(r), crank * np.sin(r)
            f = (c_x - b_x) ** 2 + (c_y - b_y) ** 2 - coupler ** 2
            df = -2.0 * ((c_x - b_x) * (-crank * np.sin(r)) + (c_y - b_y) * crank * np.cos(r))
            t = t - np.degrees(f / df)
            out.append(t)
    return out


def _loop(p):
    """Vector loop in the coupler angles, drivers (l_1..l_5, theta_1, theta_4)."""
    def closure(q, d):
        t2, t3 = q
        l1, l2, l3, l4, l5, t1, t4 = d
        return (l1 * jcos(t1) + l2 * jcos(t2) - l5 - l4 * jcos(t4) - l3 * jcos(t3),
                l1 * jsin(t1) + l2 * jsin(t2) - l4 * jsin(t4) - l3 * jsin(t3))
    return closure


def _sensitivity(p, t1, t2, t3, t4) -> dict[str, np.ndarray]:
    rows = t1.shape[0]
    q = np.stack([t2, t3], axis=1)
    lengths = [p[f"l_{i}"] for i in range(1, 6)]
    out = {}
    for i in range(5):
        jets = [Jet(np.full(rows, v), np.full(rows, 1.0 if k == i else 0.0), np.zeros(rows))
                for k, v in enumerate(lengths)]
        jets += [Jet(t1, np.zeros(rows), np.zeros(rows)), Jet(t4, np.zeros(rows), np.zeros(rows))]
        dq, _, _ = rates(_loop(p), q, jets)
        th2 = Jet(t2, dq[:, 0], np.zeros(rows))
        c_x = jets[0] * jcos(jets[5]) + jets[1] * jcos(th2)
        c_y = jets[0] * jsin(jets[5]) + jets[1] * jsin(th2)
        out[f"S_x_l{i + 1}"] = c_x.d
        out[f"S_y_l{i + 1}"] = c_y.d
    return out


def _displaced(p, joint: str, alpha: int, t1, t2, t3, t4):
    """C' - C (x, y), and the moved coupler ends B', D', for a clearance at ``joint``."""
    r = p["r_clear"]
    delta = np.array([np.cos(np.radians(alpha)), np.sin(np.radians(alpha))]) * r
    delta = np.round(delta / r) * r          # exactly axis-aligned at 0, 90, 180, 270
    zero = np.zeros(2)
    a_shift, b_shift, eye, d_shift, e_shift = (delta if j == joint else zero for j in JOINTS)
    l1, l2, l3, l4, l5 = (p[f"l_{i}"] for i in range(1, 6))
    moved_b = a_shift - b_shift                       # B' - B (B's journal offset by -delta)
    moved_d = e_shift - d_shift - eye                 # D' - D as coupler 2 sees it
    gap = moved_b - moved_d
    rows = t1.shape[0]

    def closure(q, d):
        """The loop minus the nominal loop, in the coupler-angle increments (small terms
        only: u(t + e) - u(t) = 2 sin(e/2) u'(t + e/2))."""
        e2, e3 = q
        th2, th3 = d
        s2, s3 = 2.0 * l2 * jsin(e2 * 0.5), 2.0 * l3 * jsin(e3 * 0.5)
        m2, m3 = th2 + e2 * 0.5, th3 + e3 * 0.5
        return (s3 * jsin(m3) - s2 * jsin(m2) + gap[0],
                s2 * jcos(m2) - s3 * jcos(m3) + gap[1])

    b = (l1 * np.cos(t1) + moved_b[0], l1 * np.sin(t1) + moved_b[1])
    d = (l5 + l4 * np.cos(t4) + moved_d[0], l4 * np.sin(t4) + moved_d[1])
    g = (d[0] - b[0], d[1] - b[1])
    c = (b[0] - moved_b[0] + l2 * np.cos(t2), b[1] - moved_b[1] + l2 * np.sin(t2))

    def error(inc):
        half = t2 + inc[:, 0] / 2
        chord = 2.0 * np.sin(inc[:, 0] / 2) * l2
        return moved_b[0] - chord * np.sin(half), moved_b[1] + chord * np.cos(half)

    def side(px, py):   # which side of the line B'->D' the point (px, py) is on
        return np.sign(g[0] * (py - b[1]) - g[1] * (px - b[0]))

    inc, _ = newton(closure, np.zeros((rows, 2)), [t2, t3], p["r_clear"])
    ex, ey = error(inc)
    # the assembly mode kept: C' on the same side of B'D' as C; else re-solve from the mirror
    wrong = np.isfinite(ex) & (side(c[0] + ex, c[1] + ey) != side(*c))
    if np.any(wrong):
        gg = g[0] ** 2 + g[1] ** 2
        rx, ry = c[0] + ex - b[0], c[1] + ey - b[1]
        along = 2.0 * (rx * g[0] + ry * g[1]) / gg
        mx, my = b[0] + along * g[0] - rx, b[1] + along * g[1] - ry   # mirrored C'
        guess = np.stack([np.arctan2(my - b[1], mx - b[0]) - t2,
                          np.arctan2(my - d[1], mx - d[0]) - t3], axis=1)
        guess = (guess + np.pi) % (2 * np.pi) - np.pi
        inc2, _ = newton(closure, guess[wrong], [t2[wrong], t3[wrong]], p["r_clear"])
        inc[wrong] = inc2
        ex, ey = error(inc)
        bad = np.isfinite(ex) & (side(c[0] + ex, c[1] + ey) != side(*c))
        ex[bad], ey[bad] = np.nan, np.nan
    return ex, ey, b, d


def _clearance(p, t1, t2, t3, t4, c_x, c_y) -> dict[str, np.ndarray]:
    out = {}
    for joint in JOINTS:
        for alpha in ANGLES:
            ex, ey, (bx, by), (dx, dy) = _displaced(p, joint, alpha, t1, t2, t3, t4)
            out[f"dC_{joint}_{alpha}"] = np.hypot(ex, ey)
            out[f"dx_C_{joint}_{alpha}"], out[f"dy_C_{joint}_{alpha}"] = ex, ey
            if joint in "AE":   # coupler end B or D moved by +delta: C's error normal to D' - B'
                case = f"{'B' if joint == 'A' else 'D'}_{alpha}"
                gx, gy = dx - bx, dy - by
                g = np.hypot(gx, gy)
                en = (ey * gx - ex * gy) / g
                beta = (gx * (c_y - by) - gy * (c_x - bx)) / g   # C - B' across D' - B'
                out[f"en_{case}"], out[f"g_{case}"], out[f"beta_{case}"] = en, g, beta
                # along D' - B': C' - C from the solved loop; where the moved circles
                # (B', l_2) and (D', l_3) do not meet (no C'), where their radical line
                # crosses D' - B', less C's own place (a difference of lengths: used only
                # there, it would lose the digits of a tiny r_clear)
                w_a = ((c_x - bx) * gx + (c_y - by) * gy) / g
                radical = (g * g + p["l_2"] ** 2 - p["l_3"] ** 2) / (2.0 * g) - w_a
                ea = np.where(np.isfinite(en), (ex * gx + ey * gy) / g, radical)
                out[f"ea_{case}"] = ea
                # C' = C + ea along + en across on the circle (B', l_2):
                # en^2 + 2 beta en + gamma = 0, gamma = (w_a + ea)^2 + beta^2 - l_2^2
                out[f"gamma_{case}"] = np.where(np.isfinite(en), -(en * en + 2.0 * beta * en),
                                                (w_a + ea) ** 2 - p["l_2"] ** 2 + beta * beta)
    return out


def solve(p: Mapping[str, float], phi_deg: np.ndarray,
          options: Mapping[str, object]) -> dict[str, np.ndarray]:
    """Every Table column of the five-bar for path angles phi (deg)."""
    phi = np.radians(np.asarray(phi_deg, dtype=float))
    x_0, y_0, l_5 = p["x_0"], p["y_0"], p["l_5"]
    c_x = x_0 + p["R_path"] * np.cos(phi)
    c_y = y_0 + p["R_path"] * np.sin(phi)
    t1, t2 = _dyad(c_x, c_y, 0.0, p["l_1"], p["l_2"], left=True)
    t4, t3 = _dyad(c_x, c_y, l_5, p["l_4"], p["l_3"], left=False)
    psi_a = wrap_deg(np.arctan2(c_y, c_x), np.degrees(np.arctan2(y_0, x_0)) - 180.0)
    psi_e = wrap_deg(np.arctan2(c_y, c_x - l_5), np.degrees(np.arctan2(y_0, x_0 - l_5)) - 180.0)
    out = {"x_C": c_x, "y_C": c_y, "psi_AC": psi_a, "psi_EC": psi_e,
           "d_AC": np.hypot(c_x, c_y), "d_EC": np.hypot(c_x - l_5, c_y)}
    # crank angles continuous: pivot->C direction plus the elbow angle within (0, 180) deg
    theta_1 = psi_a + wrap_deg(t1 - np.radians(psi_a), -180.0)
    theta_4 = psi_e + wrap_deg(t4 - np.radians(psi_e), -180.0)
    x_b, y_b = p["l_1"] * np.cos(t1), p["l_1"] * np.sin(t1)
    x_d, y_d = l_5 + p["l_4"] * np.cos(t4), p["l_4"] * np.sin(t4)
    out |= {"x_B": x_b, "y_B": y_b, "x_D": x_d, "y_D": y_d,
            "h_B": (c_x * y_b - c_y * x_b) / out["d_AC"],
            "h_D": -((c_x - l_5) * (y_d) - c_y * (x_d - l_5)) / out["d_EC"],
            "det_BCD": (c_x - x_b) * (c_y - y_d) - (c_y - y_b) * (c_x - x_d)}
    out["cross_BCD"] = out["det_BCD"]   # the workbook's det_BCD is 0 where it flags "singular"
    if options.get("method", "closed") == "newton":
        steps = int(options.get("iterations", ITERATIONS))
        ones = _newton_iterates(c_x, c_y, 0.0, p["l_1"], p["l_2"],
                                np.where(np.isfinite(t1), psi_a + 90.0, np.nan), steps)
        fours = _newton_iterates(c_x, c_y, l_5, p["l_4"], p["l_3"],
                                 np.where(np.isfinite(t4), psi_e - 90.0, np.nan), steps)
        for j in range(steps + 1):
            out[f"th1_{j}"], out[f"th4_{j}"] = ones[j], fours[j]
        # theta_1 / theta_4 are the exact angles where the model's own k-th step moved by
        # at most CONVERGED_DEG; elsewhere "not converged": no angle, nor anything from it
        with np.errstate(invalid="ignore"):
            moved_1 = ~(np.abs(ones[-1] - ones[-2]) <= CONVERGED_DEG)
            moved_4 = ~(np.abs(fours[-1] - fours[-2]) <= CONVERGED_DEG)
        theta_1, theta_4 = np.where(moved_1, np.nan, theta_1), np.where(moved_4, np.nan, theta_4)
        t1, t4 = np.where(moved_1, np.nan, t1), np.where(moved_4, np.nan, t4)
        for name in ("x_B", "y_B"):
            out[name] = np.where(moved_1, np.nan, out[name])
        for name in ("x_D", "y_D"):
            out[name] = np.where(moved_4, np.nan, out[name])
        out["det_BCD"] = np.where(moved_1 | moved_4, np.nan, out["det_BCD"])
        out["cross_BCD"] = out["det_BCD"]
    out["theta_1"], out["theta_4"] = theta_1, theta_4
    out |= _sensitivity(p, t1, t2, t3, t4)
    out |= _clearance(p, t1, t2, t3, t4, c_x, c_y)
    return out
