"""Offset slider-crank with an inclined slide line.

Crank pivot A at the origin; the slide line has direction
u = (cos phi_slide, sin phi_slide) and lies at offset e along
n = (-sin phi_slide, cos phi_slide).  In slide coordinates the crank pin is
(u_B, n_B) = l_AB (cos psi, sin psi), psi = theta_1 - phi_slide, and the
slider is at s_C = u_B + h with h = sqrt(l_BC^2 - (e - n_B)^2) > 0 (the
slider ahead of the crank pin), written without cancellation at the dead centres as
h^2 = (l_BC - q)(l_BC + q), l_BC -+ q = (l_BC - l_AB -+ e) + l_AB (1 +- sin psi) and
1 +- sin psi = 2 sin^2((psi +- 90)/2) (angles.py), q = e - n_B.  The rod's angle relative to the slide is
ATAN2(h, e - n_B), within +-90 deg, so theta_2 is continuous.

Rates (q = e - n_B, q' = -omega_1 u_B, q'' = omega_1^2 n_B):
h' = -q q' / h, h'' = -(q'^2 + q q'' + h'^2) / h, omega_2 = q' / h,
alpha_2 = (q'' h - q' h') / h^2.
"""

from __future__ import annotations

from ..expr import (Node, abs_, atan2, cos, degrees, eq, gt, if_, iserror, le, min_, radians,
                    root, sin, sqrt)
from .angles import cos_deg, reduced_input, sin_deg, sin_half_squared
from .base import Check, Figure, InputSpec, Link, ParamSpec, Quantity, Span, Template
from .base import only_if, quantity_vars, slide_charts, speed_scale, symbols, turn_charts

l_AB, l_BC, e, phi_slide, omega_1 = symbols("l_AB l_BC e phi_slide omega_1")
(theta_1, u_B, n_B, f_BC, g_BC, h_BC, dh_BC, ddh_BC, s_C, v_C, a_C, theta_2, omega_2,
 alpha_2) = quantity_vars("theta_1 u_B n_B f_BC g_BC h_BC dh_BC ddh_BC s_C v_C a_C theta_2 omega_2 alpha_2")

w2 = omega_1 ** 2
q = e - n_B

PARAMETERS = (
    ParamSpec("l_AB", 40.0, "mm", "crank AB", positive=True),
    ParamSpec("l_BC", 120.0, "mm", "connecting rod BC", positive=True),
    ParamSpec("e", 10.0, "mm", "offset of the slide line from A, along n"),
    ParamSpec("phi_slide", 0.0, "deg", "direction of the slide line"),
    ParamSpec("omega_1", 10.0, "rad/s", "crank speed, counter-clockwise"),
)

# A reach factor within rounding of 0 is 0: the rod exactly tangent to the slide line
# (l_BC = l_AB + |e| at one crank angle) is a dead centre, flagged, its rates #DIV/0!,
# never the square root of rounding (h_BC 3.8e-7 mm, v_C -1e10 mm/s; see
# docs/stability.md, slider_crank).  The factor's terms round to a few ulps of l_BC + l_AB
# + |e| + 2 l_AB; a true excess of 1e-12 of the lengths is kept (tests/mechanisms/test_slider_crank_extremes.py).
REACH_ROUNDING = 16 * 2.0 ** -52


def _exact_zero(factor: Node) -> Node:
    return if_(le(abs_(factor), REACH_ROUNDING * (l_BC + 3 * l_AB + abs_(e))), 0, factor)


