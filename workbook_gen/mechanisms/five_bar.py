"""Five-bar linkage with two inputs: inverse kinematics of a point C on a circle,
sensitivity of C to the link lengths, and the error of C from joint clearance.

A = (0, 0), E = (l_5, 0); cranks AB = l_1 (angle theta_1) and ED = l_4 (theta_4);
couplers BC = l_2 and DC = l_3.  C follows the circle x_0 + R_path cos phi,
y_0 + R_path sin phi (``R`` is not a legal Excel name: ``R_path``).

Inverse kinematics, branch "elbows out" (B left of the directed line A->C, D right
of E->C).  With d = |C - A|, B's distance from the line AC is the half chord
h_B = sqrt((l_1+l_2+d)(l_1+l_2-d)(d+l_1-l_2)(d-l_1+l_2)) / (2d) (no cancellation
but at the true assembly limits) and its projection on AC is
a_B = ((l_1-l_2)(l_1+l_2) + d^2) / (2d); theta_1 = psi_AC + ATAN2(a_B, h_B), where
psi_AC is the direction of A->C measured from the direction A->(x_0, y_0), so it
is continuous whenever the path does not surround A.  D likewise, on the right.

``method = "newton"``: theta_1 and theta_4 by ``iterations`` Newton-Raphson steps,
see ``five_bar_newton.py``.  Sensitivity and clearance: ``five_bar_errors.py``.
Position-only template: it has no rates, so no links for the shaking force.

Limits (issue 21, docs/stability.md): a dyad stretched or folded (h_B or h_D within
LIMIT_FRACTION of its reach) is flagged "limit"; B, C, D in line (the forward singularity,
det_BCD within five_bar_errors.SINGULAR_FRACTION) "singular", with the sensitivities and
the clearance errors #DIV/0!.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Mapping

from ..expr import Node, Var, abs_, atan2, degrees, eq, iserror, if_, le, or_, root, sqrt
from ..expr import cos, radians, sin, min_, max_
from .base import (Chart, Check, InputSpec, OptionSpec, ParamSpec, Quantity, Span, Template,
                   quantity_vars, symbols)
from .five_bar_errors import CLEARANCE, CLEARANCE_CHARTS, SENSITIVITY, SENSITIVITY_CHARTS
from .five_bar_newton import newton_quantities, newton_status

l_1, l_2, l_3, l_4, l_5, x_0, y_0, R_path = symbols("l_1 l_2 l_3 l_4 l_5 x_0 y_0 R_path")
(phi, x_C, y_C, psi_AC, d_AC, h_B, psi_EC, d_EC, h_D, theta_1, theta_4) = quantity_vars(
    "phi x_C y_C psi_AC d_AC h_B psi_EC d_EC h_D theta_1 theta_4")

PARAMETERS = (
    ParamSpec("l_1", 1.2, "m", "crank AB (input theta_1 at A)", positive=True),
    ParamSpec("l_2", 1.0, "m", "coupler BC", positive=True),
    ParamSpec("l_3", 1.0, "m", "coupler DC", positive=True),
    ParamSpec("l_4", 1.2, "m", "crank ED (input theta_4 at E)", positive=True),
    ParamSpec("l_5", 1.6, "m", "ground AE: E = (l_5, 0)", positive=True),
    ParamSpec("x_0", 0.8, "m", "centre of C's circular path, x"),
    ParamSpec("y_0", 1.6, "m", "centre of C's circular path, y"),
    ParamSpec("R_path", 0.3, "m", "radius of C's path (the paper's R, not a legal Excel name)",
              positive=True),
    ParamSpec("r_clear", 1e-5, "m", "radial clearance of one joint at a time", positive=True),
)


def _direction(cx: Node, cy: Node, rx: Node, ry: Node) -> Node:
    """Direction (deg) of (cx, cy), measured from the reference direction (rx, ry):
    continuous while (cx, cy) stays off the ray opposite to (rx, ry)."""
    return degrees(atan2(rx, ry) + atan2(cx * rx + cy * ry, rx * cy - ry * cx))


def _half_chord(a: Node, b: Node, d: Node) -> Node:
    """Distance of the elbow from the line of the pivot and C (links a, b; |C - pivot| = d).
    x^0.5 of a negative product is #NUM! where C is out of reach."""
    return root((a + b + d) * (a + b - d) * (d + a - b) * (d - a + b)) / (2 * d)


