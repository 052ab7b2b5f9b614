"""The four-bar's trees, written once for every template built on a four-bar.

Ground O1 = (0, 0), O2 = (l_O1O2, 0); crank O1A at theta_2 (deg), omega_2
constant; coupler AB; rocker O2B; coupler point C at l_AC from A, at delta_C
(deg) from the direction A->B.

Position (cancellation-free circle intersection).  With d = |O2 - A|, the unit
vector e along A->O2 and n its left normal, B = A + f e + s h n, where
f = ((l_AB - l_O2B)(l_AB + l_O2B) + d^2) / (2 d) is the foot of B on A->O2 and
h = root((p^2 - d^2)(d^2 - q^2)) / (2 d), p = l_AB + l_O2B,
q = l_AB - l_O2B, is the half chord (#NUM! where the circles do not meet); the two
factors are formed from the crank's half angles and exactly summed length gaps, so
they keep full relative accuracy at the Grashof boundary (docs/stability.md).
s = +1 on the open branch (Norton: B left of the directed line A->O2), -1 on
the crossed one.

Angles are continuous: phi_AO2, the direction of A->O2, stays within 90 deg of
the ground direction where the crank is shorter than the ground and follows
the crank (within 90 deg of theta_2 + 180) where it is longer; theta_3 and
theta_4 are phi_AO2 + s*ATAN2(f, h) and phi_AO2 + s*ATAN2(f - d, h), i.e.
within [0, 180] of it on the side of the branch.  (The sign multiplies the
ATAN2, never h, so no negative zero reaches ATAN2.)

Rates, with a = A - O1, b = B - A, c = B - O2 (2-D cross u x w = u_x w_y - u_y w_x)
and b x c = s h d (exactly 0 at a toggle, where the rates are #DIV/0!):
omega_3 = -omega_2 (a x c) / (b x c),  omega_4 = -omega_2 (a x b) / (b x c), written as
omega_2 (s (f - d) g y_A / h - (g x_A - a^2)) / d^2 and the same with f for omega_4 (the
ratio y_A / h stays finite at a change point; a = |O1A|, g = |O1O2|),
alpha_3 = (omega_2^2 a.c + omega_3^2 b.c - omega_4^2 l_O2B^2) / (b x c),
alpha_4 = (omega_2^2 a.b + omega_3^2 l_AB^2 - omega_4^2 b.c) / (b x c).
Transmission angle (Norton): the acute angle between coupler and rocker,
mu = ATAN2(|b.c|, |b x c|).
"""

from __future__ import annotations

from ..expr import (Node, Param, abs_, and_, atan2, cos, degrees, eq, gt, if_, iserror, le, lt,
                    max_, min_, or_, pi, radians, root, sin, sqrt, wrap)
from .angles import (cos_deg, cos_half_squared_90, reduced, reduced_input, sin_deg,
                     sin_half_squared_90)
from .base import (Chart, Check, Derived, Figure, Link, ParamSpec, Quantity, only_if, quantity_vars,
                   speed_scale, symbols)

BRANCHES = ("open", "crossed")

l_O1O2, l_O1A, l_AB, l_O2B, l_AC, delta_C, omega_2 = symbols(
    "l_O1O2 l_O1A l_AB l_O2B l_AC delta_C omega_2")
(theta_2, x_A, y_A, d_AO2, phi_AO2, f_B, p2_d2, d2_q2, h_B, hr_B, theta_3, theta_4, x_B, y_B, omega_3, omega_4,
 alpha_3, alpha_4, x_C, y_C, vx_C, vy_C, ax_C, ay_C, mu) = quantity_vars(
    "theta_2 x_A y_A d_AO2 phi_AO2 f_B p2_d2 d2_q2 h_B hr_B theta_3 theta_4 x_B y_B omega_3 omega_4 "
    "alpha_3 alpha_4 x_C y_C vx_C vy_C ax_C ay_C mu")

THETA_2R, theta_2r = reduced_input("theta_2r", theta_2, "crank angle")

