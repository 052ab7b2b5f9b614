"""A 50-digit reference for the extreme-case tests
(docs/stability.md, Numerical soundness at the extremes), independent of the trees.

Each mechanism writes its closure equations Phi(q, x) = 0 once, in mpmath; a
textbook construction (law of cosines, at 50 digits) gives the start and
``findroot`` polishes it on the closure.  Rates come from the differentiated
constraints, J q' = -Phi_x and J q'' = -d^2/dtau^2 Phi(q + q' tau, x + tau),
with J and the derivatives by ``mpmath.diff`` at 50 digits, times the input
rate (omega or v_s; zero input acceleration).  A row whose Jacobian is
singular to 30 digits has no rates (None): it must be flagged by the template.

``solve(mechanism, params, inputs, options) -> (columns, singular)``: columns
maps an output name to a list of mpf or None per row (None: cannot assemble),
singular is a list of bools.  Angles in degrees unless the template says rad.
Nothing here imports workbook_gen.mechanisms or workbook_gen.expr.
"""

from __future__ import annotations

from typing import Callable, Mapping, Sequence

import mpmath
from mpmath import mp, mpf

import mp_parallel_4dof

DPS = 50
SINGULAR = mpf(10) ** -30   # |det J| over the scale of J: below this a row is singular


def _jacobian(phi, q, x):
    n = len(q)
    J = mpmath.matrix(n, n)
    for j in range(n):
        def along(v, j=j):
            qq = list(q)
            qq[j] = v
            return phi(qq, x)
        for i in range(n):
            J[i, j] = mpmath.diff(lambda v, i=i: along(v)[i], q[j])
    return J


def rates(phi, q: Sequence[mpf], x: mpf, rate: mpf):
    """(q', q'') in time, or (None, None) where J is singular."""
    n = len(q)
    J = _jacobian(phi, q, x)
    scale = max(abs(J[i, j]) for i in range(n) for j in range(n)) or mpf(1)
    if abs(mpmath.det(J)) <= SINGULAR * scale ** n:
        return None, None
    px = mpmath.matrix([mpmath.diff(lambda v, i=i: phi(q, v)[i], x) for i in range(n)])
    qd = mpmath.lu_solve(J, -px)
    gamma = mpmath.matrix([
        mpmath.diff(lambda tau, i=i: phi([q[j] + qd[j] * tau for j in range(n)], x + tau)[i],
                    0, 2) for i in range(n)])
    qdd = mpmath.lu_solve(J, -gamma)
    return [qd[j] * rate for j in range(n)], [qdd[j] * rate ** 2 for j in range(n)]


def polish(phi, q0: Sequence[mpf], x: mpf, scale: mpf) -> list[mpf]:
    """Newton on the closure from the construction (which is already close)."""
    try:
        if len(q0) == 1:
            q = [mpmath.findroot(lambda a: phi([a], x)[0], q0[0], tol=mpf(10) ** -90,
                                 verify=False)]
        else:
            q = list(mpmath.findroot(lambda *a: phi(list(a), x), list(q0),
                                     tol=mpf(10) ** -90, verify=False))
    except ZeroDivisionError:   # J singular at the start: exactly at a limit
        return list(q0)
    if max(abs(r) for r in phi(q, x)) > mpf(10) ** -35 * scale:
        q = list(q0)   # a double root (exact singularity): the construction stands
    return q


def _deg(v):
    return None if v is None else mpmath.degrees(v)


def _angle_near(angle, centre):
    """angle + 2 pi k within pi of centre."""
    return centre + mpmath.atan2(mpmath.sin(angle - centre), mpmath.cos(angle - centre))


