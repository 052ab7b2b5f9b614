"""Sine and cosine of an angle in degrees, exact at multiples of 90 and accurate near them.

SIN(RADIANS(180)) is 1.2e-16, not 0, and near 180 or 360 deg the sine keeps only
the absolute accuracy of pi's rounding: 1e-6 deg from 360 it has 8 digits.  Here
the angle is first reduced, exactly, to u in [-180, 180] (theta - 360 is exact
for theta in [180, 720] by Sterbenz's lemma), then to [-90, 90] for the sine
(180 - u is exact for u in [90, 180]), so the argument of SIN is the exact
distance to the nearest multiple of 180 deg, and SIN of it has full relative
accuracy.  The cosine is the sine of 90 - |u| (exact where |u| >= 45).

Templates write the reduced angle as a column of its own (``reduced_input``), so
the cells that use it read ``=l_AB*SIN(RADIANS(90-ABS(B2)))`` rather than
repeating the reduction; the functions below take that reduced angle u.
"""

from __future__ import annotations

from ..expr import Node, Var, abs_, eq, if_, le, gt, mod, radians, sign, sin
from .base import Quantity


def reduced(theta: Node) -> Node:
    """theta - 360 k in [-180, 180], exact for |theta| <= 540 (MOD beyond)."""
    return if_(le(abs_(theta), 180), theta,
               if_(le(abs_(theta), 540), theta - sign(theta) * 360,
                   mod(theta + 180, 360) - 180))


def reduced_input(name: str, theta: Node, what: str) -> tuple[Quantity, Var]:
    """The intermediate column ``name`` = ``theta`` reduced to [-180, 180], and its Var."""
    return (Quantity(name, "deg", reduced(theta), f"{what}, reduced exactly to [-180, 180] "
                     "(sines exact at multiples of 90 deg)", output=False), Var(name))


def sin_deg(u: Node) -> Node:
    """SIN of u (deg, in [-180, 180]), accurate relative to its value near 0 and +-180."""
    return sin(radians(if_(gt(abs_(u), 90), sign(u) * 180 - u, u)))


def cos_deg(u: Node) -> Node:
    """COS of u (deg, in [-180, 180]), accurate relative to its value near +-90."""
    return sin(radians(90 - abs_(u)))


def sin_half_squared(u: Node) -> Node:
    """sin^2(u/2) for u in [-270, 270] (deg), accurate near u = 0."""
    return sin(radians(u) / 2) ** 2


def cos_half_squared(u: Node) -> Node:
    """cos^2(u/2) for u (deg) in [-180, 180], accurate near u = +-180."""
    return sin(radians(abs_(u) - 180) / 2) ** 2


def sin_half_squared_90(u: Node) -> Node:
    """sin^2(u/2) for u in [-180, 180] (deg), accurate near u = 0 and exactly 1/2 at
    u = +-90 (SIN(RADIANS(45))^2 is 0.4999999999999999): a four-bar whose loop closes
    exactly at a crank angle of 90 or 270 deg is then exactly at its toggle there."""
    return if_(eq(abs_(u), 90), 0.5, sin_half_squared(u))


def cos_half_squared_90(u: Node) -> Node:
    """cos^2(u/2) for u in [-180, 180] (deg), accurate near u = +-180, exactly 1/2 at +-90."""
    return if_(eq(abs_(u), 90), 0.5, cos_half_squared(u))