# Limits (docs/stability.md, four_bar).  p^2 - d^2 = G (p + g + a) + 4 g a cos^2(theta_2/2)
# and d^2 - q^2 = G1 G2 + 4 g a sin^2(theta_2/2) round to a few ulps of the sum of their
# terms' magnitudes, which at the limit (the factor near 0) is twice the crank term,
# 4 g a cos^2 = (g + a)^2 - d^2 resp. 4 g a sin^2 = d^2 - (g - a)^2.  Within REACH_ROUNDING
# of that a factor is 0: coupler and rocker exactly in line (an assembly limit hit at a
# grid angle), h_B = 0, a toggle whose rates are #DIV/0!, never the square root of
# rounding.  Within LIMIT_BAND of it the rates would keep fewer than 9 digits: the row is a
# toggle and its rates #DIV/0! as well (hr_B = 0).
REACH_ROUNDING = 32 * 2.0 ** -52
LIMIT_BAND = 2e-6

OUTPUTS = ("theta_3", "theta_4", "omega_3", "omega_4", "alpha_3", "alpha_4",
           "x_C", "y_C", "vx_C", "vy_C", "ax_C", "ay_C", "mu")


def parameters(lengths: tuple[float, float, float, float, float], delta: float,
               omega: float, unit: str = "mm") -> tuple[ParamSpec, ...]:
    """The four-bar's parameters with defaults (ground, crank, coupler, rocker, l_AC)."""
    ground, crank, coupler, rocker, point = lengths
    return (
        ParamSpec("l_O1O2", ground, unit, "ground O1O2 (O2 on +x from O1)", positive=True),
        ParamSpec("l_O1A", crank, unit, "crank O1A (input)", positive=True),
        ParamSpec("l_AB", coupler, unit, "coupler AB", positive=True),
        ParamSpec("l_O2B", rocker, unit, "rocker O2B (output)", positive=True),
        ParamSpec("l_AC", point, unit, "coupler point C, distance from A"),
        ParamSpec("delta_C", delta, "deg", "coupler point C, angle from the direction A->B"),
        ParamSpec("omega_2", omega, "rad/s", "crank speed, counter-clockwise"),
    )


def _pm(a: Node, b: Node, s: int) -> Node:
    """a + s*b, printed as a + b or a - b."""
    return a + b if s > 0 else a - b


# The three length gaps of h_B's factors, exact to the last bit where tiny (a four-bar at
# the Grashof boundary): constants of the linkage, so derived values on the Parameters
# sheet, each formula written once there, and the Table's formulas name them (a Table
# formula with them inline was 1,420 characters long).
def _gap_values(name: str, a: Node, b: Node, c: Node, d: Node) -> tuple[Derived, ...]:
    """G_<name> = (a + b) - (c + d) to full relative accuracy when it is tiny (a four-bar
    at the Grashof boundary), in three short formulas: the differences of the larger and
    of the smaller lengths (G_<name>_hi, _lo; nearly opposite there, their sum exact by
    Sterbenz), then their sum with their rounding errors (Knuth's TwoDiff, from the
    cells: where a spreadsheet makes a difference within 15 digits of 0 exactly 0, the
    error term restores it)."""
    big, small = (max_(a, b), max_(c, d)), (min_(a, b), min_(c, d))
    hi, lo = Param(f"G_{name}_hi"), Param(f"G_{name}_lo")

    def error(s: Node, x: Node, y: Node) -> Node:   # x - y - s, s = fl(x - y)
        z = s - x
        return (x - (s - z)) - (y + z)
    a, b, c, d = (v.name for v in (a, b, c, d))
    what = f"({a} + {b}) - ({c} + {d})"
    return (Derived(f"G_{name}_hi", "mm", big[0] - big[1],
                    f"the larger of {a}, {b} less the larger of {c}, {d}"),
            Derived(f"G_{name}_lo", "mm", small[0] - small[1],
                    f"the smaller of {a}, {b} less the smaller of {c}, {d}"),
            Derived(f"G_{name}", "mm", (hi + lo) + (error(hi, *big) + error(lo, *small)),
                    f"{what}, exact where tiny (G_{name}_hi + G_{name}_lo and their "
                    f"rounding errors)"))