# ---------------------------------------------------------------- slider_crank
def slider_crank(p, theta_deg):
    l_ab, l_bc, e, phs, w = (mpf(p[k]) for k in ("l_AB", "l_BC", "e", "phi_slide", "omega_1"))
    ph = mpmath.radians(phs)
    ux, uy = mpmath.cos(ph), mpmath.sin(ph)

    def phi(q, t):
        s, th2 = q
        return [l_ab * mpmath.cos(t) + l_bc * mpmath.cos(th2) - s * ux + e * uy,
                l_ab * mpmath.sin(t) + l_bc * mpmath.sin(th2) - s * uy - e * ux]

    t = mpmath.radians(mpf(theta_deg))
    ub, nb = l_ab * mpmath.cos(t - ph), l_ab * mpmath.sin(t - ph)
    if abs(e - nb) > l_bc:
        return None, False
    rel = mpmath.asin((e - nb) / l_bc)
    q = polish(phi, [ub + l_bc * mpmath.cos(rel), ph + rel], t, l_ab + l_bc + abs(e))
    qd, qdd = rates(phi, q, t, w)
    out = {"s_C": q[0], "theta_2": mpmath.degrees(_angle_near(q[1], ph))}
    sing = qd is None
    out |= {"v_C": None if sing else qd[0], "a_C": None if sing else qdd[0],
            "omega_2": None if sing else qd[1], "alpha_2": None if sing else qdd[1]}
    return out, sing


# ---------------------------------------------------------------- sewing_machine
def sewing_machine(p, theta_deg):
    l_ab, l_bc, l_be, beta, xf, yf, l_fg, w = (mpf(p[k]) for k in (
        "l_AB", "l_BC", "l_BE", "beta_E", "x_F", "y_F", "l_FG", "omega_1"))
    b = mpmath.radians(beta)

    def phi(q, t):
        yc, th2, s, th5 = q
        bx, by = l_ab * mpmath.cos(t), l_ab * mpmath.sin(t)
        ex = bx + l_be * mpmath.cos(th2 + b)
        ey = by + l_be * mpmath.sin(th2 + b)
        return [bx + l_bc * mpmath.cos(th2), by + l_bc * mpmath.sin(th2) - yc,
                ex - xf - s * mpmath.cos(th5), ey - yf - s * mpmath.sin(th5)]

    t = mpmath.radians(mpf(theta_deg))
    bx, by = l_ab * mpmath.cos(t), l_ab * mpmath.sin(t)
    if abs(bx) > l_bc:
        return None, False
    th2 = mpmath.atan2(-mpmath.sqrt(l_bc ** 2 - bx ** 2), -bx)
    ex, ey = bx + l_be * mpmath.cos(th2 + b), by + l_be * mpmath.sin(th2 + b)
    ref = mpmath.atan2(-yf, -xf)
    th5 = _angle_near(mpmath.atan2(ey - yf, ex - xf), ref)
    q0 = [by + l_bc * mpmath.sin(th2), th2, mpmath.hypot(ex - xf, ey - yf), th5]
    q = polish(phi, q0, t, l_ab + l_bc + abs(xf) + abs(yf))
    qd, qdd = rates(phi, q, t, w)
    th5 = q[3]
    c5, s5 = mpmath.cos(th5), mpmath.sin(th5)
    out = {"y_C": q[0], "s_FE": q[2], "theta_5": mpmath.degrees(th5),
           "x_G": xf + l_fg * c5, "y_G": yf + l_fg * s5}
    if qd is None:
        return out | dict.fromkeys(("v_C", "a_C", "v_FE", "a_FE", "omega_5", "alpha_5", "vx_G",
                                    "vy_G", "ax_G", "ay_G")), True
    w5, a5 = qd[3], qdd[3]
    return out | {
        "v_C": qd[0], "a_C": qdd[0], "v_FE": qd[2], "a_FE": qdd[2], "omega_5": w5,
        "alpha_5": a5, "vx_G": -l_fg * w5 * s5, "vy_G": l_fg * w5 * c5,
        "ax_G": -l_fg * (a5 * s5 + w5 ** 2 * c5), "ay_G": l_fg * (a5 * c5 - w5 ** 2 * s5)}, False


