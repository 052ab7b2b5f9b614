"""A 50-digit reference for the spatial 4-DOF parallel mechanism
(docs/mechanisms.md, parallel_4dof), for the extreme-case tests (issue 21), independent of the trees
and of workbook_gen.reference.

Pose at the path parameter t: alpha = alpha_0 + A_alpha sin t, psi = A_psi sin(t + 45),
vartheta = A_vartheta cos t, phi = A_phi sin 2t (deg); the platform is turned by
Rz(psi) Ry(vartheta) Rx(phi) (matrices multiplied out here at 50 digits) about P5 =
l_5 (cos alpha, 0, sin alpha).  Leg i: link i1 turns about the hinge axis
zeta = (cos gamma, sin gamma, 0) through O_i1, its direction xi(theta) = sin theta h +
cos theta e_z, h = (sin gamma, -cos gamma, 0); the closure |P_i - O_i1 - l_i1 xi|^2 = l_i2^2
is R cos(theta - beta) = C with R, beta the polar form of (d.e_z, d.h): theta = beta +- acos(C/R)
(the branch sign), polished by findroot on the closure itself.  Rates: mpmath.diff of
each position along t at 50 digits, times omega_t (deg of t per rad: 180/pi).  A leg whose
closure has a double root (R^2 - C^2 below 1e-30 of R^2) is singular: its rate is None.
Centres of mass from the link frames; with balance = true the counterweights' positions
come from the paper's 12 conditions solved at 50 digits.

``solve(params, t_deg, options) -> (row, singular)``, as the five-bar's in mp_reference.
"""

from __future__ import annotations

import mpmath
from mpmath import mpf

LEGS = (1, 2, 3, 4)
SINGULAR = mpf(10) ** -30


