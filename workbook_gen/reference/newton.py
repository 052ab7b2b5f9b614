"""Generic batched machinery of the reference solver.

A mechanism writes its closure equations Phi(q, d) = 0 once, as a function of
second-order Taylor jets (:class:`Jet`): ``q`` are the unknowns, ``d`` the
driving quantities (crank angle, or a point moved by an earlier stage). From
that one function this module gets, for all sweep rows at once:

- the positions, by Newton-Raphson with the Jacobian read off the jets;
- the velocities, from  J qdot = -(dPhi/dd) ddot;
- the accelerations, from J qddot = -gamma, gamma being the second time
  derivative of Phi along the motion with qddot = 0 (the "Jdot qdot + ..." terms).

Nothing here knows a closed form of any mechanism.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

#: Newton stops when a full sweep of steps is below this times the problem scale.
STEP_TOL = 1e-15
#: A row whose residual stays above this times the scale cannot be assembled.
ASSEMBLY_TOL = 1e-10
#: A row whose normalised Jacobian determinant is below this is singular.
SINGULAR_TOL = 1e-8
MAX_ITER = 100
POLISH_ITER = 2


# ``out[name + NOISE]``: the magnitude a reference value cancelled on the way (its
# rounding is about eps times it); the audit allows it as it allows its own (noise.py).
NOISE = "~noise"

class Jet:
    """Value, first and second time derivative of an array quantity."""

    __slots__ = ("v", "d", "dd")

    def __init__(self, v, d=0.0, dd=0.0):
        self.v = np.asarray(v, dtype=float)
        self.d = np.asarray(d, dtype=float)
        self.dd = np.asarray(dd, dtype=float)

    @staticmethod
    def lift(x) -> "Jet":
        return x if isinstance(x, Jet) else Jet(x)

    def __add__(self, other):
        o = Jet.lift(other)
        return Jet(self.v + o.v, self.d + o.d, self.dd + o.dd)

    __radd__ = __add__

    def __neg__(self):
        return Jet(-self.v, -self.d, -self.dd)

    def __sub__(self, other):
        return self + (-Jet.lift(other))

    def __rsub__(self, other):
        return Jet.lift(other) - self

    def __mul__(self, other):
        o = Jet.lift(other)
        return Jet(
            self.v * o.v,
            self.d * o.v + self.v * o.d,
            self.dd * o.v + 2.0 * self.d * o.d + self.v * o.dd,
        )

    __rmul__ = __mul__


def jcos(x: Jet) -> Jet:
    """cos of a jet."""
    c, s = np.cos(x.v), np.sin(x.v)
    return Jet(c, -s * x.d, -c * x.d * x.d - s * x.dd)


def jsin(x: Jet) -> Jet:
    """sin of a jet."""
    c, s = np.cos(x.v), np.sin(x.v)
    return Jet(s, c * x.d, -s * x.d * x.d + c * x.dd)


Closure = Callable[[Sequence[Jet], Sequence[Jet]], Sequence[Jet]]


def _eval(phi: Closure, q: np.ndarray, dq: np.ndarray, ddq: np.ndarray, drivers, ddrivers):
    """Phi evaluated on jets; returns (values, first, second) as (rows, m) arrays."""
    qj = [Jet(q[:, k], dq[:, k], ddq[:, k]) for k in range(q.shape[1])]
    dj = [Jet(v, d, dd) for (v, d, dd) in zip(drivers, *ddrivers)]
    out = phi(qj, dj)
    shape = (q.shape[0],)

    def stack(part: str) -> np.ndarray:
        return np.stack([np.broadcast_to(getattr(o, part), shape) for o in out], axis=1)

    return stack("v"), stack("d"), stack("dd")


def jacobian(phi: Closure, q: np.ndarray, drivers: Sequence[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Residual (rows, m) and Jacobian dPhi/dq (rows, m, n) at q with drivers held."""
    rows, n = q.shape
    zero = np.zeros_like(q)
    still = ([np.zeros(rows)] * len(drivers), [np.zeros(rows)] * len(drivers))
    res, cols = None, []
    for k in range(n):
        seed = zero.copy()
        seed[:, k] = 1.0
        res, first, _ = _eval(phi, q, seed, zero, drivers, still)
        cols.append(first)
    return res, np.stack(cols, axis=2)