# ---------------------------------------------------------------- four_bar
def four_bar(p, theta_deg, branch="open"):
    g, a, b, c, l_ac, delta, w = (mpf(p[k]) for k in (
        "l_O1O2", "l_O1A", "l_AB", "l_O2B", "l_AC", "delta_C", "omega_2"))
    dl = mpmath.radians(delta)

    def phi(q, t):
        th3, th4 = q
        return [a * mpmath.cos(t) + b * mpmath.cos(th3) - g - c * mpmath.cos(th4),
                a * mpmath.sin(t) + b * mpmath.sin(th3) - c * mpmath.sin(th4)]

    t = mpmath.radians(mpf(theta_deg))
    ax, ay = a * mpmath.cos(t), a * mpmath.sin(t)
    d = mpmath.hypot(g - ax, ay)
    if d == 0:   # A on O2 (crank = ground at 0 deg): B anywhere on a circle, or nowhere
        return (None, False) if b != c else ({}, True)
    cos_b = (b ** 2 + d ** 2 - c ** 2) / (2 * b * d)     # angle at A between A->O2 and A->B
    if abs(cos_b) > 1:
        return None, False
    side = 1 if branch == "open" else -1
    th3 = mpmath.atan2(-ay, g - ax) + side * mpmath.acos(cos_b)
    bx, by = ax + b * mpmath.cos(th3), ay + b * mpmath.sin(th3)
    q0 = [th3, mpmath.atan2(by, bx - g)]
    try:
        q = polish(phi, q0, t, a + b + c + g)
    except ZeroDivisionError:   # exactly at a toggle: the construction stands
        q = q0
    qd, qdd = rates(phi, q, t, w)
    th3, th4 = q
    tc = th3 + dl
    out = {"theta_3": mpmath.degrees(th3), "theta_4": mpmath.degrees(th4),
           "x_C": ax + l_ac * mpmath.cos(tc), "y_C": ay + l_ac * mpmath.sin(tc),
           "mu": mpmath.degrees(mpmath.atan2(abs(mpmath.sin(th3 - th4)),
                                             abs(mpmath.cos(th3 - th4))))}
    if qd is None:
        return out | dict.fromkeys(("omega_3", "omega_4", "alpha_3", "alpha_4", "vx_C", "vy_C",
                                    "ax_C", "ay_C")), True
    w3, w4, a3, a4 = qd[0], qd[1], qdd[0], qdd[1]
    ct, st = mpmath.cos(tc), mpmath.sin(tc)
    return out | {
        "omega_3": w3, "omega_4": w4, "alpha_3": a3, "alpha_4": a4,
        "vx_C": -w * ay - l_ac * w3 * st, "vy_C": w * ax + l_ac * w3 * ct,
        "ax_C": -w ** 2 * ax - l_ac * (a3 * st + w3 ** 2 * ct),
        "ay_C": -w ** 2 * ay + l_ac * (a3 * ct - w3 ** 2 * st)}, False


# ---------------------------------------------------------------- actuator_linkage
def actuator_linkage(p, s_bc):
    xa, ya, xb, yb, l1, l1c, vs = (mpf(p[k]) for k in (
        "x_A", "y_A", "x_B", "y_B", "l_A1", "l_A1C", "v_s"))

    def lever(f):
        return (xa + l1 * mpmath.cos(f) + l1c * mpmath.sin(f),
                ya + l1 * mpmath.sin(f) - l1c * mpmath.cos(f))

    def phi(q, s):
        f2, f3 = q
        cx, cy = lever(f2)
        return [cx - xb - s * mpmath.cos(f3), cy - yb - s * mpmath.sin(f3)]

    s = mpf(s_bc)
    ab = mpmath.hypot(xb - xa, yb - ya)
    r = mpmath.hypot(l1, l1c)
    cos_a = (ab ** 2 + r ** 2 - s ** 2) / (2 * ab * r)
    if abs(cos_a) > 1:
        return None, False
    dir_ab = mpmath.atan2(yb - ya, xb - xa)
    phi_ac = dir_ab + mpmath.acos(cos_a)          # C left of A->B
    f2 = phi_ac + mpmath.atan2(l1c, l1)
    cx, cy = lever(f2)
    q = polish(phi, [f2, mpmath.atan2(cy - yb, cx - xb)], s, ab + r + s)
    qd, qdd = rates(phi, q, s, vs)
    f2, f3 = q
    cx, cy = lever(f2)
    phi_ac = _angle_near(mpmath.atan2(cy - ya, cx - xa), dir_ab)
    gam = mpmath.atan2(abs((xa - cx) * (yb - cy) - (ya - cy) * (xb - cx)),
                       (xa - cx) * (xb - cx) + (ya - cy) * (yb - cy))
    out = {"phi_AC": phi_ac, "phi_2": phi_ac + _angle_near(f2 - phi_ac, mpf(0)),
           "phi_3": _angle_near(f3, dir_ab + mpmath.pi), "gamma": gam, "x_C": cx, "y_C": cy}
    if qd is None:
        return out | dict.fromkeys(("omega_2", "alpha_2", "omega_3", "alpha_3")), True
    return out | {"omega_2": qd[0], "alpha_2": qdd[0], "omega_3": qd[1],
                  "alpha_3": qdd[1]}, False


