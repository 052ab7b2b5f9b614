"""Full shaking-force balance of a four-bar by counterweights on crank and rocker
(docs/mechanisms.md, Shaking force and balance).

Linearly independent vectors method (Berkof and Lowen, 1969): with complex numbers for
the plane and each link's centre of mass written z = u + i v in its own frame (crank from
O1 along O1->A, coupler from A along A->B, rocker from O2 along O2->B), the loop
A + l_AB e_3 = O2 + l_O2B e_4 eliminates e_3, and

    sum m_i S_i = const + [m_2 z_2 + m_3 l_O1A (1 - z_3 / l_AB)] e_2
                        + [m_4 z_4 + m_3 l_O2B z_3 / l_AB] e_4.

That is, the coupler's mass is shared between A (factor 1 - z_3/l_AB) and B (z_3/l_AB).
e_2 and e_4 are linearly independent over the motion, so the total centre of mass stands
still exactly when both brackets vanish.  A counterweight m_cw at z_cw on each link makes
them vanish:  m_cw z_cw = W  with

    W_crank  = -(m_2 z_2 + m_3 l_O1A (1 - z_3 / l_AB)),
    W_rocker = -(m_4 z_4 + m_3 l_O2B z_3 / l_AB).

The designer chooses the counterweight's radius ``r_cw_crank`` / ``r_cw_rocker`` (parameters,
default: the link's length); then m_cw = |W| / r_cw and its angle from the link's direction
is ATAN2(W_x, W_y), counter-clockwise.  Mass and angle are formulas over the parameters,
shown on the Summary sheet, and written into the counterweights' columns, so the balance
follows any edit of a length or mass in the workbook.
"""

from __future__ import annotations

from typing import Mapping

from ..errors import SceneError
from ..expr import Node, Param, atan2, degrees, eq, if_, sqrt, wrap
from .base import Derived, Mass, ParamSpec, PointMass, Template

_LINKS = ("crank", "coupler", "rocker")
_LENGTHS = ("l_O1A", "l_AB", "l_O2B")


def _mass(masses: Mapping[str, Mass], link: str) -> tuple[Node, Node, Node]:
    """m, u, v of a link as parameter nodes; a link without a mass counts as massless."""
    if link in masses:
        return Param(f"m_{link}"), Param(f"u_{link}"), Param(f"v_{link}")
    zero = wrap(0)
    return zero, zero, zero


def required_moments(masses: Mapping[str, Mass]) -> dict[str, tuple[Node, Node]]:
    """W = m_cw z_cw (kg * length) for the crank's and the rocker's counterweight."""
    a, b, c = (Param(n) for n in _LENGTHS)
    m2, u2, v2 = _mass(masses, "crank")
    m3, u3, v3 = _mass(masses, "coupler")
    m4, u4, v4 = _mass(masses, "rocker")
    return {
        "crank": (-(m2 * u2 + m3 * a * (1 - u3 / b)), -(m2 * v2 - m3 * a * v3 / b)),
        "rocker": (-(m4 * u4 + m3 * c * u3 / b), -(m4 * v4 + m3 * c * v3 / b)),
    }


def counterweights(template: Template, masses: Mapping[str, Mass]):
    """(parameters, point masses, derived values) of the balancing counterweights: the
    radius is a parameter; mass, angle and position are derived values, live formulas
    on the Parameters sheet that the counterweight's columns refer to by name."""
    links = {link.name: link for link in template.links}
    params = {p.name: p for p in template.parameters}
    if not set(_LINKS) <= set(links) or not set(_LENGTHS) <= set(params):
        raise SceneError(f"{template.id}: balance = true needs a four-bar's crank, coupler "
                         f"and rocker")
    specs, points, derived = [], [], []
    pivots = {"crank": ("l_O1A", "O1->A"), "rocker": ("l_O2B", "O2->B")}
    for link, (wx, wy) in required_moments(masses).items():
        length, direction = pivots[link]
        name = f"cw_{link}"
        unit = params[length].unit
        r_cw, mx, my, m_cw = (Param(f"{p}_{name}") for p in ("r", "mx", "my", "m"))
        specs.append(ParamSpec(f"r_{name}", params[length].default, unit,
                               f"balancing counterweight on the {link}: its radius from the "
                               f"pivot (its mass and angle follow below)", positive=True))
        derived += [
            Derived(f"mx_{name}", f"kg*{unit}", wx, f"mass moment the counterweight supplies "
                    f"along the {link} (Berkof-Lowen full force balance)"),
            Derived(f"my_{name}", f"kg*{unit}", wy,
                    f"mass moment the counterweight supplies to the left of the {link}"),
            Derived(f"m_{name}", "kg", sqrt(mx ** 2 + my ** 2) / r_cw,
                    f"counterweight mass on the {link}"),
            Derived(f"phi_{name}", "deg", if_(eq(m_cw, 0), 0, degrees(atan2(mx, my))),
                    f"counterweight angle on the {link}, from the direction {direction}"),
            Derived(f"u_{name}", unit, if_(eq(m_cw, 0), r_cw, mx / m_cw),
                    f"counterweight position along the {link}"),
            Derived(f"v_{name}", unit, if_(eq(m_cw, 0), 0, my / m_cw),
                    f"counterweight position to the left of the {link}"),
        ]
        points.append(PointMass(name, links[link], Param(f"m_{name}"), Param(f"u_{name}"),
                                Param(f"v_{name}"), f"counterweight on the {link}"))
    return tuple(specs), points, tuple(derived)