G_far, G_near, G_cross = Param("G_far"), Param("G_near"), Param("G_cross")
GAPS = (_gap_values("far", l_AB, l_O2B, l_O1O2, l_O1A)
        + _gap_values("near", l_O1O2, l_O2B, l_AB, l_O1A)
        + _gap_values("cross", l_O1O2, l_AB, l_O2B, l_O1A))


def _signed(a: Node, s: int) -> Node:
    """s*a, printed as a or -a."""
    return a if s > 0 else -a


def _dot(u: tuple[Node, Node], w: tuple[Node, Node]) -> Node:
    return u[0] * w[0] + u[1] * w[1]


#: Rows whose rates carry more than about this relative rounding are at a toggle.
TOGGLE_LOSS = 1e-10
_EPS = 2.0 ** -52


def _rounded_toggle() -> Node:
    """True where the rates' rounding exceeds TOGGLE_LOSS: coupler and rocker in line to
    rounding away from a change point.  h_B^2 = far near / (4 d^2) comes from the factors
    far = p^2 - d^2 and near = d^2 - q^2 formed with 4 g a cos^2(theta_2/2) and
    4 g a sin^2(theta_2/2), whose rounding (eps times at most 2 g (a + x_A), resp.
    2 g (a - x_A), beyond the factor itself) makes h_B, and with it every rate, off by
    eps g ((a - x_A) far + (a + x_A) near) / (2 d^2 h_B^2) relative; far and near are only
    weighed here (the columns p2_d2 and d2_q2).  At a change point both terms vanish like
    h_B^2 (the ratio y_A / h_B stays finite): not flagged by this, but by TOGGLE_FRACTION."""
    weight = l_O1O2 * ((l_O1A - x_A) * abs_(p2_d2) + (l_O1A + x_A) * abs_(d2_q2))
    return lt(2 * TOGGLE_LOSS / _EPS * d_AO2 ** 2 * h_B ** 2, weight)


_ROUNDED_TOGGLE = _rounded_toggle()
#: Rows with B within this fraction of l_AB + l_O2B of the line A->O2 are flagged
#: "toggle": the rates there are singular (b x c = 0) or, a hair away from a change
#: point, their accelerations carry rounding amplified by (l_AB + l_O2B) / h_B (1e-4:
#: the closure of the accelerations stays within 1e-10 outside it, docs/stability.md).
TOGGLE_FRACTION = 1e-4
_TOGGLE = or_(le(h_B, TOGGLE_FRACTION * (l_AB + l_O2B)), _ROUNDED_TOGGLE)


def _coupler_direction() -> tuple[Node, Node]:
    """COS and SIN of delta_C, the angle first reduced exactly to [-180, 180] deg
    (angles.reduced; the same value for |delta_C| <= 180): RADIANS of a delta_C of 1e10 deg
    is off by 2e-8 rad, and SIN of 2^27 rad or more is #NUM! in Excel."""
    delta = radians(reduced(delta_C))
    return cos(delta), sin(delta)