def _projection(a: Node, b: Node, d: Node) -> Node:
    """Projection of the elbow on the line pivot->C."""
    return ((a - b) * (a + b) + d ** 2) / (2 * d)


Q = Quantity
PATH_AND_REACH = (
    Q("x_C", "m", x_0 + R_path * cos(radians(phi)), "point C on its path, x"),
    Q("y_C", "m", y_0 + R_path * sin(radians(phi)), "point C on its path, y"),
    Q("psi_AC", "deg", _direction(x_C, y_C, x_0, y_0),
      "direction of A->C, continuous (measured from A->path centre)", output=False),
    Q("d_AC", "m", sqrt(x_C ** 2 + y_C ** 2), "distance |C - A|", output=False),
    Q("h_B", "m", _half_chord(l_1, l_2, d_AC), "distance of B from the line AC (left)",
      output=False),
    Q("psi_EC", "deg", _direction(x_C - l_5, y_C, x_0 - l_5, y_0),
      "direction of E->C, continuous (measured from E->path centre)", output=False),
    Q("d_EC", "m", sqrt((x_C - l_5) ** 2 + y_C ** 2), "distance |C - E|", output=False),
    Q("h_D", "m", _half_chord(l_4, l_3, d_EC), "distance of D from the line EC (right)",
      output=False),
)

CLOSED = (
    Q("theta_1", "deg", psi_AC + degrees(atan2(_projection(l_1, l_2, d_AC), h_B)),
      "crank AB angle, inverse kinematics (B left of A->C), continuous"),
    Q("theta_4", "deg", psi_EC - degrees(atan2(_projection(l_4, l_3, d_EC), h_D)),
      "crank ED angle, inverse kinematics (D right of E->C), continuous"),
)

CANNOT = or_(iserror(h_B), iserror(h_D))
#: A dyad whose elbow is within this fraction of its reach (h_B <= LIMIT_FRACTION (l_1 + l_2),
#: stretched or folded) is at the limit of its workspace: the half chord carries an absolute
#: rounding of about eps (l_1 + l_2)^2 / h_B, so theta_1 keeps ~eps (l_1 + l_2) / h_B rad, and
#: the clearance columns (C' - C of size r_clear, from B and D) amplify it further: 6.6e-9 of
#: their magnitude at h_B = 2.4e-6 (l_1 + l_2) against 50-digit mpmath, 4.2e-12 at 2.4e-3.
#: The row is flagged "limit".
LIMIT_FRACTION = 1e-3
AT_LIMIT = or_(le(h_B, LIMIT_FRACTION * (l_1 + l_2)), le(h_D, LIMIT_FRACTION * (l_3 + l_4)))
IN_LINE = eq(Var("det_BCD"), 0)   # B, C, D in line (five_bar_errors.SINGULAR_FRACTION)


def flagged(unconverged: Node | None = None) -> Node:
    """'cannot assemble', 'limit' (a dyad stretched or folded), 'not converged' (Newton,
    where ``unconverged``), 'singular' (B, C, D in line: the sensitivities are #DIV/0!),
    else 'ok'."""
    rest = if_(IN_LINE, "singular", "ok")
    if unconverged is not None:
        rest = if_(unconverged, "not converged", rest)
    return if_(CANNOT, "cannot assemble", if_(AT_LIMIT, "limit", rest))


CLOSED_STATUS = flagged()


