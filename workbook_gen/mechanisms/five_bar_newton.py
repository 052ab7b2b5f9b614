"""Five-bar inverse kinematics by Newton-Raphson, one pair of columns per step.

The two closure equations f1 = |C - B(theta_1)|^2 - l_2^2 and
f2 = |C - D(theta_4)|^2 - l_3^2 each hold one unknown, so the 2x2 Jacobian is
diagonal and a Newton step on (theta_1, theta_4) is two scalar steps.  Divided by
-2 l_1, f1 is g(t) = (C - A).u(t) - k_B with k_B = (|C - A|^2 + l_1^2 - l_2^2) / (2 l_1)
and g'(t) = (C - A) x u(t), so a step is t <- t - g / g' (t in deg, the step
converted from rad); D likewise with C - E, l_4, l_3.

Start (row-local, crude closed form): the crank perpendicular to the line from
its pivot to C, on the elbows-out side: th1_0 = psi_AC + 90, th4_0 = psi_EC - 90
(#NUM! where C is out of the dyad's reach, which h_B / h_D flag).  From there the
iteration converges monotonically to the elbows-out root, quadratically at the end.
Columns: th1_0, th4_0, th1_1, th4_1, ..., th1_{k-1}, th4_{k-1}, theta_1, theta_4:
``iterations`` = k steps, the k-th is theta_1 / theta_4.
"""

from __future__ import annotations

from typing import Callable

from ..expr import Node, Var, abs_, cos, degrees, gt, if_, iserror, or_, radians, sin
from .base import Quantity, symbols

l_1, l_2, l_3, l_4, l_5 = symbols("l_1 l_2 l_3 l_4 l_5")
x_C, y_C, d_AC, d_EC, psi_AC, psi_EC, h_B, h_D = (
    Var(n) for n in "x_C y_C d_AC d_EC psi_AC psi_EC h_B h_D".split())

#: A row is "not converged" where the last step moved an angle by more than this (deg).
CONVERGED_DEG = 1e-9


def _step(t: Node, cx: Node, cy: Node, d: Node, a: Node, b: Node) -> Node:
    """One Newton step for the crank angle t (deg); C - pivot = (cx, cy), |C - pivot| = d,
    crank a, coupler b."""
    c, s = cos(radians(t)), sin(radians(t))
    k = (d ** 2 + (a - b) * (a + b)) / (2 * a)
    return t - degrees((cx * c + cy * s - k) / (cy * c - cx * s))


def _names(steps: int, which: str) -> list[str]:
    final = {"1": "theta_1", "4": "theta_4"}[which]
    return [f"th{which}_{j}" for j in range(steps)] + [final]


def newton_quantities(steps: int) -> tuple[Quantity, ...]:
    """Guess and ``steps`` Newton steps for both cranks, chained along the row."""
    one, four = _names(steps, "1"), _names(steps, "4")
    out = [
        Quantity(one[0], "deg", if_(iserror(h_B), h_B, psi_AC + 90),
                 "Newton start for theta_1: crank AB perpendicular to A->C, B on the left",
                 output=False),
        Quantity(four[0], "deg", if_(iserror(h_D), h_D, psi_EC - 90),
                 "Newton start for theta_4: crank ED perpendicular to E->C, D on the right",
                 output=False),
    ]
    for j in range(1, steps + 1):
        last = j == steps
        out.append(Quantity(
            one[j], "deg", _step(Var(one[j - 1]), x_C, y_C, d_AC, l_1, l_2),
            "crank AB angle, inverse kinematics by Newton-Raphson (B left of A->C)" if last
            else f"theta_1 after Newton step {j}", output=last))
        out.append(Quantity(
            four[j], "deg", _step(Var(four[j - 1]), x_C - l_5, y_C, d_EC, l_4, l_3),
            "crank ED angle, inverse kinematics by Newton-Raphson (D right of E->C)" if last
            else f"theta_4 after Newton step {j}", output=last))
    return tuple(out)


def newton_status(steps: int, flagged: Callable[[Node], Node]) -> Node:
    """The closed form's flags (``flagged``: cannot assemble, limit, singular), then
    'not converged' (last step above CONVERGED_DEG) or 'ok'."""
    one, four = _names(steps, "1"), _names(steps, "4")
    moved = or_(gt(abs_(Var(one[-1]) - Var(one[-2])), CONVERGED_DEG),
                gt(abs_(Var(four[-1]) - Var(four[-2])), CONVERGED_DEG))
    return flagged(if_(moved, "not converged", "ok"))