def quantities(branch: str) -> tuple[Quantity, ...]:
    """The Table columns of a four-bar with coupler point C, for ``branch``."""
    s = 1 if branch == "open" else -1
    t = radians(theta_2)
    gx = l_O1O2 - x_A                       # O2 - A = (gx, -y_A)
    p, q = l_AB + l_O2B, l_AB - l_O2B
    a, b, c = (x_A, y_A), (x_B - x_A, y_B - y_A), (x_B - l_O1O2, y_B)
    bc = _dot(b, c)
    w2 = omega_2 ** 2

    # p^2 - d^2 and d^2 - q^2 from the crank's half angles, free of cancellation at the
    # change point and the toggles (d^2 = g^2 + a^2 - 2 g a cos theta_2):
    # p^2 - d^2 = (p - g - a)(p + g + a) + 4 g a cos^2(theta_2/2),
    # d^2 - q^2 = (g - a - q)(g - a + q) + 4 g a sin^2(theta_2/2),
    # the sums of lengths differenced in sorted pairs (_gap_values: G_far, G_near, G_cross).
    ga4 = 4 * l_O1O2 * l_O1A
    far = (G_far * (p + l_O1O2 + l_O1A)
           + ga4 * cos_half_squared_90(theta_2r))
    near = (G_near * G_cross
            + ga4 * sin_half_squared_90(theta_2r))
    crank_far = abs_((l_O1O2 + l_O1A) ** 2 - d_AO2 ** 2)    # 4 g a cos^2(theta_2/2)
    crank_near = abs_(d_AO2 ** 2 - (l_O1O2 - l_O1A) ** 2)   # 4 g a sin^2(theta_2/2)

    def unless_in_line(fraction: float, value: Node) -> Node:
        """0 where a factor is within ``fraction`` of its terms, else ``value`` (nested
        IFs rather than OR, which the audit's rounding-noise estimate follows)."""
        return if_(le(abs_(p2_d2), fraction * crank_far), 0,
                   if_(le(abs_(d2_q2), fraction * crank_near), 0, value))

    # a x e and a.e times d (e the unit vector A->O2): -g y_A and g x_A - a^2; the rates
    # as ratios y_A / h_B, both proportional to theta_2 near a change point; #DIV/0! in a
    # toggle row (hr_B = 0), where they are singular or rounding noise
    lever = l_O1O2 * y_A / hr_B
    a_e = l_O1O2 * x_A - l_O1A ** 2

    def over_bxc(num: Node) -> Node:          # num / (b x c), b x c = s h d
        return (num if s > 0 else -num) / (hr_B * d_AO2)

    cd, sd = _coupler_direction()
    k = l_AC / l_AB
    px, py = x_C - x_A, y_C - y_A           # C - A
    Q = Quantity
    return (
        # A from the crank angle reduced exactly to [-180, 180] (angles.py): bit-identical
        # rows at 0 and 360 deg, and y_A exact (0) at 0 and 180 and accurate near them
        THETA_2R,
        Q("x_A", "mm", l_O1A * cos_deg(theta_2r), "crank pin A, x", output=False),
        Q("y_A", "mm", l_O1A * sin_deg(theta_2r), "crank pin A, y", output=False),
        Q("d_AO2", "mm", sqrt(gx ** 2 + y_A ** 2), "distance A to O2", output=False),
        # A on O2 (crank = ground at 0 deg): no direction, #DIV/0! (never ATAN2(0, 0),
        # which LibreOffice makes 0)
        Q("phi_AO2", "rad",
          if_(lt(l_O1A, l_O1O2), atan2(gx, 0 - y_A),
              if_(gt(d_AO2, 0), t + pi() + atan2(l_O1A ** 2 - l_O1O2 * x_A, l_O1O2 * y_A),
                  1 / d_AO2)),
          "direction of A->O2, continuous", output=False),
        Q("f_B", "mm", (q * p + d_AO2 ** 2) / (2 * d_AO2), "foot of B on the line A->O2",
          output=False),
        Q("p2_d2", "mm^2", far, "(l_AB + l_O2B)^2 - d_AO2^2: 0 with coupler and rocker "
          "extended in line", output=False),
        Q("d2_q2", "mm^2", near, "d_AO2^2 - (l_AB - l_O2B)^2: 0 with them folded in line",
          output=False),
        Q("h_B", "mm", root(unless_in_line(REACH_ROUNDING, p2_d2 * d2_q2)) / (2 * d_AO2),
          "distance of B from the line A->O2 (half chord)", output=False),
        Q("hr_B", "mm", if_(_TOGGLE, 0, unless_in_line(LIMIT_BAND, h_B)),
          "h_B where the rates keep their digits, else 0 (the rates #DIV/0!)", output=False),
        Q("theta_3", "deg", degrees(_pm(phi_AO2, atan2(f_B, h_B), s)),
          "coupler angle (direction A->B)"),
        Q("theta_4", "deg", degrees(_pm(phi_AO2, atan2(f_B - d_AO2, h_B), s)),
          "rocker angle (direction O2->B)"),
        Q("x_B", "mm", x_A + _pm(f_B * gx, h_B * y_A, s) / d_AO2, "coupler-rocker pin B, x",
          output=False),
        Q("y_B", "mm", (y_A + (h_B * gx - f_B * y_A) / d_AO2 if s > 0
                        else y_A - (h_B * gx + f_B * y_A) / d_AO2),
          "coupler-rocker pin B, y", output=False),
        Q("omega_3", "rad/s", omega_2 * (_signed((f_B - d_AO2) * lever, s) - a_e) / d_AO2 ** 2,
          "coupler angular velocity"),
        Q("omega_4", "rad/s", omega_2 * (_signed(f_B * lever, s) - a_e) / d_AO2 ** 2,
          "rocker angular velocity"),
        Q("alpha_3", "rad/s^2",
          over_bxc(w2 * _dot(a, c) + omega_3 ** 2 * bc - omega_4 ** 2 * l_O2B ** 2),
          "coupler angular acceleration"),
        Q("alpha_4", "rad/s^2",
          over_bxc(w2 * _dot(a, b) + omega_3 ** 2 * l_AB ** 2 - omega_4 ** 2 * bc),
          "rocker angular acceleration"),
        Q("x_C", "mm", x_A + k * (b[0] * cd - b[1] * sd), "coupler point C, x"),
        Q("y_C", "mm", y_A + k * (b[0] * sd + b[1] * cd), "coupler point C, y"),
        Q("vx_C", "mm/s", -omega_2 * y_A - omega_3 * py, "coupler point C, x velocity"),
        Q("vy_C", "mm/s", omega_2 * x_A + omega_3 * px, "coupler point C, y velocity"),
        Q("ax_C", "mm/s^2", -w2 * x_A - alpha_3 * py - omega_3 ** 2 * px,
          "coupler point C, x acceleration"),
        Q("ay_C", "mm/s^2", -w2 * y_A + alpha_3 * px - omega_3 ** 2 * py,
          "coupler point C, y acceleration"),
        Q("mu", "deg", degrees(atan2(abs_(bc), h_B * d_AO2)),
          "transmission angle (acute angle between coupler and rocker)"),
    )