Q = Quantity
PSI, psi = reduced_input("psi", theta_1 - phi_slide, "crank angle from the slide line")
QUANTITIES = (
    PSI,
    Q("u_B", "mm", l_AB * cos_deg(psi), "crank pin along the slide",
      output=False),
    Q("n_B", "mm", l_AB * sin_deg(psi), "crank pin across the slide",
      output=False),
    Q("f_BC", "mm", _exact_zero((l_BC - l_AB - e) + 2 * l_AB * sin_half_squared(psi + 90)),
      "l_BC - q, first factor of h_BC^2", output=False),
    Q("g_BC", "mm", _exact_zero((l_BC - l_AB + e) + 2 * l_AB * sin_half_squared(psi - 90)),
      "l_BC + q, second factor of h_BC^2", output=False),
    Q("h_BC", "mm", root(f_BC * g_BC), "rod's projection on the slide", output=False),
    Q("dh_BC", "mm/s", omega_1 * u_B * q / h_BC, "rate of h_BC", output=False),
    Q("ddh_BC", "mm/s^2", -(w2 * u_B ** 2 + q * w2 * n_B + dh_BC ** 2) / h_BC,
      "second rate of h_BC", output=False),
    Q("s_C", "mm", u_B + h_BC, "slider C along the slide line"),
    Q("v_C", "mm/s", -omega_1 * n_B + dh_BC, "slider velocity"),
    Q("a_C", "mm/s^2", -w2 * u_B + ddh_BC, "slider acceleration"),
    Q("theta_2", "deg", phi_slide + degrees(atan2(h_BC, q)), "rod angle (direction B->C)"),
    Q("omega_2", "rad/s", -omega_1 * u_B / h_BC, "rod angular velocity"),
    Q("alpha_2", "rad/s^2", (w2 * n_B * h_BC + omega_1 * u_B * dh_BC) / h_BC ** 2,
      "rod angular acceleration"),
)

# A row whose reach factor is within NEAR_REACH of the lengths is a dead centre too: the
# factor's terms cancel there, and their rounding (a few ulps of the lengths, inherent in
# the sine of a float angle) leaves the rates 8 digits, not 16, 1e-6 deg from a tangent
# point or with the rod 1e-12 longer than the tangent length (tests/mechanisms/test_slider_crank_extremes.py).
# Outside the band the rates keep better than 1e-9 of their magnitude.
NEAR_REACH = 1e-6
STATUS = if_(iserror(h_BC), "cannot assemble",
             if_(le(min_(f_BC, g_BC), NEAR_REACH * (l_BC + 3 * l_AB + abs_(e))),
                 "dead centre", "ok"))


def rod_checks(r, rv, ra, l_AB: Node, l_BC: Node, ws: Node) -> tuple[Check, ...]:
    """The rod BC of a crank AB keeps its length: ``r`` = C - B, ``rv`` and ``ra`` its
    rates; ``ws`` = speed_scale(omega_1). Also the sewing machine's rod."""
    pos, vel, acc = l_BC, ws * l_AB * l_BC, ws ** 2 * l_AB * l_BC
    return (
        Check("rod_length", "position", (sqrt(r[0] ** 2 + r[1] ** 2) - l_BC) / pos,
              "|C - B| - l_BC, over l_BC"),
        Check("rod_velocity", "velocity", (r[0] * rv[0] + r[1] * rv[1]) / vel,
              "(C - B).(C' - B'), over omega_1 l_AB l_BC"),
        Check("rod_acceleration", "acceleration",
              (rv[0] ** 2 + rv[1] ** 2 + r[0] * ra[0] + r[1] * ra[1]) / acc,
              "|C' - B'|^2 + (C - B).(C'' - B''), over omega_1^2 l_AB l_BC"),
    )


def _checks() -> tuple[Check, ...]:
    psi = radians(theta_1 - phi_slide)
    ub, nb = l_AB * cos(psi), l_AB * sin(psi)
    ubv, nbv = -omega_1 * nb, omega_1 * ub
    uba, nba = -w2 * ub, -w2 * nb
    r = (s_C - ub, e - nb)             # C - B in slide coordinates
    rv = (v_C - ubv, -nbv)
    ra = (a_C - uba, -nba)
    rel = radians(theta_2 - phi_slide)
    c2, s2 = cos(rel), sin(rel)
    ws = speed_scale(omega_1)  # 1 at zero speed, where every rate is 0
    return (
        *rod_checks(r, rv, ra, l_AB, l_BC, ws),
        Check("rod_angle", "position", (r[0] * s2 - r[1] * c2) / l_BC,
              "(C - B) x e_2, over l_BC"),
        Check("rod_angular_velocity", "velocity",
              (rv[0] * s2 - rv[1] * c2 + (r[0] * c2 + r[1] * s2) * omega_2) / (ws * l_BC),
              "rate of (C - B) x e_2, over omega_1 l_BC"),
        Check("rod_angular_acceleration", "acceleration",
              (ra[0] * s2 - ra[1] * c2 + 2 * (rv[0] * c2 + rv[1] * s2) * omega_2
               - (r[0] * s2 - r[1] * c2) * omega_2 ** 2 + (r[0] * c2 + r[1] * s2) * alpha_2)
              / (ws ** 2 * l_BC), "second rate of (C - B) x e_2, over omega_1^2 l_BC"),
    )