def _checks() -> tuple[Check, ...]:
    """Closure of both loops with B and D rebuilt from the input angles, C on its circle,
    and the branch (zero on the elbows-out branch)."""
    t1, t4 = radians(theta_1), radians(theta_4)
    bx, by = x_C - l_1 * cos(t1), y_C - l_1 * sin(t1)            # C - B
    dx, dy = x_C - l_5 - l_4 * cos(t4), y_C - l_4 * sin(t4)       # C - D
    return (
        Check("coupler_BC", "position", (sqrt(bx ** 2 + by ** 2) - l_2) / l_2,
              "|C - B| - l_2, over l_2 (B = l_1 (cos theta_1, sin theta_1))"),
        Check("coupler_DC", "position", (sqrt(dx ** 2 + dy ** 2) - l_3) / l_3,
              "|C - D| - l_3, over l_3 (D = E + l_4 (cos theta_4, sin theta_4))"),
        Check("path", "position",
              (sqrt((x_C - x_0) ** 2 + (y_C - y_0) ** 2) - R_path)
              / (R_path + abs_(x_0) + abs_(y_0)),
              "|C - (x_0, y_0)| - R_path, over R_path + |x_0| + |y_0| (C's coordinates "
              "carry the rounding of x_0 and y_0, which the difference cancels)"),
        Check("elbow_B_left", "position",
              min_(0, x_C * sin(t1) - y_C * cos(t1)) / l_2,
              "(C - A) x (B - A) / l_1 where negative (B right of A->C), over l_2"),
        Check("elbow_D_right", "position",
              max_(0, (x_C - l_5) * sin(t4) - y_C * cos(t4)) / l_3,
              "(C - E) x (D - E) / l_4 where positive (D left of E->C), over l_3"),
    )


OPTIONS = (
    OptionSpec("method", "closed", "inverse kinematics: closed form, or Newton-Raphson steps "
               "as columns", choices=("closed", "newton")),
    OptionSpec("iterations", 8, "Newton-Raphson steps (method = \"newton\")", minimum=1,
               maximum=20),
)


def configure(template: Template, options: Mapping[str, object]) -> Template:
    """Closed-form or Newton inverse kinematics; the rest of the template is shared."""
    if options["method"] == "closed":
        return template
    steps = int(options["iterations"])  # type: ignore[arg-type]
    quantities = PATH_AND_REACH + newton_quantities(steps) + SENSITIVITY + CLEARANCE
    return replace(template, quantities=quantities, status=newton_status(steps, flagged))


def _validate(p: Mapping[str, float]) -> tuple[str, str] | None:
    if p["x_0"] == 0 and p["y_0"] == 0:
        return ("x_0", "the path centre (x_0, y_0) must not coincide with the pivot A = (0, 0)")
    if p["x_0"] == p["l_5"] and p["y_0"] == 0:
        return ("x_0", "the path centre (x_0, y_0) must not coincide with the pivot E = (l_5, 0)")
    return None


def _why_not(p: Mapping[str, float]) -> str:
    return (f"no point of C's path (centre ({p['x_0']:g}, {p['y_0']:g}), R_path = "
            f"{p['R_path']:g}) is within reach of both dyads: needs "
            f"|l_1 - l_2| <= |C - A| <= l_1 + l_2 and |l_4 - l_3| <= |C - E| <= l_4 + l_3")


TEMPLATE = Template(
    id="five_bar",
    title="Five-bar linkage: inverse kinematics, link-length sensitivity, joint clearance",
    description="Two cranks drive point C around a circle; crank angles by inverse "
                "kinematics, sensitivity of C to the link lengths, and C's error from a "
                "clearance at each joint.",
    input=InputSpec("phi", "deg", "angle of C on its circular path"),
    parameters=PARAMETERS,
    quantities=PATH_AND_REACH + CLOSED + SENSITIVITY + CLEARANCE,
    status=CLOSED_STATUS,
    checks=_checks(),
    charts=(
        Chart("Path of C", "x_C", ("y_C",), "y_C [m]", path=True),
        Chart("Crank angles", "phi", ("theta_1", "theta_4"), "angle [deg]"),
    ) + SENSITIVITY_CHARTS + CLEARANCE_CHARTS,
    spans=(Span("crank AB swing", "theta_1"), Span("crank ED swing", "theta_4")),
    options=OPTIONS,
    links=(),  # position-only: no rates, so no shaking force
    length_unit_m=1.0,
    configure=configure,
    validate=_validate,
    assembly_failure=_why_not,
)
