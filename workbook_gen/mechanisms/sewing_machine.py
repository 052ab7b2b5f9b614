"""Sewing machine: needle bar (centred slider-crank) and thread take-up lever.

A = (0, 0); crank AB turns at omega_1; the needle bar C slides on x = 0 below
B; E is a point of the rod BC; the take-up lever turns about F, its direction
is F->E (a block pinned at E slides along it); the thread eye G is on the
lever at l_FG from F.

Derivation, with h = y_B - y_C (the rod's vertical projection):
h^2 = l_BC^2 - x_B^2, so h' = omega_1 x_B y_B / h and
h'' = -(omega_1^2 (y_B^2 - x_B^2) + h'^2) / h.
E = B + k R(beta_E) (C - B) with k = l_BE / l_BC, and the same for its rates.
With d = E - F = s (cos theta_5, sin theta_5):
s' = d'.e, omega_5 = (d x d') / s^2, s'' = d''.e + s omega_5^2,
alpha_5 = ((d x d'') / s - 2 s' omega_5) / s.
theta_5 is measured on the branch within 180 deg of the direction F->A, so
it is continuous over the sweep wherever F lies outside E's path.  The direction
F->A is ATAN2(0-x_F, 0-y_F), not ATAN2(-x_F, -y_F): LibreOffice keeps the sign of
a negated zero, and ATAN2(-60, -0) would be -180 deg there, +180 deg in Excel.
"""

from __future__ import annotations

import math

from ..expr import (Node, abs_, atan2, cos, degrees, eq, ge, gt, if_, iserror, le, or_, pi,
                    radians, root, sin, sqrt)
from .angles import cos_deg, cos_half_squared, reduced_input, sin_deg, sin_half_squared
from .base import (Chart, Check, Figure, InputSpec, Link, ParamSpec, Quantity, Span,
                   Template, only_if, quantity_vars, slide_charts, speed_scale, symbols,
                   turn_charts)
from .slider_crank import rod_checks

l_AB, l_BC, l_BE, beta_E, x_F, y_F, l_FG, omega_1 = symbols(
    "l_AB l_BC l_BE beta_E x_F y_F l_FG omega_1")
theta_2, omega_2, alpha_2 = quantity_vars("theta_2 omega_2 alpha_2")
(theta_1, x_B, y_B, lm_BC, lp_BC, h_BC, hr_BC, dh_BC, ddh_BC, y_C, v_C, a_C, x_E, y_E, vx_E, vy_E,
 ax_E, ay_E, s_FE, sr_FE, v_FE, a_FE, theta_5, omega_5, alpha_5, x_G, y_G, vx_G, vy_G, ax_G, ay_G) = quantity_vars(
    "theta_1 x_B y_B lm_BC lp_BC h_BC hr_BC dh_BC ddh_BC y_C v_C a_C x_E y_E vx_E vy_E ax_E ay_E "
    "s_FE sr_FE v_FE a_FE theta_5 omega_5 alpha_5 x_G y_G vx_G vy_G ax_G ay_G")

k = l_BE / l_BC
cb, sb = cos(radians(beta_E)), sin(radians(beta_E))
dx, dy = x_E - x_F, y_E - y_F
w2 = omega_1 ** 2

# Limits (docs/stability.md, sewing_machine).  A reach factor l_BC -+ x_B = d + t, d = l_BC - l_AB,
# t = 2 l_AB sin^2 or cos^2 >= 0, rounds to a few ulps of |d| + t = |f - d| + |d|: within
# REACH_ROUNDING of that it is 0 (the rod exactly perpendicular to the needle bar: a dead
# centre, h_BC = 0, its rates #DIV/0!, never the square root of rounding); within
# LIMIT_BAND of it (only where d < 0: the rod shorter than the crank, a reach limit between
# grid angles) the rates would keep fewer than 9 digits and are #DIV/0! too, the row flagged.
# The rod within ROD_BAND of the lengths of perpendicular to the needle bar (rod = crank,
# near its dead centres) is a dead centre too: the rates' terms cancel there (y_B^2 - x_B^2
# + dh_BC^2), and beyond it they keep 9 digits (docs/stability.md).
# E within rounding of the lever pivot F (|E - F| <= REACH_ROUNDING of the lengths): the
# lever's angle is undefined (#DIV/0!).  Near F the lever's angle is the direction of
# E - F, whose rounding (eps of the lengths) moves omega_5 by eps (L/s)^2 and alpha_5 by
# eps (L/s)^3 (L the lengths, s = s_FE): within LEVER_BAND of the lengths, where that
# exceeds 1e-9, the lever's rates are #DIV/0! and the row a dead centre.
REACH_ROUNDING = 16 * 2.0 ** -52
LIMIT_BAND = 1e-6
ROD_BAND = 1e-6
LEVER_BAND = 6e-3   # (eps / 1e-9)^(1/3)
_d = l_BC - l_AB
lever_size = l_AB + l_BE + abs_(x_F) + abs_(y_F)   # |E| + |F| at most


