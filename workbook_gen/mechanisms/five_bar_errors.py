"""Five-bar: sensitivity of C to the link lengths, and C's exact error from joint clearance.

Both hold the inputs theta_1, theta_4.  With p = C - B and q = C - D the closure
equations are f1 = |p|^2 - l_2^2 = 0, f2 = |q|^2 - l_3^2 = 0, so
A = d(f1, f2)/d(x_C, y_C) = 2 [p; q] and B = d(f1, f2)/d(l_1..l_5) =
-2 [p.u_1, l_2, 0, 0, 0; 0, 0, l_3, q.u_4, q_x] (u_1, u_4 the crank directions; E moves
with l_5 along x).  S = -A^-1 B with the 2x2 inverse written out:
S = [q_y, -p_y; -q_x, p_x] [p.u_1, l_2, 0, 0, 0; 0, 0, l_3, q.u_4, q_x] / det_BCD,
det_BCD = p x q (zero when B, C, D are in line: C is then not located; made 0 within
SINGULAR_FRACTION l_2 l_3 of that, so S is #DIV/0! in the rows flagged "singular").

Clearance r_clear at one joint, direction alpha, u = (cos alpha, sin alpha) (issue 12):
  joint A or E (a crank's pivot): the crank's journal is offset from its ground pivot by
           r_clear u, so coupler 2's end B (resp. coupler 3's end D) moves by +r_clear u;
  joint B: coupler 2's journal at B is offset by -r_clear u: B moves by -r_clear u;
  joint C or D: coupler 3's end D moves by -r_clear u (at C: coupler 3's eye sits at
           r_clear u from coupler 2's pin C, the output point).
So with the inputs held B at alpha is A at alpha + 180 deg, C and D agree, and E at alpha
is D at alpha + 180 deg; the reference solves each joint from its own displaced geometry.

C' is re-solved exactly (not linearised) as a small displacement e = C' - C, without
cancellation: with B', D' the moved ends, g = D' - B', m the unit normal to g (left),
the powers of C with respect to the moved circles k_1 = |C - B'|^2 - l_2^2,
k_2 = |C - D'|^2 - l_3^2 (= r^2 - 2 p.delta or r^2 - 2 q.delta: no subtraction of
near-equal terms), e = ea g/|g| + en m with
  ea = (k_2 - k_1) / (2 |g|)  (the radical line of the two circles; written inline),
  en = -gamma / (beta + SIGN(beta) sqrt(beta^2 - gamma)),  the small root of
  en^2 + 2 beta en + gamma = 0, beta = m.(C - B'), gamma = ea^2 + 2 ea (g/|g|).(C - B') + k_1.
The root kept puts C' on the same side of the line B'D' as C (the assembly mode kept).
The error of C is C' - C = ea g/|g| + en m: its components dx_C_<joint>_<alpha>,
dy_C_<joint>_<alpha> [m] and its length |C' - C| = sqrt(ea^2 + en^2) (dC_<joint>_<alpha>);
the intermediate columns en_B_<alpha> / en_D_<alpha> hold en for coupler end B / D moved.
"""

from __future__ import annotations

from ..expr import Node, Var, abs_, cos, eq, if_, le, radians, root, sign, sin, sqrt
from .base import Chart, Quantity, symbols

l_1, l_2, l_3, l_4, l_5, r_clear = symbols("l_1 l_2 l_3 l_4 l_5 r_clear")
x_C, y_C, x_B, y_B, x_D, y_D, det_BCD, theta_1, theta_4 = (
    Var(n) for n in "x_C y_C x_B y_B x_D y_D det_BCD theta_1 theta_4".split())

Q = Quantity
px, py = x_C - x_B, y_C - y_B        # C - B
qx, qy = x_C - x_D, y_C - y_D        # C - D
p_u1 = (px * x_B + py * y_B) / l_1            # (C - B).u_1
q_u4 = (qx * (x_D - l_5) + qy * y_D) / l_4    # (C - D).u_4

