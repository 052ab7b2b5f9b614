"""Which tabulated positions differentiate to which analytic rate columns.

A chain ``Chain(position, velocity, acceleration)`` says that the velocity
column is the time derivative of the position column and the acceleration
column the derivative of the velocity.  The input runs at a constant rate
(the parameter ``rate``): the crank angle in deg at omega [rad/s], so
d/dt = omega * 180/pi * d/dtheta_deg; the actuator's length at v_s [1/s], so
d/dt = v_s * d/ds.  An angle tabulated in deg is converted to rad before it is
compared with a rate in rad/s.

    sewing_machine   y_C -> v_C -> a_C, s_FE -> v_FE -> a_FE, theta_5 -> omega_5 -> alpha_5,
                     x_G -> vx_G -> ax_G, y_G -> vy_G -> ay_G              (rate omega_1)
    slider_crank     s_C -> v_C -> a_C, theta_2 -> omega_2 -> alpha_2      (rate omega_1)
    four_bar,        theta_3 -> omega_3 -> alpha_3, theta_4 -> omega_4 -> alpha_4,
    walking_beam     x_C -> vx_C -> ax_C, y_C -> vy_C -> ay_C              (rate omega_2)
    actuator_linkage phi_2 -> omega_2 -> alpha_2, phi_3 -> omega_3 -> alpha_3 (rate v_s)
    five_bar         none: a position-only template

A template not listed has no chains: the derivative dimension is reported as
not applicable.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Chain:
    position: str
    velocity: str
    acceleration: str


def _chains(*triples: str) -> tuple[Chain, ...]:
    return tuple(Chain(*t.split()) for t in triples)


_FOUR_BAR = ("omega_2", _chains("theta_3 omega_3 alpha_3", "theta_4 omega_4 alpha_4",
                                "x_C vx_C ax_C", "y_C vy_C ay_C"))
CHAINS: dict[str, tuple[str, tuple[Chain, ...]]] = {
    "sewing_machine": ("omega_1", _chains("y_C v_C a_C", "s_FE v_FE a_FE",
                                          "theta_5 omega_5 alpha_5", "x_G vx_G ax_G",
                                          "y_G vy_G ay_G")),
    "slider_crank": ("omega_1", _chains("s_C v_C a_C", "theta_2 omega_2 alpha_2")),
    "four_bar": _FOUR_BAR,
    "walking_beam": _FOUR_BAR,
    "actuator_linkage": ("v_s", _chains("phi_2 omega_2 alpha_2", "phi_3 omega_3 alpha_3")),
}


def chains_for(template, requested: tuple[str, ...]) -> tuple[str | None, tuple[Chain, ...]]:
    """The rate parameter and the chains whose three columns the scene requests."""
    rate, chains = CHAINS.get(template.id, (None, ()))
    have = set(requested)
    return rate, tuple(c for c in chains if {c.position, c.velocity, c.acceleration} <= have)


def time_factor(template, parameters) -> float:
    """d/dt per d/d(input): the rate, times 180/pi for an input in degrees."""
    rate, _ = CHAINS[template.id]
    factor = float(parameters[rate])
    return factor * 180.0 / math.pi if template.input.unit == "deg" else factor


def position_factor(template, name: str) -> float:
    """Converts a tabulated position to the unit its rates use (deg -> rad)."""
    return math.pi / 180.0 if template.quantity(name).unit == "deg" else 1.0


def differences(y: np.ndarray, h: float, scheme: str) -> tuple[np.ndarray, np.ndarray]:
    """First and second derivative of samples ``y`` at spacing ``h``, on the rows where
    the scheme is defined (NaN elsewhere). ``central``: (y+ - y-)/2h and
    (y+ - 2y + y-)/h^2; ``forward``: (y+ - y)/h and (y++ - 2y+ + y)/h^2."""
    d1, d2 = np.full(len(y), np.nan), np.full(len(y), np.nan)
    if scheme == "central":
        d1[1:-1] = (y[2:] - y[:-2]) / (2 * h)
        d2[1:-1] = (y[2:] - 2 * y[1:-1] + y[:-2]) / h ** 2
    elif scheme == "forward":
        d1[:-1] = (y[1:] - y[:-1]) / h
        d2[:-2] = (y[2:] - 2 * y[1:-1] + y[:-2]) / h ** 2
    else:
        raise ValueError(f"unknown difference scheme {scheme!r}")
    return d1, d2