def _rot(psi, vt, ph):
    cz, sz, cy, sy, cx, sx = (mpmath.cos(psi), mpmath.sin(psi), mpmath.cos(vt),
                              mpmath.sin(vt), mpmath.cos(ph), mpmath.sin(ph))
    rz = mpmath.matrix([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    ry = mpmath.matrix([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    rx = mpmath.matrix([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    return rz * ry * rx


def _pose(c, t):
    """(alpha, psi, vartheta, phi) in rad at t (rad)."""
    r = mpmath.pi / 180
    return (r * (c["alpha_0"] + c["A_alpha"] * mpmath.sin(t)),
            r * c["A_psi"] * mpmath.sin(t + mpmath.pi / 4),
            r * c["A_vartheta"] * mpmath.cos(t),
            r * c["A_phi"] * mpmath.sin(2 * t))


def _points(c, t):
    """P5, Q and the platform joints P_1..P_4 at t (rad)."""
    alpha, psi, vt, ph = _pose(c, t)
    q = _rot(psi, vt, ph)
    p5 = mpmath.matrix([c["l_5"] * mpmath.cos(alpha), 0, c["l_5"] * mpmath.sin(alpha)])
    a5 = mpmath.matrix([c["a_5"], c["b_5"], c["c_5"]])

    def on_platform(a):
        return p5 + q * (mpmath.matrix(a) - a5)
    joints = {i: on_platform([c[f"a_{i}"], c[f"b_{i}"], c[f"c_{i}"]]) for i in LEGS}
    return p5, q, on_platform, joints


def _leg_frame(c, i, theta):
    g = c[f"gamma_{i}"] * mpmath.pi / 180
    zeta = mpmath.matrix([mpmath.cos(g), mpmath.sin(g), 0])
    h = mpmath.matrix([mpmath.sin(g), -mpmath.cos(g), 0])
    xi = mpmath.sin(theta) * h + mpmath.cos(theta) * mpmath.matrix([0, 0, 1])
    eta = mpmath.matrix([zeta[1] * xi[2] - zeta[2] * xi[1], zeta[2] * xi[0] - zeta[0] * xi[2],
                         zeta[0] * xi[1] - zeta[1] * xi[0]])
    return xi, eta, zeta, h


def _theta(c, i, joint, sign):
    """Drive angle (rad) of leg i, and whether the leg is at the edge of its reach;
    (None, False) out of reach."""
    o1 = mpmath.matrix([c[f"x_{i}0"], c[f"y_{i}0"], c[f"z_{i}0"]])
    d = joint - o1
    _, _, _, h = _leg_frame(c, i, mpf(0))
    a, b = d[2], sum(d[k] * h[k] for k in range(3))
    l1, l2 = c[f"l_{i}1"], c[f"l_{i}2"]
    cc = (sum(v ** 2 for v in d) + l1 ** 2 - l2 ** 2) / (2 * l1)
    r2 = a ** 2 + b ** 2
    if cc ** 2 > r2:
        return None, False
    edge = r2 - cc ** 2 <= SINGULAR * r2
    theta = mpmath.atan2(b, a) + sign * mpmath.acos(cc / mpmath.sqrt(r2))
    if not edge:
        def closure(th):
            xi = _leg_frame(c, i, th)[0]
            rod = d - l1 * xi
            return sum(v ** 2 for v in rod) - l2 ** 2
        theta = mpmath.findroot(closure, theta, tol=mpf(10) ** -90, verify=False)
    return theta, edge


def counterweights(c):
    """u_ci, v_ci, u_cP, v_cP, w_cP, s_c5 from the 12 balancing conditions (balance = true)."""
    out = {}
    mu = {i: c[f"m_{i}2"] * c[f"xi_{i}"] / c[f"l_{i}2"] for i in LEGS}
    for i in LEGS:
        out[f"u_c{i}"] = -(c[f"m_{i}1"] * c[f"u_{i}1"] + c[f"m_{i}2"] * c[f"l_{i}1"]
                           * (c[f"l_{i}2"] - c[f"xi_{i}"]) / c[f"l_{i}2"]) / c[f"m_c{i}"]
        out[f"v_c{i}"] = -c[f"m_{i}1"] * c[f"v_{i}1"] / c[f"m_c{i}"]
    for joint, com in (("a", "u"), ("b", "v"), ("c", "w")):
        o = c[f"{joint}_5"]
        moment = c["m_P"] * (c[f"{com}_P"] - o) + sum(mu[i] * (c[f"{joint}_{i}"] - o)
                                                      for i in LEGS)
        out[f"{com}_cP"] = o - moment / c["m_cP"]
    out["s_c5"] = -(c["m_5"] * c["l_5c"] + c["l_5"] * (c["m_P"] + c["m_cP"] + sum(mu.values()))
                    ) / c["m_c5"]
    return out


def _positions(c, t, signs, balance):
    """Every compared position at t (rad): {name: mpf or None}, and the legs at an edge."""
    alpha, psi, vt, ph = _pose(c, t)
    p5, _, on_platform, joints = _points(c, t)
    out = {"alpha": mpmath.degrees(alpha), "psi": mpmath.degrees(psi),
           "vartheta": mpmath.degrees(vt), "phi": mpmath.degrees(ph)}
    masses, edges, reached = [], set(), True
    for i in LEGS:
        joint = joints[i]
        for k, axis in enumerate("xyz"):
            out[f"{axis}_P{i}"] = joint[k]
        theta, edge = _theta(c, i, joint, signs[i])
        if theta is None:
            reached = False
            for name in (f"theta_{i}1", f"x_O{i}2", f"y_O{i}2", f"z_O{i}2"):
                out[name] = None
            continue
        if edge:
            edges.add(i)
        xi, eta, zeta, _ = _leg_frame(c, i, theta)
        o1 = mpmath.matrix([c[f"x_{i}0"], c[f"y_{i}0"], c[f"z_{i}0"]])
        o2 = o1 + c[f"l_{i}1"] * xi
        out[f"theta_{i}1"] = mpmath.degrees(theta)
        for k, axis in enumerate("xyz"):
            out[f"{axis}_O{i}2"] = o2[k]
        masses.append((c[f"m_{i}1"], o1 + c[f"u_{i}1"] * xi + c[f"v_{i}1"] * eta
                       + c[f"w_{i}1"] * zeta))
        masses.append((c[f"m_{i}2"], o2 + (c[f"xi_{i}"] / c[f"l_{i}2"]) * (joint - o2)))
        if balance:
            masses.append((c[f"m_c{i}"], o1 + c[f"u_c{i}"] * xi + c[f"v_c{i}"] * eta))
    e_alpha = mpmath.matrix([mpmath.cos(alpha), 0, mpmath.sin(alpha)])
    masses.append((c["m_P"], on_platform([c["u_P"], c["v_P"], c["w_P"]])))
    masses.append((c["m_5"], c["l_5c"] * e_alpha))
    if balance:
        masses.append((c["m_cP"], on_platform([c["u_cP"], c["v_cP"], c["w_cP"]])))
        masses.append((c["m_c5"], c["s_c5"] * e_alpha))
    total = sum(m for m, _ in masses)
    for k, axis in enumerate("xyz"):
        out[f"{axis}_S"] = (sum(m * r[k] for m, r in masses) / total) if reached else None
    return out, edges


def solve(p, t_deg, options=None):
    """(row, singular) at the path parameter t_deg: positions, and the drive rates and
    joint velocities by 50-digit differentiation along t (None where a leg is singular)."""
    options = options or {}
    branch = str(options.get("branch", "++++"))
    balance = bool(options.get("balance", False))
    c = {k: mpf(v) for k, v in p.items()}
    if balance:
        c |= counterweights(c)
    signs = {i: (1 if s == "+" else -1) for i, s in zip(LEGS, branch)}
    t = mpmath.radians(mpf(t_deg))
    row, edges = _positions(c, t, signs, balance)
    rate = c["omega_t"]               # dt/dtime in rad/s: t in rad here
    for i in LEGS:
        _, _, _, joints = _points(c, t)
        for k, axis in enumerate("xyz"):
            row[f"v{axis}_P{i}"] = rate * mpmath.diff(
                lambda v, k=k, i=i: _points(c, v)[3][i][k], t)
        if row[f"theta_{i}1"] is None or i in edges:
            row[f"omega_{i}1"] = None
            continue
        row[f"omega_{i}1"] = rate * mpmath.diff(
            lambda v, i=i: _theta(c, i, _points(c, v)[3][i], signs[i])[0], t)
    return row, bool(edges)
