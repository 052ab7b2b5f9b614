"""A 50-digit reference for the walking beam (the eight-bar of templates/walking_beam.toml),
independent of the trees, in the manner of mp_reference.py.

The eight-bar is solved whole: the four-bar O1 A B O2 (unknowns theta_3, theta_4), its
copy with ground pivots at (l_CD, 0) and (l_O1O2 + l_CD, 0) whose crank turns in phase
(the parallelogram; unknowns theta_3', theta_4'), and the beam from C, the coupler point
of the first, to D, the coupler point of the copy (unknowns theta_7 and its length L):
C + L e(theta_7) = D.  Six closure equations in six unknowns; the start is the law of
cosines at 50 digits for each four-bar and the beam read off C and D, polished by Newton
with the analytic Jacobian.  Rates from the differentiated constraints, J q' = -Phi_t and
J q'' = -d^2/dtau^2 Phi(q + q' tau, t + tau), written out by hand (and checked against
mp_reference.rates' numerical derivatives in tests/mechanisms/test_walking_beam_limits.py).
D is the copy's own coupler point, so x_D, y_D check the beam rather than restate it.
"""

from __future__ import annotations

import mpmath
from mpmath import mpf

OUTPUT_RATES = ("omega_3", "omega_4", "alpha_3", "alpha_4", "vx_C", "vy_C", "ax_C", "ay_C")


class EightBar:
    """The closure Phi(q, t), its Jacobian J and the rates, for one set of parameters."""

    def __init__(self, p):
        (self.g, self.a, self.b, self.c, self.l_ac, delta, self.w, self.l_cd) = (
            mpf(p[k]) for k in ("l_O1O2", "l_O1A", "l_AB", "l_O2B", "l_AC", "delta_C",
                                "omega_2", "l_CD"))
        self.dl = mpmath.radians(delta)

    def point(self, shift, t, th3):
        """The coupler point of the four-bar whose ground starts at (shift, 0)."""
        return (shift + self.a * mpmath.cos(t) + self.l_ac * mpmath.cos(th3 + self.dl),
                self.a * mpmath.sin(t) + self.l_ac * mpmath.sin(th3 + self.dl))

    def phi(self, q, t):
        g, a, b, c = self.g, self.a, self.b, self.c
        th3, th4, th3c, th4c, th7, length = q
        out = []
        for t3, t4 in ((th3, th4), (th3c, th4c)):   # the copy's shift cancels
            out += [a * mpmath.cos(t) + b * mpmath.cos(t3) - g - c * mpmath.cos(t4),
                    a * mpmath.sin(t) + b * mpmath.sin(t3) - c * mpmath.sin(t4)]
        cx, cy = self.point(0, t, th3)
        dx, dy = self.point(self.l_cd, t, th3c)
        return out + [cx + length * mpmath.cos(th7) - dx, cy + length * mpmath.sin(th7) - dy]

    def jacobian(self, q):
        b, c, l_ac = self.b, self.c, self.l_ac
        th3, th4, th3c, th4c, th7, length = q
        J = mpmath.zeros(6, 6)
        for row, (col3, col4, t3, t4) in ((0, (0, 1, th3, th4)), (2, (2, 3, th3c, th4c))):
            J[row, col3], J[row, col4] = -b * mpmath.sin(t3), c * mpmath.sin(t4)
            J[row + 1, col3], J[row + 1, col4] = b * mpmath.cos(t3), -c * mpmath.cos(t4)
        J[4, 0], J[5, 0] = -l_ac * mpmath.sin(th3 + self.dl), l_ac * mpmath.cos(th3 + self.dl)
        J[4, 2], J[5, 2] = l_ac * mpmath.sin(th3c + self.dl), -l_ac * mpmath.cos(th3c + self.dl)
        J[4, 4], J[5, 4] = -length * mpmath.sin(th7), length * mpmath.cos(th7)
        J[4, 5], J[5, 5] = mpmath.cos(th7), mpmath.sin(th7)
        return J

    def polish(self, q, t):
        for _ in range(60):
            r = mpmath.matrix(self.phi(q, t))
            if mpmath.norm(r) < mpf(10) ** -45:
                break
            try:
                step = mpmath.lu_solve(self.jacobian(q), r)
            except ZeroDivisionError:   # exactly at a toggle: the construction stands
                break
            q = [q[i] - step[i] for i in range(6)]
        return q

    def rates(self, q, t):
        """(q', q'') in time, or (None, None) where J is singular (mp_reference's rule)."""
        from mp_reference import SINGULAR
        a, b, c, l_ac, dl = self.a, self.b, self.c, self.l_ac, self.dl
        J = self.jacobian(q)
        scale = max(abs(J[i, j]) for i in range(6) for j in range(6))
        if abs(mpmath.det(J)) <= SINGULAR * scale ** 6:
            return None, None
        st, ct = mpmath.sin(t), mpmath.cos(t)
        qd = mpmath.lu_solve(J, -mpmath.matrix([-a * st, a * ct, -a * st, a * ct, 0, 0]))
        th3, th4, th3c, th4c, th7, length = q
        gam = []
        for t3, t4, d3, d4 in ((th3, th4, qd[0], qd[1]), (th3c, th4c, qd[2], qd[3])):
            gam += [-a * ct - b * mpmath.cos(t3) * d3 ** 2 + c * mpmath.cos(t4) * d4 ** 2,
                    -a * st - b * mpmath.sin(t3) * d3 ** 2 + c * mpmath.sin(t4) * d4 ** 2]
        d7, dl_ = qd[4], qd[5]
        for f, sign in ((mpmath.cos, -1), (mpmath.sin, 1)):
            other = mpmath.sin if f is mpmath.cos else mpmath.cos
            gam.append(-l_ac * f(th3 + dl) * qd[0] ** 2 + l_ac * f(th3c + dl) * qd[2] ** 2
                       + sign * 2 * dl_ * d7 * other(th7) - length * d7 ** 2 * f(th7))
        qdd = mpmath.lu_solve(J, -mpmath.matrix(gam))
        return [qd[j] * self.w for j in range(6)], [qdd[j] * self.w ** 2 for j in range(6)]


