"""Full shaking-force balance of a four-bar by counterweights on crank and rocker (SPEC 7.7).

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
from .base import Figure, Mass, ParamSpec, Template

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
    """(parameters, point masses, Summary figures) of the balancing counterweights."""
    from .dynamics import PointMass  # dynamics imports this module lazily: no cycle

    links = {link.name: link for link in template.links}
    params = {p.name: p for p in template.parameters}
    if not set(_LINKS) <= set(links) or not set(_LENGTHS) <= set(params):
        raise SceneError(f"{template.id}: balance = true needs a four-bar's crank, coupler "
                         f"and rocker")
    specs, points, figures = [], [], []
    pivots = {"crank": ("l_O1A", "O1->A"), "rocker": ("l_O2B", "O2->B")}
    for link, (wx, wy) in required_moments(masses).items():
        length, direction = pivots[link]
        name = f"cw_{link}"
        r_cw = Param(f"r_{name}")
        norm = sqrt(wx ** 2 + wy ** 2)
        specs.append(ParamSpec(f"r_{name}", params[length].default, params[length].unit,
                               f"balancing counterweight on the {link}: its radius from the "
                               f"pivot (mass and angle follow, Summary sheet)", positive=True))
        m_cw = norm / r_cw
        u_cw = if_(eq(norm, 0), r_cw, r_cw * wx / norm)
        v_cw = if_(eq(norm, 0), 0, r_cw * wy / norm)
        points.append(PointMass(name, links[link], m_cw, u_cw, v_cw,
                                f"counterweight on the {link}"))
        figures += [
            Figure(f"m_{name}: counterweight mass on the {link}", "kg", m_cw,
                   f"full force balance (Berkof-Lowen), at radius r_{name}"),
            Figure(f"phi_{name}: counterweight angle on the {link}", "deg",
                   if_(eq(norm, 0), 0, degrees(atan2(wx, wy))),
                   f"from the direction {direction}, counter-clockwise"),
        ]
    return tuple(specs), points, tuple(figures)