POSITIONS = (
    Q("x_B", "m", l_1 * cos(radians(theta_1)), "crank pin B, x", output=False),
    Q("y_B", "m", l_1 * sin(radians(theta_1)), "crank pin B, y", output=False),
    Q("x_D", "m", l_5 + l_4 * cos(radians(theta_4)), "crank pin D, x", output=False),
    Q("y_D", "m", l_4 * sin(radians(theta_4)), "crank pin D, y", output=False),
)

_ROWS = {"x": (qy, -py), "y": (-qx, px)}   # rows of the adjugate of [p; q]
_B1 = {1: p_u1, 2: l_2}                   # -B/2, first row (f1)
_B2 = {3: l_3, 4: q_u4, 5: qx}            # -B/2, second row (f2)


def _sensitivity(axis: str, i: int) -> Node:
    first, second = _ROWS[axis]
    term = first * _B1[i] if i in _B1 else second * _B2[i]
    return term / det_BCD


#: B, C, D within this fraction of l_2 l_3 of a line (|sin BCD| below it) is the forward
#: singularity: det_BCD is made 0 there, so the sensitivities are #DIV/0! and the row is
#: flagged "singular".  det_BCD carries an absolute rounding of a few eps (l_1 + |C|)
#: (l_2 + l_3) (B, D rebuilt from the angles), and S = term / det_BCD and the clearance's
#: small root divide by it: 3.5e-10 of S's magnitude at l_2 3e-6 from in line, 6.3e-11 at
#: 3e-4 (50-digit mpmath).
SINGULAR_FRACTION = 1e-4
cross_BCD = Var("cross_BCD")

SENSITIVITY = POSITIONS + (
    Q("cross_BCD", "m^2", px * qy - py * qx, "(C - B) x (C - D) as computed", output=False),
    Q("det_BCD", "m^2", if_(le(abs_(cross_BCD), SINGULAR_FRACTION * l_2 * l_3), 0, cross_BCD),
      "(C - B) x (C - D): det(A)/4 of the closure Jacobian in (x_C, y_C); 0 within "
      "SINGULAR_FRACTION l_2 l_3 of B, C, D in line (C is not located there)", output=False),
) + tuple(
    Q(f"S_{axis}_l{i}", "m/m", _sensitivity(axis, i),
      f"sensitivity d{axis}_C/dl_{i} with theta_1, theta_4 held (S = -A^-1 B)")
    for axis in ("x", "y") for i in range(1, 6))

ANGLES = (0, 90, 180, 270)
_UNIT = {0: (1, 0), 90: (0, 1), 180: (-1, 0), 270: (0, -1)}


def _plus(node: Node, s: int) -> Node:
    """node + s r_clear for s in (-1, 0, 1), without a '+0' term."""
    return node if s == 0 else (node + r_clear if s > 0 else node - r_clear)


def _power(s: int, along_x: bool, v: tuple[Node, Node]) -> Node:
    """r^2 - 2 v.delta for delta = s r_clear along x or y: the power of C with respect
    to a circle through C whose centre moved by delta (v = C - old centre)."""
    v_i = v[0 if along_x else 1]
    return r_clear * (r_clear - 2 * v_i if s > 0 else r_clear + 2 * v_i)