def actuator_bisection(p, s_bc, halvings):
    """The paper's halving at 50 digits: phi_2_iter (None: not converged), halvings_used."""
    xa, ya, xb, yb, l1, l1c, eps = (mpf(p[k]) for k in (
        "x_A", "y_A", "x_B", "y_B", "l_A1", "l_A1C", "epsilon"))
    s = mpf(s_bc)

    def f(v):
        cx = xa + l1 * mpmath.cos(v) + l1c * mpmath.sin(v)
        cy = ya + l1 * mpmath.sin(v) - l1c * mpmath.cos(v)
        return (cx - xb) ** 2 + (cy - yb) ** 2 - s ** 2

    lo, hi = mpf(p["phi_lo"]), mpf(p["phi_hi"])
    f_lo = f(lo)
    for k in range(1, halvings + 1):
        mid = (lo + hi) / 2
        fk = f(mid)
        if abs(fk) < eps:
            return {"phi_2_iter": mid, "halvings_used": mpf(k)}
        if f_lo * fk < 0:
            hi = mid
        else:
            lo = mid
    return {"phi_2_iter": None, "halvings_used": mpf(halvings)}


# ---------------------------------------------------------------- five_bar
def five_bar(p, phi_deg):
    l1, l2, l3, l4, l5, x0, y0, rp = (mpf(p[k]) for k in (
        "l_1", "l_2", "l_3", "l_4", "l_5", "x_0", "y_0", "R_path"))
    v = mpmath.radians(mpf(phi_deg))
    cx, cy = x0 + rp * mpmath.cos(v), y0 + rp * mpmath.sin(v)

    def phi(q, _):
        t1, t4 = q
        return [(cx - l1 * mpmath.cos(t1)) ** 2 + (cy - l1 * mpmath.sin(t1)) ** 2 - l2 ** 2,
                (cx - l5 - l4 * mpmath.cos(t4)) ** 2 + (cy - l4 * mpmath.sin(t4)) ** 2 - l3 ** 2]

    da, de = mpmath.hypot(cx, cy), mpmath.hypot(cx - l5, cy)
    ca = (l1 ** 2 + da ** 2 - l2 ** 2) / (2 * l1 * da)
    ce = (l4 ** 2 + de ** 2 - l3 ** 2) / (2 * l4 * de)
    if abs(ca) > 1 or abs(ce) > 1:
        return None, False
    t1 = _angle_near(mpmath.atan2(cy, cx), mpmath.atan2(y0, x0)) + mpmath.acos(ca)
    t4 = _angle_near(mpmath.atan2(cy, cx - l5), mpmath.atan2(y0, x0 - l5)) - mpmath.acos(ce)
    q = polish(phi, [t1, t4], v, l1 + l2 + l3 + l4 + l5)
    t1, t4 = q
    bx, by = l1 * mpmath.cos(t1), l1 * mpmath.sin(t1)
    dx, dy = l5 + l4 * mpmath.cos(t4), l4 * mpmath.sin(t4)
    out = {"theta_1": mpmath.degrees(t1), "theta_4": mpmath.degrees(t4)}
    # Sensitivity: C(l) with the inputs held, by implicit differentiation of
    # F(C, l) = (|C - B(l)|^2 - l_2^2, |C - D(l)|^2 - l_3^2) = 0.
    lengths = [l1, l2, l3, l4, l5]

    def closure(c, ls):
        b = (ls[0] * mpmath.cos(t1), ls[0] * mpmath.sin(t1))
        d = (ls[4] + ls[3] * mpmath.cos(t4), ls[3] * mpmath.sin(t4))
        return [(c[0] - b[0]) ** 2 + (c[1] - b[1]) ** 2 - ls[1] ** 2,
                (c[0] - d[0]) ** 2 + (c[1] - d[1]) ** 2 - ls[2] ** 2]

    J = _jacobian(lambda c, _: closure(c, lengths), [cx, cy], None)
    singular = abs(mpmath.det(J)) <= SINGULAR * max(abs(J[i, j]) for i in range(2)
                                                     for j in range(2)) ** 2
    for i in range(5):
        def moved(h, i=i):
            ls = list(lengths)
            ls[i] = h
            return closure([cx, cy], ls)
        col = mpmath.matrix([mpmath.diff(lambda h, k=k: moved(h)[k], lengths[i])
                             for k in range(2)])
        sx = None if singular else mpmath.lu_solve(J, -col)
        out[f"S_x_l{i + 1}"] = None if singular else sx[0]
        out[f"S_y_l{i + 1}"] = None if singular else sx[1]
    # Clearance: C re-solved with one coupler end moved (exact, not linearised).
    r = mpf(p["r_clear"])
    # issue 12's convention: A/E +r u (B resp. D moves by +r u), B -r u, C and D: D by -r u
    for joint, (end, turn) in {"A": ("B", 0), "B": ("B", 180), "C": ("D", 180),
                               "D": ("D", 180), "E": ("D", 0)}.items():
        for alpha in (0, 90, 180, 270):
            al = mpmath.radians(alpha + turn)
            dlt = (r * mpmath.cos(al), r * mpmath.sin(al))
            b2 = (bx + dlt[0], by + dlt[1]) if end == "B" else (bx, by)
            d2 = (dx + dlt[0], dy + dlt[1]) if end == "D" else (dx, dy)

            def moved_c(*c, b2=b2, d2=d2):
                return [(c[0] - b2[0]) ** 2 + (c[1] - b2[1]) ** 2 - l2 ** 2,
                        (c[0] - d2[0]) ** 2 + (c[1] - d2[1]) ** 2 - l3 ** 2]
            try:
                c2 = mpmath.findroot(moved_c, [cx, cy], tol=mpf(10) ** -90)
                out[f"dC_{joint}_{alpha}"] = mpmath.hypot(c2[0] - cx, c2[1] - cy)
                out[f"dx_C_{joint}_{alpha}"] = c2[0] - cx
                out[f"dy_C_{joint}_{alpha}"] = c2[1] - cy
            except (ValueError, ZeroDivisionError):
                for name in ("dC", "dx_C", "dy_C"):
                    out[f"{name}_{joint}_{alpha}"] = None
    return out, singular