# A on O2 with coupler = rocker (a kite folding at 0 deg): B anywhere on one circle, a
# change point whose positions are undefined (#DIV/0!); with coupler != rocker nothing closes.
# A toggle: hr_B = 0 (TOGGLE_FRACTION, the rates' rounding, LIMIT_BAND of a reach limit).
STATUS = if_(iserror(h_B),
             if_(and_(eq(d_AO2, 0), eq(l_AB, l_O2B)), "toggle", "cannot assemble"),
             if_(eq(hr_B, 0), "toggle", "ok"))


def _norm(x: Node, y: Node) -> Node:
    return sqrt(x ** 2 + y ** 2)


def checks() -> tuple[Check, ...]:
    """Loop closure and the rigid coupler point, rebuilt from theta_2 and the angle columns."""
    t, t3, t4 = radians(theta_2), radians(theta_3), radians(theta_4)
    c2, s2, c3, s3, c4, s4 = cos(t), sin(t), cos(t3), sin(t3), cos(t4), sin(t4)
    # e(theta_3 + delta_C) by the angle sum, as the Table writes C
    cd, sd = _coupler_direction()
    cc, sc = c3 * cd - s3 * sd, s3 * cd + c3 * sd
    w2 = omega_2 ** 2
    loop = (l_O1A * c2 + l_AB * c3 - l_O1O2 - l_O2B * c4, l_O1A * s2 + l_AB * s3 - l_O2B * s4)
    loop_v = (-l_O1A * omega_2 * s2 - l_AB * omega_3 * s3 + l_O2B * omega_4 * s4,
              l_O1A * omega_2 * c2 + l_AB * omega_3 * c3 - l_O2B * omega_4 * c4)
    loop_a = (-w2 * l_O1A * c2 - l_AB * (alpha_3 * s3 + omega_3 ** 2 * c3)
              + l_O2B * (alpha_4 * s4 + omega_4 ** 2 * c4),
              -w2 * l_O1A * s2 + l_AB * (alpha_3 * c3 - omega_3 ** 2 * s3)
              - l_O2B * (alpha_4 * c4 - omega_4 ** 2 * s4))
    reach = l_O1A + l_AC
    ws = speed_scale(omega_2)  # 1 at zero speed, where every rate is 0
    point = (x_C - l_O1A * c2 - l_AC * cc, y_C - l_O1A * s2 - l_AC * sc)
    point_v = (vx_C + omega_2 * l_O1A * s2 + omega_3 * l_AC * sc,
               vy_C - omega_2 * l_O1A * c2 - omega_3 * l_AC * cc)
    point_a = (ax_C + w2 * l_O1A * c2 + alpha_3 * l_AC * sc + omega_3 ** 2 * l_AC * cc,
               ay_C + w2 * l_O1A * s2 - alpha_3 * l_AC * cc + omega_3 ** 2 * l_AC * sc)
    return (
        Check("loop_position", "position", _norm(*loop) / l_O1O2,
              "|O1A + AB - O1O2 - O2B|, over l_O1O2"),
        Check("loop_velocity", "velocity", _norm(*loop_v) / (ws * l_O1A),
              "its rate, over omega_2 l_O1A"),
        Check("loop_acceleration", "acceleration", _norm(*loop_a) / (ws ** 2 * l_O1A),
              "its second rate, over omega_2^2 l_O1A"),
        Check("coupler_point_position", "position", _norm(*point) / reach,
              "|C - A - l_AC e(theta_3 + delta_C)|, over l_O1A + l_AC"),
        Check("coupler_point_velocity", "velocity", _norm(*point_v) / (ws * reach),
              "its rate, over omega_2 (l_O1A + l_AC)"),
        Check("coupler_point_acceleration", "acceleration", _norm(*point_a) / (ws ** 2 * reach),
              "its second rate, over omega_2^2 (l_O1A + l_AC)"),
    )