def _within(factor: Node, fraction: float) -> Node:
    return le(abs_(factor), fraction * (abs_(factor - _d) + abs_(_d)))


def _zero_within(fraction: float, value: Node, zero: Node | int = 0) -> Node:
    """``zero`` where either reach factor is within ``fraction`` of its terms, else
    ``value`` (nested IFs rather than OR, which the audit's rounding-noise estimate
    follows)."""
    return if_(_within(lm_BC, fraction), zero, if_(_within(lp_BC, fraction), zero, value))

PARAMETERS = (
    ParamSpec("l_AB", 32.0, "mm", "crank AB", positive=True),
    ParamSpec("l_BC", 100.0, "mm", "connecting rod BC (crank pin to needle bar)", positive=True),
    ParamSpec("l_BE", 28.0, "mm", "distance of the lever's pin E from B along the rod",
              positive=True),
    ParamSpec("beta_E", 0.0, "deg", "angle of BE from the direction B->C"),
    ParamSpec("x_F", -60.0, "mm", "take-up lever pivot F, x"),
    ParamSpec("y_F", -20.0, "mm", "take-up lever pivot F, y"),
    ParamSpec("l_FG", 90.0, "mm", "thread eye G on the lever, distance from F",
              positive=True),
    ParamSpec("omega_1", 2 * math.pi, "rad/s", "crank speed, counter-clockwise"),
)

Q = Quantity
THETA_1R, theta_1r = reduced_input("theta_1r", theta_1, "crank angle")
QUANTITIES = (
    THETA_1R,
    Q("x_B", "mm", l_AB * cos_deg(theta_1r), "crank pin B, x", output=False),
    Q("y_B", "mm", l_AB * sin_deg(theta_1r), "crank pin B, y", output=False),
    # h^2 = (l_BC - x_B)(l_BC + x_B), l_BC -+ x_B = (l_BC - l_AB) + l_AB (1 -+ cos theta_1):
    # no cancellation when the rod is barely longer than the crank
    Q("lm_BC", "mm", _d + 2 * l_AB * sin_half_squared(theta_1r), "l_BC - x_B", output=False),
    Q("lp_BC", "mm", _d + 2 * l_AB * cos_half_squared(theta_1r), "l_BC + x_B", output=False),
    Q("h_BC", "mm", root(_zero_within(REACH_ROUNDING, lm_BC * lp_BC)),
      "rod's vertical projection y_B - y_C (0 where a reach factor is 0 to rounding)",
      output=False),
    Q("hr_BC", "mm", if_(le(h_BC, ROD_BAND * (l_AB + l_BC)), 0,
                         _zero_within(LIMIT_BAND, h_BC, 0 * h_BC)),   # 0, or #NUM! as h_BC
      "h_BC where its rates keep their digits, else 0 (the rates #DIV/0!)", output=False),
    Q("dh_BC", "mm/s", omega_1 * x_B * y_B / hr_BC, "rate of h_BC", output=False),
    Q("ddh_BC", "mm/s^2", -(w2 * (y_B ** 2 - x_B ** 2) + dh_BC ** 2) / hr_BC,
      "second rate of h_BC", output=False),
    Q("y_C", "mm", y_B - h_BC, "needle bar C, position"),
    Q("v_C", "mm/s", omega_1 * x_B - dh_BC, "needle bar C, velocity"),
    Q("a_C", "mm/s^2", -w2 * y_B - ddh_BC, "needle bar C, acceleration"),
    # The rod's direction B->C = (-x_B, -h_BC) points downwards: its angle stays in
    # (-180, 0) deg, continuous.  Rates from d/dt of that direction (|B->C| = l_BC).
    Q("theta_2", "deg", degrees(atan2(0 - x_B, 0 - h_BC)), "rod angle (direction B->C)",
      output=False),
    Q("omega_2", "rad/s", omega_1 * y_B / hr_BC, "rod angular velocity", output=False),
    Q("alpha_2", "rad/s^2", omega_1 * (omega_1 * x_B * hr_BC - y_B * dh_BC) / hr_BC ** 2,
      "rod angular acceleration", output=False),
    Q("x_E", "mm", x_B + k * (h_BC * sb - x_B * cb), "lever pin E on the rod, x", output=False),
    Q("y_E", "mm", y_B - k * (x_B * sb + h_BC * cb), "lever pin E on the rod, y", output=False),
    Q("vx_E", "mm/s", -omega_1 * y_B + k * (omega_1 * y_B * cb + dh_BC * sb), "E, x velocity",
      output=False),
    Q("vy_E", "mm/s", omega_1 * x_B + k * (omega_1 * y_B * sb - dh_BC * cb), "E, y velocity",
      output=False),
    Q("ax_E", "mm/s^2", -w2 * x_B + k * (w2 * x_B * cb + ddh_BC * sb), "E, x acceleration",
      output=False),
    Q("ay_E", "mm/s^2", -w2 * y_B + k * (w2 * x_B * sb - ddh_BC * cb), "E, y acceleration",
      output=False),
    Q("s_FE", "mm", sqrt(if_(le(dx ** 2 + dy ** 2, (REACH_ROUNDING * lever_size) ** 2), 0,
                              dx ** 2 + dy ** 2)),
      "block E along the lever, distance from F (0 where E is on F to rounding)"),
    Q("sr_FE", "mm", if_(le(s_FE, LEVER_BAND * lever_size), 0, s_FE),
      "s_FE where the lever's rates keep their digits, else 0 (the rates #DIV/0!)",
      output=False),
    Q("theta_5", "deg",
      if_(gt(s_FE, 0),
          degrees(atan2(0 - x_F, 0 - y_F) + atan2(-x_F * dx - y_F * dy, -x_F * dy + y_F * dx)),
          1 / s_FE),
      "take-up lever angle (direction F->E), continuous; #DIV/0! with E on F"),
    Q("v_FE", "mm/s", (dx * vx_E + dy * vy_E) / sr_FE, "block sliding velocity along the lever"),
    Q("omega_5", "rad/s", (dx * vy_E - dy * vx_E) / sr_FE ** 2, "take-up lever angular velocity"),
    Q("a_FE", "mm/s^2", (dx * ax_E + dy * ay_E) / s_FE + s_FE * omega_5 ** 2,
      "block sliding acceleration along the lever"),
    Q("alpha_5", "rad/s^2", ((dx * ay_E - dy * ax_E) / s_FE - 2 * v_FE * omega_5) / s_FE,
      "take-up lever angular acceleration"),
    Q("x_G", "mm", x_F + l_FG * dx / s_FE, "thread eye G, x"),
    Q("y_G", "mm", y_F + l_FG * dy / s_FE, "thread eye G, y"),
    Q("vx_G", "mm/s", -l_FG * omega_5 * dy / s_FE, "thread eye G, x velocity"),
    Q("vy_G", "mm/s", l_FG * omega_5 * dx / s_FE, "thread eye G, y velocity"),
    Q("ax_G", "mm/s^2", -l_FG * (omega_5 ** 2 * dx + alpha_5 * dy) / s_FE,
      "thread eye G, x acceleration"),
    Q("ay_G", "mm/s^2", l_FG * (alpha_5 * dx - omega_5 ** 2 * dy) / s_FE,
      "thread eye G, y acceleration"),
)