def construction(m: EightBar, t, side):
    """Newton's start: each four-bar by the law of cosines in its own frame, the beam read
    off C and D; None where a loop does not close."""
    q = []
    for shift in (0, m.l_cd):
        ax, ay = shift + m.a * mpmath.cos(t), m.a * mpmath.sin(t)
        d = mpmath.hypot(shift + m.g - ax, ay)
        cos_b = (m.b ** 2 + d ** 2 - m.c ** 2) / (2 * m.b * d)
        if abs(cos_b) > 1:
            return None
        th3 = mpmath.atan2(-ay, shift + m.g - ax) + side * mpmath.acos(cos_b)
        bx, by = ax + m.b * mpmath.cos(th3), ay + m.b * mpmath.sin(th3)
        q += [th3, mpmath.atan2(by, bx - shift - m.g)]
    cx, cy = m.point(0, t, q[0])
    dx, dy = m.point(m.l_cd, t, q[2])
    return q + [mpmath.atan2(dy - cy, dx - cx), mpmath.hypot(dx - cx, dy - cy)]


def walking_beam(p, theta_deg, branch="open"):
    """(row, singular) for one crank angle (deg); (None, False) where it cannot assemble."""
    m = EightBar(p)
    side = 1 if branch == "open" else -1
    t = mpmath.radians(mpf(theta_deg))
    q0 = construction(m, t, side)
    if q0 is None:
        return None, False
    q = m.polish(q0, t)
    qd, qdd = m.rates(q, t)
    th3, th4, th3c = q[0], q[1], q[2]
    cx, cy = m.point(0, t, th3)
    dx, dy = m.point(m.l_cd, t, th3c)
    out = {"theta_3": mpmath.degrees(th3), "theta_4": mpmath.degrees(th4),
           "x_C": cx, "y_C": cy, "x_D": dx, "y_D": dy,
           "mu": mpmath.degrees(mpmath.atan2(abs(mpmath.sin(th3 - th4)),
                                             abs(mpmath.cos(th3 - th4)))),
           "theta_7": mpmath.degrees(q[4]), "l_beam": q[5]}
    if qd is None:
        return out | dict.fromkeys(OUTPUT_RATES + ("omega_7", "alpha_7")), True
    w3, w4, a3, a4 = qd[0], qd[1], qdd[0], qdd[1]
    tc = th3 + m.dl
    ct, st = mpmath.cos(tc), mpmath.sin(tc)
    ax, ay, w = m.a * mpmath.cos(t), m.a * mpmath.sin(t), m.w
    return out | {
        "omega_3": w3, "omega_4": w4, "alpha_3": a3, "alpha_4": a4,
        "vx_C": -w * ay - m.l_ac * w3 * st, "vy_C": w * ax + m.l_ac * w3 * ct,
        "ax_C": -w ** 2 * ax - m.l_ac * (a3 * st + w3 ** 2 * ct),
        "ay_C": -w ** 2 * ay + m.l_ac * (a3 * ct - w3 ** 2 * st),
        "omega_7": qd[4], "alpha_7": qdd[4]}, False