def _triangle_angle(r: Node) -> Node:
    """Angle (rad) at O1 between O1O2 and O1B in the triangle O1 O2 B with |O1B| = r:
    ATAN2(2 g r cos, 2 g r sin), the sine from Heron's factored form."""
    g, l4 = l_O1O2, l_O2B
    # a degenerate triangle (a change point, within the Grashof tolerance) is one
    four_area = root(max_(0, (g + r + l4) * (r + l4 - g) * (g - r + l4) * (g + r - l4)))
    return atan2((g - l4) * (g + l4) + r * r, four_area)


_LINKS = (l_O1O2, l_O1A, l_AB, l_O2B)
_TOTAL = l_O1O2 + l_O1A + l_AB + l_O2B


def _grashof() -> tuple[Node, Node, Node]:
    """(shortest link s, (s + l) - (p + q), the rounding allowed on it)."""
    return min_(*_LINKS), Param("grashof_excess"), 1e-12 * _TOTAL


def crank_rocker() -> Node:
    """True where the crank turns fully and the rocker swings (Grashof or at the change
    point, the crank the only shortest link): the toggles and the time ratio exist."""
    s, excess, tol = _grashof()
    return and_(eq(l_O1A, s), lt(l_O1A, l_O1O2), le(excess, tol))


CRANK_ROCKER_TEXT = "a crank-rocker (l_O1A the shortest link, s + l <= p + q)"


def grashof_class() -> Node:
    """Text: Grashof class by s + l against p + q and which link is shortest."""
    s, excess, tol = _grashof()
    return if_(le(abs_(excess), tol), "change point",
               if_(lt(excess, 0),
                   if_(eq(l_AB, s), "Grashof double-rocker",
                       if_(eq(l_O1O2, s), "Grashof double-crank", "Grashof crank-rocker")),
                   "non-Grashof triple-rocker"))


