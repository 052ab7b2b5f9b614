"""Reference solution of the spatial 4-DOF parallel mechanism (docs/mechanisms.md, parallel_4dof),
shared with no tree.

Positions: the platform's rotation is applied as three successive axis rotations
(Rodrigues' formula about x, then y, then z; no matrix entries written out), P5 is e_x
turned about the hinge axis, and each leg's drive angle is the root of
|P_i - O_i2(theta)|^2 - l_i2^2 = 0 found by batched Newton from twelve starts, O_i2 being
O_i1 plus l_i1 times e_z turned about the hinge axis zeta_i1 by theta.  The branch is the
side of the platform joint: '+' where (P_i - O_i1).eta_i1 < 0 (eta_i1 = zeta_i1 x xi_i1),
'-' where it is > 0.  Reporting convention (not a formula): theta_i1 within 180 deg of the
direction of P_i - O_i1 in the leg's plane (from e_z towards xi at 90 deg), on the branch's
side.  Centres of mass are placed in each link's frame and summed with their masses.

Rates by complex-step differentiation: every position (pose, rotation, P5, P_i, and
theta_i1 by two more Newton steps from the real root) is recomputed at the complex path
parameter t + i h, h = 1e-30 rad; the rate is Im(f(t + i h)) / h, exact to rounding (no
difference is taken, so nothing cancels).  ``rates_mpmath`` gives the same rates by a
central difference at 50 digits in mpmath (slow; the tests cross-check a few rows).
"""

from __future__ import annotations

import math
from typing import Mapping

import mpmath
import numpy as np

from ..mechanisms.parallel_4dof_params import counterweight_parameters, parameters

DEFAULTS = {p.name: p.default for p in parameters() + counterweight_parameters()}
DEFAULTS.update({f"{c}_c{i}": 0.0 for i in (1, 2, 3, 4) for c in "uv"})
DEFAULTS.update({"u_cP": 0.0, "v_cP": 0.0, "w_cP": 0.0, "s_c5": 0.0})
LEGS = (1, 2, 3, 4)
LENGTHS = ("l_5",) + tuple(f"l_{i}{k}" for i in LEGS for k in (1, 2))
TAKES_OPTIONS = True
DIGITS = 50
H = mpmath.mpf("1e-20")
STARTS_DEG = tuple(range(-165, 195, 30))
CLOSURE_TOL = 1e-12
COMPLEX_STEP = 1e-30


# --- vector algebra on 3-tuples (numpy arrays or mpmath numbers) ---------------------
def _dot(u, w):
    return u[0] * w[0] + u[1] * w[1] + u[2] * w[2]


def _cross(u, w):
    return (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])


def _lin(*pairs):
    """sum k u over (k, u)."""
    return tuple(sum(k * u[j] for k, u in pairs) for j in range(3))


def _turn(v, axis, angle, lib):
    """v turned by ``angle`` (rad) about the unit ``axis`` (Rodrigues)."""
    c, s = lib.cos(angle), lib.sin(angle)
    k = _dot(axis, v)
    kv = _cross(axis, v)
    return tuple(v[j] * c + kv[j] * s + axis[j] * k * (1 - c) for j in range(3))


E_X, E_Y, E_Z = (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)
MINUS_Y = (0.0, -1.0, 0.0)


