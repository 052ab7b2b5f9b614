"""Actuator linkage: a lever driven by a hydraulic cylinder (docs/mechanisms.md, actuator_linkage).

Lever 2 turns about the fixed pivot A = (x_A, y_A); the cylinder 3 about the
fixed pivot B = (x_B, y_B); the piston rod 4 is pinned to the lever at
C = A + l_A1 (cos phi_2, sin phi_2) + l_A1C (sin phi_2, -cos phi_2), and sets
BC = s_BC, the input.  Lengths are relative to the cylinder's minimum length,
so they carry the unit "-" and ``length_unit_m`` is 1.0 (give metres for the
shaking force); rates are per second.

Closed form, in the triangle ABC with a = |AB|, r = |AC| = sqrt(l_A1^2 + l_A1C^2)
fixed and s = s_BC: 4 * area = cross_A = sqrt((s-r+a)(s+r-a)(r+a-s)(r+a+s))
(cancellation-free Heron; written as ^0.5 so a triangle that does not close is
#NUM! in Excel and LibreOffice alike) and dot_A = a^2 + r^2 - s^2, so that
cross_A = 2 (B-A) x (C-A) and dot_A = 2 (B-A).(C-A).

Branch: C on the LEFT of the directed line A->B (the triangle A, B, C counter-
clockwise).  For the paper's pivots (B below and right of A) that puts C to
the right of A, slightly below it at the shortest cylinder, and the lever
rises as the cylinder extends; the other branch puts C below the base, left
of A.  Then angle BAC = ATAN2(dot_A, cross_A) in [0, pi] and
phi_AC = dir(A->B) + BAC, phi_2 = phi_AC + ATAN2(l_A1, l_A1C) (C is l_A1C to
the right of the lever line), both continuous.  The cylinder turns the other
way from B: phi_3 = dir(B->A) - ABC with 2 a s (cos ABC, sin ABC) =
(a^2 + s^2 - r^2, cross_A), in (dir(B->A) - pi, dir(B->A)), so continuous.
gamma = ACB with 2 r s (cos, sin) = (r^2 + s^2 - a^2, cross_A), in (0, pi).

Rates, from s^2 = a^2 + r^2 - 2 a r cos(BAC) with s' = v_s, s'' = 0:
omega_2 = 2 s v_s / cross_A, alpha_2 = (2 v_s^2 - dot_A omega_2^2) / cross_A.
C' = omega_2 J (C - A), C'' = alpha_2 J (C - A) - omega_2^2 (C - A);
omega_3 = (C - B) x C' / s^2, alpha_3 = ((C - B) x C'' / s - 2 v_s omega_3) / s.

Dead zone: the transmission angle is poor when gamma is near 0 or near pi;
``below_gamma_min`` is 1 where MIN(gamma, pi - gamma) < gamma_min (default
0.35 rad, about 20 deg), else 0 (the status stays "ok": the row is sound).  The
Summary's extremes table gives the minimum gamma and the s_BC where it
occurs, and for ``below_gamma_min`` its maximum (1 if any row is in the dead
zone) and the first s_BC where that happens.  The Summary cannot count
Table rows (no SUM over a Table column there): read the count off the flag
column.

``method = "bisection"`` adds the paper's successive halving
(``actuator_halving``): ``phi_2_iter`` and ``halvings_used``.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Mapping

from ..expr import Node, Num, abs_, atan2, cos, eq, if_, iserror, le, lt, min_, pi, root, sin, sqrt
from ..xlerror import TRIG_LIMIT  # Excel's SIN and COS give #NUM! from there
from .actuator_halving import halving_quantities, lever_point
from .base import (Chart, Check, Figure, InputSpec, Link, OptionSpec, ParamSpec, Quantity, Span,
                   Template, quantity_vars, symbols)

x_A, y_A, x_B, y_B, l_A1, l_A1C, v_s, gamma_min = symbols(
    "x_A y_A x_B y_B l_A1 l_A1C v_s gamma_min")
(s_BC, cross_A, phi_2, phi_AC, phi_3, gamma, below_gamma_min, x_C, y_C, omega_2,
 alpha_2, vx_C, vy_C, ax_C, ay_C, omega_3, alpha_3) = quantity_vars(
    "s_BC cross_A phi_2 phi_AC phi_3 gamma below_gamma_min x_C y_C omega_2 alpha_2 "
    "vx_C vy_C ax_C ay_C omega_3 alpha_3")

AB2 = (x_B - x_A) ** 2 + (y_B - y_A) ** 2
AC2 = l_A1 ** 2 + l_A1C ** 2
a_len, r_len = sqrt(AB2), sqrt(AC2)
s = s_BC
dot_A = AB2 + AC2 - s ** 2    # 2 (B-A).(C-A), written inline: defined even where cross_A is not

PARAMETERS = (
    ParamSpec("x_A", 0.156, "-", "lever pivot A, x (relative to the cylinder's minimum length)"),
    ParamSpec("y_A", 0.437, "-", "lever pivot A, y"),
    ParamSpec("x_B", 0.462, "-", "cylinder pivot B, x"),
    ParamSpec("y_B", 0.0, "-", "cylinder pivot B, y"),
    ParamSpec("l_A1", 1.237, "-", "lever: A to the foot 1 of C, along the lever", positive=True),
    ParamSpec("l_A1C", 0.325, "-", "lever: C from the lever line, to its right"),
    ParamSpec("v_s", 0.1, "1/s", "actuator speed ds_BC/dt (constant)"),
    ParamSpec("gamma_min", 0.35, "rad", "smallest acceptable transmission angle (dead zone)"),
    ParamSpec("epsilon", 1e-4, "-", "halving stops at the first midpoint with |f| < epsilon",
              positive=True),
    ParamSpec("phi_lo", -1.5, "rad", "halving bracket, lower end"),
    ParamSpec("phi_hi", 4.64, "rad", "halving bracket, upper end"),
)

#: s_BC within this fraction of AC + AB of an assembly limit |AC - AB| or AC + AB is a
#: dead centre: cross_A vanishes there, and a hair away its Heron factor carries the
#: rounding of the irrational AC and AB amplified by (AC + AB) / (distance to the limit).
DEAD_CENTRE_FRACTION = 1e-7
NEAR_LIMIT = le(min_(s - abs_(r_len - a_len), r_len + a_len - s),
                DEAD_CENTRE_FRACTION * (r_len + a_len))
# the rates divide by cross_A, made 0 at a dead centre: #DIV/0!, not a huge number
# (0 * cross_A: still #NUM! beyond the limits, where the triangle does not close)
_cross_or_zero = if_(NEAR_LIMIT, 0 * cross_A, cross_A)

Q = Quantity
_xc, _yc = lever_point(phi_2)
QUANTITIES = (
    Q("cross_A", "-", root((s - r_len + a_len) * (s + r_len - a_len) * (r_len + a_len - s)
                           * (r_len + a_len + s)),
      "2 (B-A)x(C-A) = 4 * area of ABC (Heron)", output=False),
    Q("phi_2", "rad", atan2(x_B - x_A, y_B - y_A) + atan2(dot_A, cross_A) + atan2(l_A1, l_A1C),
      "lever angle, closed form (law of cosines in ABC)"),
    Q("phi_AC", "rad", atan2(x_B - x_A, y_B - y_A) + atan2(dot_A, cross_A), "direction A->C"),
    Q("phi_3", "rad", atan2(x_A - x_B, y_A - y_B) - atan2(AB2 + s ** 2 - AC2, cross_A),
      "cylinder angle, direction B->C (full angle, continuous)"),
    Q("gamma", "rad", atan2(AC2 + s ** 2 - AB2, cross_A),
      "transmission angle ACB (between C->A and C->B)"),
    Q("below_gamma_min", "", if_(lt(min_(gamma, pi() - gamma), gamma_min), 1, 0),
      "1 where MIN(gamma, pi - gamma) < gamma_min (dead zone), else 0"),
    Q("x_C", "-", _xc, "lever point C, x"),
    Q("y_C", "-", _yc, "lever point C, y"),
    Q("omega_2", "rad/s", 2 * s * v_s / _cross_or_zero, "lever angular velocity"),
    Q("alpha_2", "rad/s^2", (2 * v_s ** 2 - dot_A * omega_2 ** 2) / _cross_or_zero,
      "lever angular acceleration"),
    Q("vx_C", "1/s", -omega_2 * (y_C - y_A), "C, x velocity", output=False),
    Q("vy_C", "1/s", omega_2 * (x_C - x_A), "C, y velocity", output=False),
    Q("ax_C", "1/s^2", -alpha_2 * (y_C - y_A) - omega_2 ** 2 * (x_C - x_A), "C, x acceleration",
      output=False),
    Q("ay_C", "1/s^2", alpha_2 * (x_C - x_A) - omega_2 ** 2 * (y_C - y_A), "C, y acceleration",
      output=False),
    Q("omega_3", "rad/s", ((x_C - x_B) * vy_C - (y_C - y_B) * vx_C) / s ** 2,
      "cylinder (and piston rod) angular velocity"),
    Q("alpha_3", "rad/s^2",
      (((x_C - x_B) * ay_C - (y_C - y_B) * ax_C) / s - 2 * v_s * omega_3) / s,
      "cylinder (and piston rod) angular acceleration"),
)


def _row_status(converged: Node | None = None, on_branch: Node | None = None) -> Node:
    """Status per row; rows in the dead zone stay "ok" (below_gamma_min says so): the
    Checks skip rows that are not "ok", and those rows are sound."""
    ok: Node | str = "ok"
    if converged is not None:
        ok = if_(converged, if_(on_branch, "ok", "other branch"), "not converged")
    return if_(iserror(cross_A), "cannot assemble", if_(NEAR_LIMIT, "dead centre", ok))


def _checks() -> tuple[Check, ...]:
    """Closure residuals with C rebuilt from phi_2 alone (not the x_C, y_C columns)."""
    cx, cy = lever_point(phi_2)
    e = (cx - x_A, cy - y_A)                     # C - A
    d = (cx - x_B, cy - y_B)                     # C - B
    dv = (-omega_2 * e[1], omega_2 * e[0])       # C'
    da = (-alpha_2 * e[1] - omega_2 ** 2 * e[0], alpha_2 * e[0] - omega_2 ** 2 * e[1])
    e3 = (cos(phi_3), sin(phi_3))
    eac = (cos(phi_AC), sin(phi_AC))

    def dot(u, w=e3) -> Node:
        return u[0] * w[0] + u[1] * w[1]

    def cross(u, w=e3) -> Node:
        return u[0] * w[1] - u[1] * w[0]

    vsc = if_(eq(v_s, 0), 1, abs_(v_s))          # velocity scale (1 for a resting actuator)
    acc = vsc ** 2 / s
    return (
        Check("cylinder_length", "position", (sqrt(dot(d, d)) - s) / s,
              "|C(phi_2) - B| - s_BC, over s_BC"),
        Check("lever_direction", "position", cross(e, eac) / r_len,
              "(C(phi_2) - A) x e_AC, over |AC|"),
        Check("cylinder_direction", "position", cross(d) / s,
              "(C(phi_2) - B) x e_3, over s_BC"),
        Check("transmission_angle", "position", dot(e, d) / (r_len * s) - cos(gamma),
              "(C - A).(C - B) / (|AC| s_BC) - cos(gamma)"),
        Check("cylinder_velocity", "velocity", (dot(d, dv) - s * v_s) / (s * vsc),
              "(C - B).C' - s_BC v_s, over s_BC |v_s|"),
        Check("cylinder_acceleration", "acceleration", (dot(dv, dv) + dot(d, da) - v_s ** 2)
              / vsc ** 2, "|C'|^2 + (C - B).C'' - v_s^2, over v_s^2"),
        Check("cylinder_angular_velocity", "velocity", (cross(dv) + dot(d) * omega_3) / vsc,
              "rate of (C - B) x e_3, over |v_s|"),
        Check("cylinder_angular_acceleration", "acceleration",
              (cross(da) + 2 * dot(dv) * omega_3 - cross(d) * omega_3 ** 2 + dot(d) * alpha_3)
              / acc, "second rate of (C - B) x e_3, over v_s^2 / s_BC"),
    )


_ZERO = Num(0.0)  # fixed pivots: no acceleration

CHARTS = (
    Chart("Lever angle", "s_BC", ("phi_2",), "phi_2 [rad]"),
    Chart("Direction A->C", "s_BC", ("phi_AC",), "phi_AC [rad]"),
    Chart("Cylinder angle", "s_BC", ("phi_3",), "phi_3 [rad]"),
    Chart("Transmission angle", "s_BC", ("gamma",), "gamma [rad]"),
    Chart("Lever angular velocity", "s_BC", ("omega_2",), "omega_2 [rad/s]"),
    Chart("Lever angular acceleration", "s_BC", ("alpha_2",), "alpha_2 [rad/s^2]"),
    Chart("Cylinder angular velocity", "s_BC", ("omega_3",), "omega_3 [rad/s]"),
    Chart("Cylinder angular acceleration", "s_BC", ("alpha_3",), "alpha_3 [rad/s^2]"),
    Chart("Path of C (lever pin)", "x_C", ("y_C",), "y_C [-]", path=True),
)

HALVING_CHARTS = (
    Chart("Lever angle: closed form and successive halving", "s_BC", ("phi_2", "phi_2_iter"),
          "phi_2 [rad]"),
    Chart("Halvings used", "s_BC", ("halvings_used",), "halvings"),
)

OPTIONS = (
    OptionSpec("method", "closed", "phi_2 in closed form only, or also by successive halving "
               "(phi_2_iter, one group of columns per halving)", choices=("closed", "bisection")),
    OptionSpec("halvings", 20, "number of halvings (column groups) with method = bisection",
               minimum=1, maximum=60),
)


def configure(template: Template, options: Mapping[str, object]) -> Template:
    """The closed-form template, or with ``method = "bisection"`` the halving columns
    inserted after phi_2 and a status that also says "not converged" (|f| >= epsilon
    after the last halving) or "other branch" (the bracket led to the mirror root)."""
    if options["method"] != "bisection":
        return template
    extra, converged, on_branch = halving_quantities(int(options["halvings"]))
    at = [q.name for q in template.quantities].index("phi_2") + 1
    quantities = template.quantities[:at] + extra + template.quantities[at:]
    return replace(template, quantities=quantities, status=_row_status(converged, on_branch),
                   charts=HALVING_CHARTS + template.charts)


def _validate(p) -> tuple[str, str] | None:
    if p["x_A"] == p["x_B"] and p["y_A"] == p["y_B"]:
        return ("x_B", "the cylinder pivot B must not coincide with the lever pivot A")
    if not p["phi_hi"] > p["phi_lo"]:
        return ("phi_hi", f"must be > phi_lo = {p['phi_lo']:g}")
    for key in ("phi_lo", "phi_hi"):   # the halving takes COS and SIN of the bracket
        if abs(p[key]) >= TRIG_LIMIT:
            return (key, f"must be smaller than 2^27 = {TRIG_LIMIT:.0f} rad in magnitude "
                         "(Excel's SIN and COS give #NUM! from there)")
    return None


def _why_not(p) -> str:
    a = ((p["x_B"] - p["x_A"]) ** 2 + (p["y_B"] - p["y_A"]) ** 2) ** 0.5
    r = (p["l_A1"] ** 2 + p["l_A1C"] ** 2) ** 0.5
    return (f"the cylinder length s_BC must lie between |AC - AB| = {abs(r - a):.6g} and "
            f"AC + AB = {r + a:.6g} (AC = {r:.6g}, AB = {a:.6g})")


TEMPLATE = Template(
    id="actuator_linkage",
    title="Actuator linkage: lever driven by a hydraulic cylinder",
    description="Lever about A driven by a cylinder about B whose rod sets BC = s_BC; "
                "closed form against successive halving.",
    input=InputSpec("s_BC", "-", "cylinder length BC (relative to its minimum length)",
                    start=1.0, stop=1.687, step=0.0687, positive=True),
    parameters=PARAMETERS,
    quantities=QUANTITIES,
    status=_row_status(),
    checks=_checks(),
    charts=CHARTS,
    spans=(Span("lever swing", "phi_2"), Span("cylinder swing", "phi_3"),
           Span("transmission angle range", "gamma")),
    figures=(
        Figure("shortest s_BC that assembles", "-", abs_(r_len - a_len), "|AC - AB|"),
        Figure("longest s_BC that assembles", "-", r_len + a_len, "AC + AB"),
        Figure("largest transmission angle, any s_BC", "rad",
               if_(lt(a_len, r_len), atan2(sqrt((r_len - a_len) * (r_len + a_len)), a_len),
                   pi() / 2),
               "ASIN(AB/AC) at s_BC = sqrt(AC^2 - AB^2) when AB < AC, else pi/2"),
    ),
    options=OPTIONS,
    links=(
        Link("lever", (x_A, y_A), (_ZERO, _ZERO), phi_2, omega_2, alpha_2),
        Link("cylinder", (x_B, y_B), (_ZERO, _ZERO), phi_3, omega_3, alpha_3),
        Link("rod", (x_C, y_C), (ax_C, ay_C), phi_3 + pi(), omega_3, alpha_3),
    ),
    length_unit_m=1.0,
    configure=configure,
    validate=_validate,
    assembly_failure=_why_not,
)