def _status_for(keep: frozenset[str]) -> Node:
    """"dead centre": the rod perpendicular to the needle bar (h_BC = 0) or, where rates
    are kept, within the bands of it; the block E on the lever pivot F (no torque on the
    lever) or near it, where the lever is kept."""
    dead = eq(hr_BC, 0) if "dh_BC" in keep else eq(h_BC, 0)
    if "s_FE" in keep:
        dead = or_(dead, eq(sr_FE, 0))
    return if_(iserror(h_BC), "cannot assemble", if_(dead, "dead centre", "ok"))


STATUS = _status_for(frozenset({"dh_BC", "s_FE"}))


def _rod_point_checks() -> tuple[Check, ...]:
    """Closure residuals, with B and E rebuilt from theta_1 and the needle columns."""
    t = radians(theta_1)
    bx, by = l_AB * cos(t), l_AB * sin(t)
    bvx, bvy = -omega_1 * by, omega_1 * bx
    bax, bay = -w2 * bx, -w2 * by
    # C - B and its rates (C = (0, y_C)).
    r = (-bx, y_C - by)
    rv = (-bvx, v_C - bvy)
    ra = (-bax, a_C - bay)

    def on_rod(base: tuple[Node, Node], rel: tuple[Node, Node]) -> tuple[Node, Node]:
        return (base[0] + k * (rel[0] * cb - rel[1] * sb), base[1] + k * (rel[0] * sb + rel[1] * cb))

    d = on_rod((bx - x_F, by - y_F), r)
    dv = on_rod((bvx, bvy), rv)
    da = on_rod((bax, bay), ra)
    t5 = radians(theta_5)
    c5, s5 = cos(t5), sin(t5)

    def cross(a, b=(c5, s5)) -> Node:
        return a[0] * b[1] - a[1] * b[0]

    def dot(a, b=(c5, s5)) -> Node:
        return a[0] * b[0] + a[1] * b[1]

    ws = speed_scale(omega_1)  # 1 at zero speed, where every rate is 0
    lever_v, lever_a = ws * l_FG, ws ** 2 * l_FG
    gx, gy = x_G - x_F, y_G - y_F
    return (
        *rod_checks(r, rv, ra, l_AB, l_BC, ws),
        Check("lever_position", "position", cross(d) / l_FG,
              "distance of E from the lever line, over l_FG"),
        Check("lever_velocity", "velocity", (cross(dv) + dot(d) * omega_5) / lever_v,
              "rate of that distance, over omega_1 l_FG"),
        Check("lever_acceleration", "acceleration",
              (cross(da) + 2 * dot(dv) * omega_5 - cross(d) * omega_5 ** 2 + dot(d) * alpha_5)
              / lever_a, "second rate of that distance, over omega_1^2 l_FG"),
        Check("block_position", "position", (dot(d) - s_FE) / l_FG,
              "(E - F).e_5 - s_FE, over l_FG"),
        Check("block_velocity", "velocity", (dot(dv) - v_FE) / lever_v,
              "E'.e_5 - v_FE, over omega_1 l_FG"),
        Check("block_acceleration", "acceleration",
              (dot(da) + s_FE * omega_5 ** 2 - a_FE) / lever_a,
              "E''.e_5 + s_FE omega_5^2 - a_FE, over omega_1^2 l_FG"),
        Check("eye_position", "position", (sqrt(gx ** 2 + gy ** 2) - l_FG) / l_FG,
              "|G - F| - l_FG, over l_FG"),
        Check("eye_velocity", "velocity", (gx * vx_G + gy * vy_G) / (l_FG * lever_v),
              "(G - F).G', over omega_1 l_FG^2"),
        Check("eye_acceleration", "acceleration",
              (vx_G ** 2 + vy_G ** 2 + gx * ax_G + gy * ay_G) / (l_FG * lever_a),
              "|G'|^2 + (G - F).G'', over omega_1^2 l_FG^2"),
    )