class _Geometry:
    """Poses and points of the mechanism for parameters ``p``, in numpy or mpmath."""

    def __init__(self, p: Mapping[str, float], lib):
        self.p, self.lib = p, lib
        conv = (lambda x: mpmath.mpf(x)) if lib is mpmath else float
        self.c = {k: conv(v) for k, v in p.items()}

    def rad(self, deg):
        return deg * (self.lib.pi / 180)

    def pose(self, t):
        """(alpha, psi, vartheta, phi) in radians at the path parameter t (rad)."""
        c, sin, cos = self.c, self.lib.sin, self.lib.cos
        quarter = self.lib.pi / 4
        return (self.rad(c["alpha_0"] + c["A_alpha"] * sin(t)),
                self.rad(c["A_psi"] * sin(t + quarter)),
                self.rad(c["A_vartheta"] * cos(t)),
                self.rad(c["A_phi"] * sin(2 * t)))

    def rotate(self, pose, v):
        """Q v, Q = Rz(psi) Ry(vartheta) Rx(phi): about x first, then y, then z."""
        _, psi, vartheta, phi = pose
        v = _turn(v, E_X, phi, self.lib)
        v = _turn(v, E_Y, vartheta, self.lib)
        return _turn(v, E_Z, psi, self.lib)

    def p5(self, pose):
        return _lin((self.c["l_5"], _turn(E_X, MINUS_Y, pose[0], self.lib)))

    def on_platform(self, pose, coords):
        a5 = (self.c["a_5"], self.c["b_5"], self.c["c_5"])
        r = self.rotate(pose, tuple(coords[j] - a5[j] for j in range(3)))
        return _lin((1, self.p5(pose)), (1, r))

    def joint(self, pose, i):
        c = self.c
        return self.on_platform(pose, (c[f"a_{i}"], c[f"b_{i}"], c[f"c_{i}"]))

    def hinge(self, i):
        c = self.c
        g = self.rad(c[f"gamma_{i}"])
        zeta = (self.lib.cos(g), self.lib.sin(g), 0 * g)
        return (c[f"x_{i}0"], c[f"y_{i}0"], c[f"z_{i}0"]), zeta

    def link_frame(self, i, theta):
        """(xi, eta, zeta) of link i1 at drive angle theta (rad)."""
        _, zeta = self.hinge(i)
        xi = _turn(E_Z, zeta, theta, self.lib)
        return xi, _cross(zeta, xi), zeta

    def elbow(self, i, theta):
        o1, _ = self.hinge(i)
        xi = self.link_frame(i, theta)[0]
        return _lin((1, o1), (self.c[f"l_{i}1"], xi))

    def gap(self, i, theta, joint):
        """|P_i - O_i2|^2 - l_i2^2 and its derivative in theta."""
        o2 = self.elbow(i, theta)
        _, eta, _ = self.link_frame(i, theta)
        d = tuple(joint[j] - o2[j] for j in range(3))
        return _dot(d, d) - self.c[f"l_{i}2"] ** 2, -2 * self.c[f"l_{i}1"] * _dot(d, eta)


def _solve_leg(g: _Geometry, i: int, joint, sign: float) -> np.ndarray:
    """Drive angle (rad) of leg i on the branch, batched Newton; NaN out of reach."""
    rows = joint[0].shape[0]
    scale = g.c[f"l_{i}1"] + g.c[f"l_{i}2"]
    best = np.full(rows, np.nan)
    o1, _ = g.hinge(i)
    d = tuple(joint[j] - o1[j] for j in range(3))
    for start in STARTS_DEG:
        if not np.isnan(best).any():
            break
        theta = np.full(rows, math.radians(start))
        with np.errstate(all="ignore"):
            quiet = 0
            for _ in range(60):
                f, df = g.gap(i, theta, joint)
                step = np.clip(np.where(df != 0, f / df, 0.0), -0.5, 0.5)
                theta = theta - step
                quiet = quiet + 1 if np.nanmax(np.abs(step)) < 1e-15 else 0
                if quiet > 1:
                    break
            f, _ = g.gap(i, theta, joint)
            eta = g.link_frame(i, theta)[1]
            side = _dot(d, eta) * sign < 0
            ok = (np.abs(f) <= CLOSURE_TOL * scale ** 2) & side & np.isnan(best)
        best[ok] = theta[ok]
    return best


def _report(theta, d_z, d_h, sign):
    """theta within [0, 180] deg of the direction of d in the leg's plane, on its side."""
    direction = np.arctan2(d_h, d_z)
    if sign > 0:
        return direction + np.mod(theta - direction, 2 * np.pi)
    return direction - np.mod(direction - theta, 2 * np.pi)


def _mp_theta(g: _Geometry, i: int, joint, theta0: float):
    theta = mpmath.mpf(theta0)
    for _ in range(12):
        f, df = g.gap(i, theta, joint)
        step = f / df
        theta -= step
        if abs(step) < mpmath.mpf(10) ** (-DIGITS + 5):
            break
    return theta


