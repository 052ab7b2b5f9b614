"""Sine and cosine of an angle in degrees, exact at multiples of 90 and accurate near them.

SIN(RADIANS(180)) is 1.2e-16, not 0, and near 180 or 360 deg the sine keeps only
the absolute accuracy of pi's rounding: 1e-6 deg from 360 it has 8 digits.  Here
the angle is first reduced, exactly, to u in [-180, 180] (theta - 360 is exact
for theta in [180, 720] by Sterbenz's lemma), then to [-90, 90] for the sine
(180 - u is exact for u in [90, 180]), so the argument of SIN is the exact
distance to the nearest multiple of 180 deg, and SIN of it has full relative
accuracy.  The cosine is the sine of 90 - |u| (exact where |u| >= 45).
"""

from __future__ import annotations

from ..expr import Node, abs_, if_, le, gt, mod, radians, sign, sin


def reduced(theta: Node) -> Node:
    """theta - 360 k in [-180, 180], exact for |theta| <= 540 (MOD beyond)."""
    return if_(le(abs_(theta), 180), theta,
               if_(le(abs_(theta), 540), theta - sign(theta) * 360,
                   mod(theta + 180, 360) - 180))


def sin_deg(theta: Node) -> Node:
    """SIN of theta (deg), accurate relative to its value near multiples of 180."""
    u = reduced(theta)
    return sin(radians(if_(gt(abs_(u), 90), sign(u) * 180 - u, u)))


def cos_deg(theta: Node) -> Node:
    """COS of theta (deg), accurate relative to its value near odd multiples of 90."""
    return sin(radians(90 - abs_(reduced(theta))))


def sin_half_squared(theta: Node) -> Node:
    """sin^2(theta/2), accurate near theta = 0 (mod 360)."""
    return sin(radians(reduced(theta)) / 2) ** 2


def cos_half_squared(theta: Node) -> Node:
    """cos^2(theta/2), accurate near theta = 180 (mod 360)."""
    return sin(radians(abs_(reduced(theta)) - 180) / 2) ** 2