_SOLVERS: dict[str, Callable] = {
    "slider_crank": slider_crank, "sewing_machine": sewing_machine, "four_bar": four_bar,
    "actuator_linkage": actuator_linkage, "five_bar": five_bar}


def solve(mechanism: str, params: Mapping[str, float], inputs, options=None):
    """(columns, singular) per row at 50 digits; None where the row cannot assemble."""
    options = options or {}
    columns: dict[str, list] = {}
    singular: list[bool] = []
    with mp.workdps(DPS):
        for x in inputs:
            if mechanism == "four_bar":
                row, sing = four_bar(params, x, options.get("branch", "open"))
            elif mechanism == "parallel_4dof":
                row, sing = mp_parallel_4dof.solve(params, x, options)
            elif mechanism == "walking_beam":
                from mp_walking_beam import walking_beam
                row, sing = walking_beam(params, x, options.get("branch", "open"))
            else:
                row, sing = _SOLVERS[mechanism](params, x)
            if row is not None and mechanism == "actuator_linkage" and \
                    options.get("method") == "bisection":
                row |= actuator_bisection(params, x, int(options.get("halvings", 20)))
            singular.append(sing)
            for name, value in (row or {}).items():
                columns.setdefault(name, [None] * (len(singular) - 1)).append(value)
            for name, values in columns.items():
                if len(values) < len(singular):
                    values.append(None)
    return columns, singular


