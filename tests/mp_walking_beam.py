"""A 50-digit reference for the walking beam (the eight-bar of templates/walking_beam.toml),
independent of the trees, in the manner of mp_reference.py.

The eight-bar is solved whole: the four-bar O1 A B O2 (unknowns theta_3, theta_4), its
copy with ground pivots at (l_CD, 0) and (l_O1O2 + l_CD, 0) whose crank turns in phase
(the parallelogram; unknowns theta_3', theta_4'), and the beam from C, the coupler point
of the first, to D, the coupler point of the copy (unknowns theta_7 and its length L):
C + L e(theta_7) = D.  Six closure equations in six unknowns; the start is the law of
cosines at 50 digits for each four-bar and the beam read off C and D, polished by
``findroot``; the rates come from the differentiated constraints (mp_reference.rates).
D is the copy's own coupler point, so x_D, y_D check the beam rather than restate it.
"""

from __future__ import annotations

import mpmath
from mpmath import mpf

OUTPUT_RATES = ("omega_3", "omega_4", "alpha_3", "alpha_4", "vx_C", "vy_C", "ax_C", "ay_C")


def _coupler_angle(g, a, b, c, shift, t, side):
    """theta_3 by the law of cosines (None where the loop does not close)."""
    ax, ay = shift + a * mpmath.cos(t), a * mpmath.sin(t)
    d = mpmath.hypot(shift + g - ax, ay)
    cos_b = (b ** 2 + d ** 2 - c ** 2) / (2 * b * d)
    if abs(cos_b) > 1:
        return None
    return mpmath.atan2(-ay, shift + g - ax) + side * mpmath.acos(cos_b)


def walking_beam(p, theta_deg, branch="open"):
    """(row, singular) for one crank angle (deg); (None, False) where it cannot assemble."""
    from mp_reference import polish, rates

    g, a, b, c, l_ac, delta, w, l_cd = (mpf(p[k]) for k in (
        "l_O1O2", "l_O1A", "l_AB", "l_O2B", "l_AC", "delta_C", "omega_2", "l_CD"))
    dl = mpmath.radians(delta)
    side = 1 if branch == "open" else -1

    def point(shift, t, th3):
        return (shift + a * mpmath.cos(t) + l_ac * mpmath.cos(th3 + dl),
                a * mpmath.sin(t) + l_ac * mpmath.sin(th3 + dl))

    def phi(q, t):
        th3, th4, th3c, th4c, th7, length = q
        out = []
        for shift, t3, t4 in ((0, th3, th4), (l_cd, th3c, th4c)):
            out += [shift + a * mpmath.cos(t) + b * mpmath.cos(t3) - (shift + g)
                    - c * mpmath.cos(t4),
                    a * mpmath.sin(t) + b * mpmath.sin(t3) - c * mpmath.sin(t4)]
        cx, cy = point(0, t, th3)
        dx, dy = point(l_cd, t, th3c)
        return out + [cx + length * mpmath.cos(th7) - dx, cy + length * mpmath.sin(th7) - dy]

    t = mpmath.radians(mpf(theta_deg))
    starts = []
    for shift in (0, l_cd):
        th3 = _coupler_angle(g, a, b, c, shift, t, side)
        if th3 is None:
            return None, False
        bx, by = shift + a * mpmath.cos(t) + b * mpmath.cos(th3), a * mpmath.sin(t) + \
            b * mpmath.sin(th3)
        starts += [th3, mpmath.atan2(by, bx - shift - g)]
    cx, cy = point(0, t, starts[0])
    dx, dy = point(l_cd, t, starts[2])
    q0 = starts + [mpmath.atan2(dy - cy, dx - cx), mpmath.hypot(dx - cx, dy - cy)]
    q = polish(phi, q0, t, a + b + c + g + abs(l_ac) + l_cd)
    qd, qdd = rates(phi, q, t, w)
    th3, th4, th3c = q[0], q[1], q[2]
    cx, cy = point(0, t, th3)
    dx, dy = point(l_cd, t, th3c)
    out = {"theta_3": mpmath.degrees(th3), "theta_4": mpmath.degrees(th4),
           "x_C": cx, "y_C": cy, "x_D": dx, "y_D": dy,
           "mu": mpmath.degrees(mpmath.atan2(abs(mpmath.sin(th3 - th4)),
                                             abs(mpmath.cos(th3 - th4)))),
           "theta_7": mpmath.degrees(q[4]), "l_beam": q[5]}
    if qd is None:
        return out | dict.fromkeys(OUTPUT_RATES + ("omega_7", "alpha_7")), True
    w3, w4, a3, a4 = qd[0], qd[1], qdd[0], qdd[1]
    tc = th3 + dl
    ct, st = mpmath.cos(tc), mpmath.sin(tc)
    ax, ay = a * mpmath.cos(t), a * mpmath.sin(t)
    return out | {
        "omega_3": w3, "omega_4": w4, "alpha_3": a3, "alpha_4": a4,
        "vx_C": -w * ay - l_ac * w3 * st, "vy_C": w * ax + l_ac * w3 * ct,
        "ax_C": -w ** 2 * ax - l_ac * (a3 * st + w3 ** 2 * ct),
        "ay_C": -w ** 2 * ay + l_ac * (a3 * ct - w3 ** 2 * st),
        "omega_7": qd[4], "alpha_7": qdd[4]}, False
