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
Columns: th1_0, th4_0, th1_1, th4_1, ..., th1_k, th4_k (``iterations`` = k steps), then
theta_1 / theta_4: the k-th iterate where the k-th step moved it by at most CONVERGED_DEG,
else #NUM! (status "not converged"; never an unconverged angle shown as the answer).
"""

from __future__ import annotations

from typing import Callable

from ..expr import Node, Var, abs_, cos, degrees, if_, iserror, le, or_, radians, root, sin
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
    return [f"th{which}_{j}" for j in range(steps + 1)]


def _converged(names: list[str], final: str, crank: str) -> Quantity:
    """The k-th iterate where its step moved the angle by at most CONVERGED_DEG, else
    #NUM! (the square root of a negative number, as the actuator's halving does)."""
    last, before = Var(names[-1]), Var(names[-2])
    moved = abs_(last - before)
    return Quantity(final, "deg", if_(le(moved, CONVERGED_DEG), last, root(CONVERGED_DEG - moved)),
                    f"crank {crank} angle, inverse kinematics by Newton-Raphson: the last "
                    f"iterate, #NUM! where its step still moved more than {CONVERGED_DEG:g} deg")


def newton_quantities(steps: int) -> tuple[Quantity, ...]:
    """Guess and ``steps`` Newton steps for both cranks, chained along the row; theta_1 and
    theta_4 are the last iterates where they converged."""
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
        out.append(Quantity(one[j], "deg", _step(Var(one[j - 1]), x_C, y_C, d_AC, l_1, l_2),
                            f"theta_1 after Newton step {j}", output=False))
        out.append(Quantity(four[j], "deg",
                            _step(Var(four[j - 1]), x_C - l_5, y_C, d_EC, l_4, l_3),
                            f"theta_4 after Newton step {j}", output=False))
    out += [_converged(one, "theta_1", "AB (B left of A->C)"),
            _converged(four, "theta_4", "ED (D right of E->C)")]
    return tuple(out)


def newton_status(steps: int, flagged: Callable[[Node | None], Node]) -> Node:
    """The closed form's flags (``flagged``: cannot assemble, limit, singular), then
    'not converged' (theta_1 or theta_4 #NUM!: the last step above CONVERGED_DEG) or 'ok'."""
    return flagged(or_(iserror(Var("theta_1")), iserror(Var("theta_4"))))