def _why_not(p) -> str:
    return (f"the rod l_BC = {p['l_BC']:g} cannot reach the slide line at offset "
            f"e = {p['e']:g} from the crank pin at any crank angle of the sweep")


def _links() -> tuple[Link, ...]:
    """Crank from A, rod from B along B->C, slider from C along the slide line."""
    t1, phi = radians(theta_1), radians(phi_slide)
    bx, by = l_AB * cos(t1), l_AB * sin(t1)
    cu = (cos(phi), sin(phi))
    c = (s_C * cu[0] - e * cu[1], s_C * cu[1] + e * cu[0])   # s_C u + e n
    return (
        Link("crank", (0.0, 0.0), (0.0, 0.0), t1, omega_1, 0.0),
        Link("rod", (bx, by), (-w2 * bx, -w2 * by), radians(theta_2), omega_2, alpha_2),
        Link("slider", c, (a_C * cu[0], a_C * cu[1]), phi, 0.0, 0.0),
    )


def _time_ratio() -> Node:
    """Working over return stroke time, (180 + D) / (180 - D) with D the crank angle
    between the dead centres beyond 180 deg: D = asin(e/(l - r)) - asin(e/(l + r)).

    ASIN of a ratio near 1 keeps half its digits (the ratio's rounding is a square-rooted
    error there); instead, with h1, h2 the rod's reach past the offset at the two dead
    centres, h = sqrt((d - e)(d + e)) for d = l -+ r (factored: no cancellation),
    asin(e/d1) - asin(e/d2) = ATAN2(h1 h2 + e^2, e (h2 - h1)) and h2 - h1 = 4 l r/(h1 + h2)."""
    h1 = sqrt((l_BC - l_AB - e) * (l_BC - l_AB + e))
    h2 = sqrt((l_BC + l_AB - e) * (l_BC + l_AB + e))
    between = degrees(atan2(h1 * h2 + e ** 2, 4 * e * l_BC * l_AB / (h1 + h2)))
    return (180 + between) / (180 - between)


TIME_RATIO: Node = _time_ratio()
# The crank turns fully, the rod never tangent to the slide line: the exact stroke and the
# time ratio hold (at l_BC = l_AB + |e| the rod is tangent at one crank angle).
FULL_TURN: Node = gt(l_BC, l_AB + abs_(e))
FULL_TURN_TEXT = "l_BC > l_AB + |e|"

TEMPLATE = Template(
    id="slider_crank",
    title="Offset slider-crank",
    description="Crank, connecting rod and slider on an inclined, offset slide line.",
    input=InputSpec("theta_1", "deg", "crank angle"),
    parameters=PARAMETERS,
    quantities=QUANTITIES,
    status=STATUS,
    checks=_checks(),
    charts=(slide_charts("Slider", "theta_1", ("s_C", "v_C", "a_C"))
            + turn_charts("Rod", "theta_1", ("theta_2", "omega_2", "alpha_2"))),
    spans=(Span("stroke", "s_C"), Span("rod swing", "theta_2")),
    figures=(
        Figure("stroke, exact", "mm", only_if(sqrt((l_BC + l_AB) ** 2 - e ** 2)
                                              - sqrt((l_BC - l_AB) ** 2 - e ** 2),
                                              FULL_TURN, FULL_TURN_TEXT),
               f"between the dead centres (rod and crank in line); needs {FULL_TURN_TEXT}"),
        Figure("time ratio", "", only_if(TIME_RATIO, FULL_TURN, FULL_TURN_TEXT),
               f"working stroke time over return stroke time; needs {FULL_TURN_TEXT}"),
    ),
    links=_links(),
    length_unit_m=1e-3,
    assembly_failure=_why_not,
)