def _clearance_pair(end: str, alpha: int) -> tuple[list[Quantity], Node, Node,
                                                  tuple[Node, Node, Node]]:
    """(columns, ea, en, (g_x, g_y, |g|)) of C's displacement when coupler end ``end``
    ("B" or "D") moves by delta at ``alpha``: the columns g, ea, beta and gamma of the
    case (so that en's formula is short enough to read), ea and |g| as references to
    them; ea exists even where the moved circles do not meet, en is #NUM! there."""
    cx, cy = _UNIT[alpha]
    s, along_x = cx + cy, cx != 0
    if end == "B":   # B' = B + delta: g = D - B', C - B' = p - delta
        gx, gy = _plus(x_D - x_B, -cx), _plus(y_D - y_B, -cy)
        wx, wy = _plus(px, -cx), _plus(py, -cy)
        k_1 = _power(s, along_x, (px, py))
        along = -k_1
    else:            # D' = D + delta: g = D' - B, C - B' = p
        gx, gy = _plus(x_D - x_B, cx), _plus(y_D - y_B, cy)
        wx, wy = px, py
        k_1 = None
        along = _power(s, along_x, (qx, qy))
    case = f"{end}_{alpha}"
    g, ea, beta, gamma = (Var(f"{n}_{case}") for n in ("g", "ea", "beta", "gamma"))
    moved = f"coupler end {end} moved by r_clear at {alpha} deg"
    gamma_tree = ea ** 2 + 2 * ea * (gx * wx + gy * wy) / g
    if k_1 is not None:
        gamma_tree = gamma_tree + k_1
    columns = [
        Q(f"g_{case}", "m", sqrt(gx ** 2 + gy ** 2), f"|D' - B'|, {moved}", output=False),
        Q(f"ea_{case}", "m", along / (2 * g), f"C's error along D' - B', {moved}",
          output=False),
        Q(f"beta_{case}", "m", (gx * wy - gy * wx) / g,
          f"C - B' across D' - B' (to the left), {moved}", output=False),
        Q(f"gamma_{case}", "m^2", gamma_tree,
          f"power of C with respect to the moved circles, {moved}", output=False),
    ]
    # B, C, D in line (det_BCD made 0, "singular"): beta is rounding, and which of the two
    # C' is meant is not decided by its sign: #DIV/0! in every engine
    return columns, ea, \
        -gamma / if_(eq(det_BCD, 0), 0, beta + sign(beta) * root(beta ** 2 - gamma)), (gx, gy, g)


def _clearance_columns() -> tuple[Quantity, ...]:
    out, along, line = [], {}, {}
    for end in ("B", "D"):
        moved = ("coupler 2's end B (joint A or B)" if end == "B"
                 else "coupler 3's end D (joint C, D or E)")
        for alpha in ANGLES:
            columns, along[f"{end}_{alpha}"], en, line[f"{end}_{alpha}"] = \
                _clearance_pair(end, alpha)
            out += columns
            out.append(Q(f"en_{end}_{alpha}", "m", en,
                         f"C's error normal to D'-B' (to the left) when {moved} moves by "
                         f"r_clear at {alpha} deg; #NUM! where C' does not exist",
                         output=False))
    # which coupler end moves, and by delta at alpha + turn
    source = {"A": ("B", 0), "B": ("B", 180), "C": ("D", 180), "D": ("D", 180),
              "E": ("D", 0)}
    signed = []
    for joint, (end, turn) in source.items():
        for alpha in ANGLES:
            case = f"{end}_{(alpha + turn) % 360}"
            ea, en = along[case], Var(f"en_{case}")
            gx, gy, g = line[case]
            where = f"from a clearance r_clear at joint {joint}, direction {alpha} deg"
            out.append(Q(f"dC_{joint}_{alpha}", "m", sqrt(ea ** 2 + en ** 2),
                         f"|C' - C|: exact error of C {where}"))
            signed += [Q(f"dx_C_{joint}_{alpha}", "m", (ea * gx - en * gy) / g,
                         f"x of C' - C, exact, {where}"),
                       Q(f"dy_C_{joint}_{alpha}", "m", (ea * gy + en * gx) / g,
                         f"y of C' - C, exact, {where}")]
    return tuple(out + signed)


CLEARANCE = _clearance_columns()

SENSITIVITY_CHARTS = tuple(
    Chart(f"Sensitivity of {axis}_C to the link lengths", "phi",
          tuple(f"S_{axis}_l{i}" for i in range(1, 6)), f"d{axis}_C/dl [m/m]")
    for axis in ("x", "y"))
CLEARANCE_CHARTS = tuple(
    Chart(f"Error of C from a clearance at joint {joint}", "phi",
          tuple(f"dC_{joint}_{alpha}" for alpha in ANGLES), "|C' - C| [m]")
    for joint in "ABCDE")