def _links() -> tuple[Link, ...]:
    """Crank from A; rod from B along B->C; needle bar from C, its u axis upwards (+y);
    take-up lever from F along F->E."""
    return (
        Link("crank", (0.0, 0.0), (0.0, 0.0), radians(theta_1), omega_1, 0.0),
        Link("rod", (x_B, y_B), (-w2 * x_B, -w2 * y_B), radians(theta_2), omega_2, alpha_2),
        Link("needle_bar", (0.0, y_C), (0.0, a_C), pi() / 2, 0.0, 0.0),
        Link("lever", (x_F, y_F), (0.0, 0.0), radians(theta_5), omega_5, alpha_5),
    )


def _validate(p) -> tuple[str, str] | None:
    if p["x_F"] == 0 and p["y_F"] == 0:
        return ("x_F", "the lever pivot F must not coincide with the crank pivot A = (0, 0)")
    return None


def _why_not(p) -> str:
    return (f"the rod l_BC = {p['l_BC']:g} cannot reach the needle bar's line x = 0 from the "
            f"crank pin at any crank angle of the sweep (needs l_BC >= |x_B|, l_AB = {p['l_AB']:g})")


TEMPLATE = Template(
    id="sewing_machine",
    title="Sewing machine: needle bar and thread take-up lever",
    description="Needle bar driven by a centred slider-crank; thread take-up lever driven "
                "by a block on the connecting rod.",
    input=InputSpec("theta_1", "deg", "crank angle"),
    parameters=PARAMETERS,
    quantities=QUANTITIES,
    status=STATUS,
    status_for=_status_for,
    checks=_rod_point_checks(),
    charts=(
        *slide_charts("Needle bar", "theta_1", ("y_C", "v_C", "a_C")),
        *turn_charts("Take-up lever", "theta_1", ("theta_5", "omega_5", "alpha_5")),
        Chart("Path of E (lever pin on the rod)", "x_E", ("y_E",), "y_E [mm]", path=True),
        Chart("Path of G (thread eye)", "x_G", ("y_G",), "y_G [mm]", path=True),
    ),
    spans=(Span("needle stroke", "y_C"), Span("lever swing", "theta_5"),
           Span("block travel on the lever", "s_FE")),
    figures=(Figure("needle stroke, exact", "mm",
                    only_if(2 * l_AB, ge(l_BC, l_AB), "l_BC >= l_AB"),
                    "2 l_AB: the slide line passes through A; needs l_BC >= l_AB (the rod "
                    "reaches the slide line at every crank angle)"),),
    links=_links(),
    length_unit_m=1e-3,
    validate=_validate,
    assembly_failure=_why_not,
)