# ---------------------------------------------------------------- comparison
ANGLE_PERIOD = {"deg": 360.0, "rad": 2 * 3.141592653589793}


def scene_at(mechanism: str, params: Mapping[str, float], inputs, options=None,
             outputs: Sequence[str] | None = None):
    """A scene of ``mechanism`` whose Table rows are exactly ``inputs``."""
    import dataclasses

    from workbook_gen.scene import Sweep, parse_scene

    lines = [f'name = "extreme"', f'mechanism = "{mechanism}"', "[parameters]"]
    lines += [f"{k} = {float(v)!r}" for k, v in params.items()]
    if outputs:
        lines += ["[outputs]", "quantities = [" + ", ".join(f'"{o}"' for o in outputs) + "]"]
    if options:
        lines.append("[options]")
        for k, v in options.items():
            lines.append(f"{k} = " + (f'"{v}"' if isinstance(v, str) else
                                      str(v).lower() if isinstance(v, bool) else str(v)))
    scene = parse_scene("\n".join(lines), "extreme.toml")
    values = [float(x) for x in inputs]

    class Points(Sweep):
        @property
        def rows(self) -> int:
            return len(values)

        def values(self) -> list[float]:
            return values

    return dataclasses.replace(scene, sweep=Points(values[0], values[-1], 1.0))


def measure(mechanism: str, params: Mapping[str, float], inputs, options=None,
            outputs: Sequence[str] | None = None):
    """Worst error of each output column against the 50-digit reference, over the column's
    magnitude (rows flagged by the status, or errors where the reference is singular, are
    skipped), and the rows that are singular but neither flagged nor errors.

    Returns (worst: {name: (error, input)}, unflagged: [(name, input)], status array)."""
    import math

    import numpy as np

    from workbook_gen.tabulate import evaluate

    scene = scene_at(mechanism, params, inputs, options, outputs)
    ev = evaluate(scene)
    ref, singular = solve(mechanism, scene.parameters, ev.inputs, scene.options)
    status = ev.status
    worst: dict[str, tuple[float, float]] = {}
    unflagged: list[tuple[str, float]] = []
    for q in ev.model.outputs():
        if q.name not in ref:
            continue
        ours = ev.columns[q.name]
        vals = np.where(ours.err != 0, np.nan, ours.val).astype(float)
        exact = ref[q.name]
        rows = [i for i in range(len(vals)) if exact[i] is not None and status[i] == "ok"]
        # a column that is zero in exact arithmetic (1e-54 here) is compared absolutely
        magnitude = max(max((abs(float(exact[i])) for i in rows), default=0.0), 1e-30)
        period = ANGLE_PERIOD.get(q.unit) if q.name not in ("below_gamma_min",) else None
        bad, at = 0.0, math.nan
        for i in range(len(vals)):
            if exact[i] is None:
                if singular[i] and status[i] == "ok" and math.isfinite(vals[i]):
                    unflagged.append((q.name, float(ev.inputs[i])))
                continue
            if status[i] != "ok":
                continue
            with mp.workdps(DPS):
                diff = mpf(vals[i]) - exact[i] if math.isfinite(vals[i]) else mpmath.inf
                if period is not None and diff != mpmath.inf:
                    diff = diff - period * mpmath.nint(diff / period)
                err = float(abs(diff)) / magnitude
            if not err <= bad:
                bad, at = err, float(ev.inputs[i])
        worst[q.name] = (bad, at)
    return worst, unflagged, status


def worst_of(worst: Mapping[str, tuple[float, float]]) -> tuple[str, float, float]:
    name = max(worst, key=lambda n: worst[n][0])
    return name, worst[name][0], worst[name][1]