def figures(branch: str) -> tuple[Figure, ...]:
    """Grashof class, the crank's toggle angles (rocker extremes) and the time ratio."""
    s = 1 if branch == "open" else -1
    extended = Param("toggle_ext")   # crank and coupler in line
    folded = Param("toggle_fold")    # crank folded over the coupler
    spread = abs_(folded - extended)
    side = "above" if s > 0 else "below"
    rocks = crank_rocker()
    return (
        Figure("Grashof class", "", grashof_class(),
               "s + l against p + q (shortest s, longest l) and which link is shortest"),
        Figure("toggle, crank and coupler extended", "deg",
               only_if(degrees(extended) if s > 0 else -degrees(extended), rocks,
                       CRANK_ROCKER_TEXT),
               f"crank angle where the rocker is at one extreme (B {side} the ground line); "
               f"needs {CRANK_ROCKER_TEXT}"),
        Figure("toggle, crank and coupler folded", "deg",
               only_if(180 + degrees(folded) if s > 0 else 180 - degrees(folded), rocks,
                       CRANK_ROCKER_TEXT),
               f"crank angle where the rocker is at its other extreme (B {side} the ground "
               f"line); needs {CRANK_ROCKER_TEXT}"),
        Figure("time ratio", "", only_if((pi() + spread) / (pi() - spread), rocks,
                                         CRANK_ROCKER_TEXT),
               "slow stroke over quick stroke, (180 + beta)/(180 - beta) with beta the angle "
               f"between the two toggle lines; needs {CRANK_ROCKER_TEXT}"),
    )


def links() -> tuple[Link, ...]:
    """Crank, coupler and rocker, for the shaking force."""
    zero, w2 = wrap(0), omega_2 ** 2
    return (
        Link("crank", (zero, zero), (zero, zero), radians(theta_2), omega_2, zero),
        Link("coupler", (x_A, y_A), (-w2 * x_A, -w2 * y_A), radians(theta_3), omega_3, alpha_3),
        Link("rocker", (l_O1O2, zero), (zero, zero), radians(theta_4), omega_4, alpha_4),
    )


def charts(point: str = "Coupler point C") -> tuple[Chart, ...]:
    return (
        Chart("Coupler and rocker angles", "theta_2", ("theta_3", "theta_4"), "angle [deg]"),
        Chart("Angular velocities", "theta_2", ("omega_3", "omega_4"), "omega [rad/s]"),
        Chart("Angular accelerations", "theta_2", ("alpha_3", "alpha_4"), "alpha [rad/s^2]"),
        Chart(f"Path of {point}", "x_C", ("y_C",), "y_C [mm]", path=True),
        Chart(f"{point}: velocity", "theta_2", ("vx_C", "vy_C"), "v [mm/s]"),
        Chart(f"{point}: acceleration", "theta_2", ("ax_C", "ay_C"), "a [mm/s^2]"),
        Chart("Transmission angle", "theta_2", ("mu",), "mu [deg]"),
    )


def why_not(p) -> str:
    return (f"the coupler l_AB = {p['l_AB']:g} and rocker l_O2B = {p['l_O2B']:g} cannot close "
            f"the loop at any crank angle of the sweep (crank l_O1A = {p['l_O1A']:g}, ground "
            f"l_O1O2 = {p['l_O1O2']:g})")


# Constants of the linkage the Table's and the Summary's formulas name (derived values on
# the Parameters sheet, each formula written once there): the length gaps of h_B, the
# Grashof excess and the crank-rocker's toggle angles.
GRASHOF = (Derived("grashof_excess", "mm", 2 * (min_(*_LINKS) + max_(*_LINKS)) - _TOTAL,
                   "(s + l) - (p + q), shortest s and longest l: <= 0 for a Grashof linkage, "
                   "0 at a change point"),)
TOGGLES = (Derived("toggle_ext", "rad", _triangle_angle(l_AB + l_O1A),
                   "angle at O1 from O1O2 to O1B with crank and coupler extended in line"),
           Derived("toggle_fold", "rad", _triangle_angle(l_AB - l_O1A),
                   "angle at O1 from O1O2 to O1B with the crank folded over the coupler"))
DERIVED = GAPS + GRASHOF + TOGGLES