def _mp_positions(g: _Geometry, t, thetas: dict[int, float]) -> list:
    """Every quantity whose rate the Table shows, at t (rad), in mpmath: the pose (4), Q
    row by row (9), P5's x and z, then per leg P_i's x, y, z and theta_i1 (0 where out
    of reach)."""
    pose = g.pose(t)
    out = list(pose)
    cols = [g.rotate(pose, e) for e in (E_X, E_Y, E_Z)]
    out += [cols[c][r] for r in range(3) for c in range(3)]     # Q_rc, row by row
    p5 = g.p5(pose)
    out += [p5[0], p5[2]]
    for i in LEGS:
        joint = g.joint(pose, i)
        out += list(joint)
        out.append(_mp_theta(g, i, joint, thetas[i]) if i in thetas else mpmath.mpf(0))
    return out


def _positions(g: _Geometry, t, thetas: dict[int, np.ndarray]) -> list:
    """As _mp_positions, for arrays (complex: the complex step), theta_i1 by two Newton
    steps from the real roots ``thetas`` (NaN out of reach)."""
    pose = g.pose(t)
    out = list(pose)
    cols = [g.rotate(pose, e) for e in (E_X, E_Y, E_Z)]
    out += [cols[c][r] for r in range(3) for c in range(3)]
    p5 = g.p5(pose)
    out += [p5[0], p5[2]]
    for i in LEGS:
        joint = g.joint(pose, i)
        out += list(joint)
        theta = thetas[i].astype(complex)
        with np.errstate(all="ignore"):
            for _ in range(3):
                f, df = g.gap(i, theta, joint)
                theta = theta - f / df
        out.append(theta)
    return out


def _rates(p, t_rad: np.ndarray, thetas: dict[int, np.ndarray]) -> np.ndarray:
    """d/dt of _positions per row (rows, n), by the complex step."""
    g = _Geometry(p, np)
    values = _positions(g, t_rad + 1j * COMPLEX_STEP, thetas)
    return np.stack([np.imag(v) / COMPLEX_STEP for v in values], axis=1)


def rates_mpmath(p, t_rad: np.ndarray, thetas: dict[int, np.ndarray]) -> np.ndarray:
    """d/dt of _mp_positions per row (rows, n), by a central difference at 50 digits."""
    rows = []
    with mpmath.workdps(DIGITS):
        g = _Geometry(p, mpmath)
        for r, t in enumerate(t_rad):
            start = {i: float(v[r]) for i, v in thetas.items() if np.isfinite(v[r])}
            t = mpmath.mpf(float(t))
            ahead, back = _mp_positions(g, t + H, start), _mp_positions(g, t - H, start)
            rows.append([float((a - b) / (2 * H)) for a, b in zip(ahead, back)])
    return np.array(rows).reshape(len(t_rad), -1)


def solve(p: Mapping[str, float], t_deg: np.ndarray,
          options: Mapping[str, object]) -> dict[str, np.ndarray]:
    """Every Table column at the path parameters ``t_deg``."""
    g = _Geometry(p, np)
    t = np.radians(np.asarray(t_deg, dtype=float))
    out, thetas = positions(p, g.pose(t), options)
    _add_rates(out, p, t, float(p["omega_t"]), thetas)
    return out