def solve_batched(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solve a[i] x[i] = b[i] per row; returns (x, singular mask). Singular rows get NaN."""
    det = np.linalg.det(a)
    colnorm = np.prod(np.linalg.norm(a, axis=1), axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        rel = np.abs(det) / colnorm
    singular = ~(rel > SINGULAR_TOL)
    safe = np.where(singular[:, None, None], np.eye(a.shape[1]), a)
    x = np.linalg.solve(safe, b[..., None])[..., 0]
    x[singular] = np.nan
    return x, singular


def newton(phi: Closure, q0: np.ndarray, drivers: Sequence[np.ndarray], scale: float) -> tuple[np.ndarray, np.ndarray]:
    """Batched Newton-Raphson on Phi(q, drivers) = 0 from q0 (rows, n).

    Iterates every row until all steps are at rounding level (or MAX_ITER), then
    polishes. Returns (q, assembled mask); rows whose residual is not at rounding
    level are not assembled and their q is NaN.
    """
    q = np.array(q0, dtype=float)
    drivers = [np.asarray(d, dtype=float) for d in drivers]
    quiet = np.zeros(q.shape[0], dtype=int)  # consecutive rounding-level steps per row
    active = np.arange(q.shape[0])
    with np.errstate(invalid="ignore", over="ignore"):
        for _ in range(MAX_ITER):
            qa = q[active]
            res, jac = jacobian(phi, qa, [d[active] for d in drivers])
            ok = np.all(np.isfinite(jac), axis=(1, 2)) & np.all(np.isfinite(res), axis=1)
            det = np.linalg.det(np.where(ok[:, None, None], jac, 0.0))
            good = ok & (det != 0.0)
            safe = np.where(good[:, None, None], jac, np.eye(q.shape[1]))
            step = np.linalg.solve(safe, np.where(good[:, None], res, 0.0)[..., None])[..., 0]
            qa = qa - step
            q[active] = qa
            small = np.max(np.abs(step), axis=1) <= STEP_TOL * (scale + np.max(np.abs(qa), axis=1))
            quiet[active] = np.where(small, quiet[active] + 1, 0)
            # a row is done after POLISH_ITER extra iterations at rounding level, or if hopeless
            active = active[(quiet[active] <= POLISH_ITER) & good]
            if active.size == 0:
                break
        res, _ = jacobian(phi, q, drivers)
    assembled = np.max(np.abs(res), axis=1) <= ASSEMBLY_TOL * scale
    q[~assembled] = np.nan
    return q, assembled


@dataclass
class Motion:
    """Positions, velocities, accelerations of the unknowns, and the masks."""

    q: np.ndarray
    dq: np.ndarray
    ddq: np.ndarray
    assembled: np.ndarray
    singular: np.ndarray

    def jets(self) -> list[Jet]:
        return [Jet(self.q[:, k], self.dq[:, k], self.ddq[:, k]) for k in range(self.q.shape[1])]


def rates(phi: Closure, q: np.ndarray, drivers: Sequence[Jet]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Velocities and accelerations of q given converged positions and driver jets.

    Returns (dq, ddq, singular mask).
    """
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        return _rates(phi, q, drivers)


def _rates(phi, q, drivers):
    rows = q.shape[0]
    dv = [np.broadcast_to(j.v, (rows,)) for j in drivers]
    dd = ([np.broadcast_to(j.d, (rows,)) for j in drivers], [np.broadcast_to(j.dd, (rows,)) for j in drivers])
    zero = np.zeros_like(q)
    _, jac = jacobian(phi, q, dv)
    # with qdot = qddot = 0 the first coefficient is dPhi/dd * ddot
    _, drive, _ = _eval(phi, q, zero, zero, dv, dd)
    dq, sing = solve_batched(jac, -drive)
    # with the true qdot and qddot = 0 the second coefficient is gamma
    _, _, gamma = _eval(phi, q, np.nan_to_num(dq), zero, dv, dd)
    ddq, _ = solve_batched(jac, -gamma)
    ddq[sing] = np.nan
    return dq, ddq, sing


def solve_stage(phi: Closure, q0: np.ndarray, drivers: Sequence[Jet], scale: float,
                fix_branch: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]] | None = None) -> Motion:
    """Positions by Newton, branch check, then rates. Unassembled rows are NaN throughout.

    ``fix_branch(q)`` returns (wrong-branch mask, mirrored guesses); wrong rows are
    solved again from the mirrored guesses and must then be on the branch.
    """
    rows = q0.shape[0]
    dv = [np.broadcast_to(j.v, (rows,)).astype(float) for j in drivers]
    q, assembled = newton(phi, q0, dv, scale)
    if fix_branch is not None:
        wrong, guess = fix_branch(q)
        wrong &= assembled
        if np.any(wrong):
            q2, ok2 = newton(phi, guess[wrong], [d[wrong] for d in dv], scale)
            q[wrong] = q2
            assembled[wrong] = ok2
            still_wrong, _ = fix_branch(q)
            bad = still_wrong & assembled
            q[bad] = np.nan
            assembled &= ~bad
    dq, ddq, sing = rates(phi, q, drivers)
    dq[~assembled] = np.nan
    ddq[~assembled] = np.nan
    return Motion(q, dq, ddq, assembled, sing & assembled)


def wrap_deg(angle_rad: np.ndarray, low_deg: float | np.ndarray) -> np.ndarray:
    """Angle (rad) in degrees, wrapped into (low, low + 360]."""
    deg = np.degrees(angle_rad)
    return low_deg + 360.0 - np.mod(low_deg + 360.0 - deg, 360.0)
