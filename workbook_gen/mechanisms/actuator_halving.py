"""Successive halving of the actuator linkage's constraint (the paper's method).

f(phi) = |C(phi) - B|^2 - s_BC^2 on the bracket [phi_lo, phi_hi].  Halving k
is a visible group of four columns along the row:

    lo_k, hi_k   the bracket (lo_1 = phi_lo, hi_1 = phi_hi)
    mid_k        (lo_k + hi_k) / 2
    f_k          f(mid_k)

and the next bracket keeps the half whose ends differ in sign:
hi_{k+1} = mid_k if f(phi_lo) * f_k < 0, else lo_{k+1} = mid_k.  f keeps the
sign of f(phi_lo) at lo throughout (lo only moves to a midpoint of that sign),
so the sign test against the column ``f_lo`` is the paper's f(lo) * f(mid) < 0.
A row STOPS at the first midpoint with |f_k| < epsilon: from then on the
bracket is carried unchanged (IF on that condition), so mid and f repeat
exactly.  ``phi_2_iter`` is the last midpoint if it was accepted, else #NUM!
(the status says "not converged"); ``halvings_used`` is the first k with
|f_k| < epsilon (the number of halvings, N if none).

Which root: for the paper's defaults f(phi_lo) < 0 and, from the second row
on, f(phi_hi) < 0 as well: the bracket (nearly a full turn) holds both roots,
the lever's (f rising through 0, C left of A->B) and the mirror one (f
falling).  With lo always on the negative side, hi moves only to a positive
midpoint, so the bracket closes on a root where f rises, which is the
lever's branch; the first midpoint 1.57 is positive in every row but the
last, and there the second one (3.105) is.  The reference bisects
independently by the same rule and the tests check it lands on phi_2.  In
general f rises through a root exactly where C is left of A->B, so for other
geometry the rule may close on the mirror root: the status then says
"other branch" (choose phi_lo, phi_hi to suit).
"""

from __future__ import annotations

from functools import reduce

from ..expr import Node, Num, Var, abs_, and_, cos, gt, if_, lt, not_, or_, root, sin
from .base import Quantity, symbols

x_A, y_A, x_B, y_B, l_A1, l_A1C, epsilon, phi_lo, phi_hi = symbols(
    "x_A y_A x_B y_B l_A1 l_A1C epsilon phi_lo phi_hi")
s_BC = Var("s_BC")


def lever_point(phi: Node) -> tuple[Node, Node]:
    """C = A + l_A1 (cos phi, sin phi) + l_A1C (sin phi, -cos phi)."""
    return (x_A + l_A1 * cos(phi) + l_A1C * sin(phi),
            y_A + l_A1 * sin(phi) - l_A1C * cos(phi))


def constraint(phi: Node) -> Node:
    """f(phi) = |C(phi) - B|^2 - s_BC^2."""
    cx, cy = lever_point(phi)
    return (cx - x_B) ** 2 + (cy - y_B) ** 2 - s_BC ** 2


def halving_quantities(n: int) -> tuple[tuple[Quantity, ...], Node, Node]:
    """The columns of ``n`` halvings, halvings_used and phi_2_iter; and the row's
    "converged" and "on the lever's branch" conditions (for the status)."""
    def v(name: str, k: int) -> Var:
        return Var(f"{name}_{k}")

    f_lo = Var("f_lo")
    out = [Quantity("f_lo", "-", constraint(phi_lo), "f at phi_lo (its sign stays at lo)",
                    output=False)]
    for k in range(1, n + 1):
        if k == 1:
            lo, hi = phi_lo, phi_hi
        else:
            f_prev, mid_prev = v("f", k - 1), v("mid", k - 1)
            done = lt(abs_(f_prev), epsilon)
            change = lt(f_lo * f_prev, 0)
            lo = if_(or_(done, change), v("lo", k - 1), mid_prev)
            hi = if_(and_(not_(done), change), mid_prev, v("hi", k - 1))
        out += [
            Quantity(f"lo_{k}", "rad", lo, f"halving {k}: bracket, lower end", output=False),
            Quantity(f"hi_{k}", "rad", hi, f"halving {k}: bracket, upper end", output=False),
            Quantity(f"mid_{k}", "rad", (v("lo", k) + v("hi", k)) / 2, f"halving {k}: midpoint",
                     output=False),
            Quantity(f"f_{k}", "-", constraint(v("mid", k)), f"halving {k}: f at the midpoint",
                     output=False),
        ]
    not_yet = [if_(lt(abs_(v("f", k)), epsilon), 0, 1) for k in range(1, n)]
    used = reduce(lambda a, b: a + b, not_yet, Num(1.0))
    converged = lt(abs_(v("f", n)), epsilon)
    cx, cy = lever_point(v("mid", n))
    on_branch = gt((x_B - x_A) * (cy - y_A) - (y_B - y_A) * (cx - x_A), 0)
    out += [
        Quantity("halvings_used", "", used,
                 "halvings used in this row: the first with |f| < epsilon (N if none)"),
        Quantity("phi_2_iter", "rad", if_(converged, v("mid", n),
                                          root(epsilon - abs_(v("f", n)))),
                 "lever angle by successive halving (#NUM! if |f| >= epsilon after N)"),
    ]
    return tuple(out), converged, on_branch