def positions(p: Mapping[str, float], pose, options: Mapping[str, object]):
    """Every position column at the poses ``pose`` = (alpha, psi, vartheta, phi) in
    radians (arrays), and the drive angles as solved (rad, NaN out of reach)."""
    branch = str(options.get("branch", "++++"))
    balance = bool(options.get("balance", False))
    g = _Geometry(p, np)
    t = pose[0]
    out: dict[str, np.ndarray] = {}
    for name, angle in zip(("alpha", "psi", "vartheta", "phi"), pose):
        out[name] = np.degrees(angle)
    for c, e in enumerate((E_X, E_Y, E_Z), start=1):
        col = g.rotate(pose, e)
        for r in range(3):
            out[f"Q_{r + 1}{c}"] = col[r]
    p5 = g.p5(pose)
    out["x_P5"], out["z_P5"] = p5[0], p5[2]
    masses = []                                   # (mass, position) of every mass
    thetas = {}
    for i, s in zip(LEGS, branch):
        sign = 1.0 if s == "+" else -1.0
        joint = g.joint(pose, i)
        for axis, v in zip("xyz", joint):
            out[f"{axis}_P{i}"] = v
        o1, _ = g.hinge(i)
        d = tuple(joint[j] - o1[j] for j in range(3))
        across = g.link_frame(i, np.full_like(t, np.pi / 2))[0]
        l1, l2 = p[f"l_{i}1"], p[f"l_{i}2"]
        out[f"A_{i}"], out[f"B_{i}"] = d[2], _dot(d, across)
        out[f"C_{i}"] = (_dot(d, d) - l2 * l2 + l1 * l1) / (2 * l1)
        out[f"K_{i}"] = out[f"A_{i}"] ** 2 + out[f"B_{i}"] ** 2 - out[f"C_{i}"] ** 2
        theta = _solve_leg(g, i, joint, sign)
        thetas[i] = theta
        out[f"theta_{i}1"] = np.degrees(_report(theta, d[2], out[f"B_{i}"], sign))
        o2 = g.elbow(i, theta)
        for axis, v in zip("xyz", o2):
            out[f"{axis}_O{i}2"] = v
        xi, eta, zeta = g.link_frame(i, theta)
        com1 = _lin((1, o1), (p[f"u_{i}1"], xi), (p[f"v_{i}1"], eta), (p[f"w_{i}1"], zeta))
        rod = tuple(joint[j] - o2[j] for j in range(3))
        length = np.sqrt(_dot(rod, rod))
        com2 = _lin((1, o2), (p[f"xi_{i}"] / length, rod))
        masses += [(f"S{i}1", p[f"m_{i}1"], com1), (f"S{i}2", p[f"m_{i}2"], com2)]
        if balance:
            masses.append((f"Sc{i}", p[f"m_c{i}"],
                           _lin((1, o1), (p[f"u_c{i}"], xi), (p[f"v_c{i}"], eta))))
    e_alpha = _turn(E_X, MINUS_Y, pose[0], np)
    masses += [("SP", p["m_P"], g.on_platform(pose, (p["u_P"], p["v_P"], p["w_P"]))),
               ("S5", p["m_5"], _lin((p["l_5c"], e_alpha)))]
    if balance:
        masses += [("ScP", p["m_cP"], g.on_platform(pose, (p["u_cP"], p["v_cP"], p["w_cP"]))),
                   ("Sc5", p["m_c5"], _lin((p["s_c5"], e_alpha)))]
    total = sum(m for _, m, _ in masses)
    for k, axis in enumerate("xyz"):
        for stem, _, r in masses:
            out[f"{axis}_{stem}"] = r[k]
        out[f"{axis}_S"] = sum(m * r[k] for _, m, r in masses) / total
    return out, thetas


def _add_rates(out, p, t, w, thetas) -> None:
    rates = _rates(p, t, thetas) * w
    names = ["alpha_dot", "psi_dot", "vartheta_dot", "phi_dot"]
    q_dot = rates[:, 4:13]
    for k, name in enumerate(names):
        out[name] = rates[:, k]
    # angular velocity from Q' Q^T = [w]x (Q from the reference's own rotation)
    qm = np.stack([np.stack([out[f"Q_{r}{c}"] for c in (1, 2, 3)], axis=-1)
                   for r in (1, 2, 3)], axis=-2)
    qd = q_dot.reshape(-1, 3, 3)
    spin = qd @ np.swapaxes(qm, -1, -2)
    out["w_x"], out["w_y"], out["w_z"] = spin[:, 2, 1], spin[:, 0, 2], spin[:, 1, 0]
    out["vx_P5"], out["vz_P5"] = rates[:, 13], rates[:, 14]
    for k, i in enumerate(LEGS):
        base = 15 + 4 * k
        out[f"vx_P{i}"], out[f"vy_P{i}"], out[f"vz_P{i}"] = rates[:, base:base + 3].T
        out[f"omega_{i}1"] = np.where(np.isfinite(thetas[i]), rates[:, base + 3], np.nan)
