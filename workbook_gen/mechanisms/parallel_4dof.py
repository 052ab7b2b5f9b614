"""Spatial 4-DOF parallel mechanism with shaking-force balance (docs/mechanisms.md, parallel_4dof).

Base frame Oxyz, z up, O the centre of leg 5's hinge (axis y).  Leg 5 (undriven):
P5 = l_5 (cos alpha, 0, sin alpha).  The platform turns about the spherical joint P5,
Q = Rz(psi) Ry(vartheta) Rx(phi); a platform point with platform coordinates a is at
P5 + Q (a - a5).  Legs i = 1..4 (R-U-S): hinge O_i1 with axis zeta_i1 = (cos gamma_i,
sin gamma_i, 0); link i1 at theta_i1 from z, xi_i1 = sin theta h_i + cos theta e_z with
h_i = (sin gamma_i, -cos gamma_i, 0), eta_i1 = zeta_i1 x xi_i1; O_i2 = O_i1 + l_i1 xi_i1;
link i2 from O_i2 to P_i, |P_i - O_i2| = l_i2.

The input t (deg) drives the pose: alpha = alpha_0 + A_alpha sin t, psi = A_psi sin(t + 45),
vartheta = A_vartheta cos t, phi = A_phi sin 2t, with dt/dtime = omega_t.

Inverse kinematics per leg, closed form: d = P_i - O_i1, A = d_z, B = d.h_i,
C = (|d|^2 + l_i1^2 - l_i2^2) / (2 l_i1), so that A cos theta + B sin theta = C:
theta_i1 = ATAN2(A, B) + s_i ATAN2(C, (A^2 + B^2 - C^2)^0.5) (Excel's argument order; the
second ATAN2 is ACOS(C / sqrt(A^2 + B^2)) without the ratio; #NUM! where P_i is out of reach).
Rates: (B cos theta - A sin theta) theta' = C' - A' cos theta - B' sin theta, with
d' = P_i' = P5' + w x (P_i - P5), w the platform's angular velocity
w = psi' e_z + vartheta' Rz(psi) e_y + phi' Q e_x.
Centres of mass: link i1 at O_i1 + u_i1 xi + v_i1 eta + w_i1 zeta; link i2 on O_i2 P_i at
xi_i from O_i2; the platform at P5 + Q (c_P - a5); leg 5 at l_5c e(alpha).
"""

from __future__ import annotations

import dataclasses
from itertools import product
from typing import Mapping

from ..expr import (Node, Param, Var, abs_, atan2, cos, degrees, eq, if_, iserror, le, or_,
                    radians, root, sin, wrap)
from ..expr.vec import (Vec3, add, combine, cross, dot, mat_mul, mat_vec, matrix_of, norm,
                        rot_x, rot_y, rot_z, sub, total, vec)
from . import parallel_4dof_balance as balancing
from .base import Chart, Check, InputSpec, OptionSpec, Quantity, Span, Template
from .parallel_4dof_params import LEGS, counterweight_parameters, parameters

BRANCHES = tuple("".join(signs) for signs in product("+-", repeat=4))
Q_NAMES = tuple(f"Q_{r}{c}" for r in (1, 2, 3) for c in (1, 2, 3))
ZERO = wrap(0)


def _p(name: str) -> Param:
    return Param(name)


def _v(name: str) -> Var:
    return Var(name)


def _vv(prefix: str, suffix: str) -> Vec3:
    """The Vars (x_, y_, z_) + suffix, e.g. the columns of P1."""
    return vec(_v(f"{prefix}x_{suffix}" if prefix else f"x_{suffix}"),
               _v(f"{prefix}y_{suffix}" if prefix else f"y_{suffix}"),
               _v(f"{prefix}z_{suffix}" if prefix else f"z_{suffix}"))


def _columns(names: tuple[str, str, str], unit: str, trees: Vec3, what: str,
             output: bool = False) -> list[Quantity]:
    return [Quantity(n, unit, t, f"{what}, {axis}", output=output)
            for n, t, axis in zip(names, trees, "xyz")]


def _xyz(stem: str, prefix: str = "") -> tuple[str, str, str]:
    return (f"{prefix}x_{stem}", f"{prefix}y_{stem}", f"{prefix}z_{stem}")


Q = matrix_of([_v(n) for n in Q_NAMES])
P5 = vec(_v("x_P5"), ZERO, _v("z_P5"))
A5 = vec(_p("a_5"), _p("b_5"), _p("c_5"))


def _h(i: int) -> Vec3:
    g = radians(_p(f"gamma_{i}"))
    return vec(sin(g), -cos(g), ZERO)


def _zeta(i: int) -> Vec3:
    g = radians(_p(f"gamma_{i}"))
    return vec(cos(g), sin(g), ZERO)


def _frame(i: int) -> tuple[Vec3, Vec3, Vec3]:
    """xi_i1, eta_i1, zeta_i1 of link i1 from the theta_i1 column."""
    t = radians(_v(f"theta_{i}1"))
    c, s, h, ez = cos(t), sin(t), _h(i), vec(ZERO, ZERO, 1)
    xi = combine((s, h), (c, ez))
    eta = combine((c, h), (-s, ez))
    return xi, eta, _zeta(i)


def _hinge(i: int) -> Vec3:
    return vec(_p(f"x_{i}0"), _p(f"y_{i}0"), _p(f"z_{i}0"))


def _on_link_i1(i: int, u: Node, v: Node, w: Node | None = None) -> Vec3:
    xi, eta, zeta = _frame(i)
    terms = [(u, xi), (v, eta)] + ([(w, zeta)] if w is not None else [])
    return add(_hinge(i), combine(*terms))


def _on_platform(a: Vec3) -> Vec3:
    return add(P5, mat_vec(Q, sub(a, A5)))


def pose_quantities() -> list[Quantity]:
    t = _v("t")
    rt, w = radians(t), _p("omega_t")
    angles = [_v(n) for n in ("psi", "vartheta", "phi")]
    rotation = mat_mul(rot_z(radians(angles[0])),
                       mat_mul(rot_y(radians(angles[1])), rot_x(radians(angles[2]))))
    entries = [rotation[r][c] for r in range(3) for c in range(3)]
    a = radians(_v("alpha"))
    psi = radians(_v("psi"))
    spin = combine((_v("psi_dot"), vec(ZERO, ZERO, 1)),
                   (_v("vartheta_dot"), vec(-sin(psi), cos(psi), ZERO)),
                   (_v("phi_dot"), vec(_v("Q_11"), _v("Q_21"), _v("Q_31"))))
    Qn = Quantity
    return [
        Qn("alpha", "deg", _p("alpha_0") + _p("A_alpha") * sin(rt), "leg-5 angle"),
        Qn("psi", "deg", _p("A_psi") * sin(radians(t + 45)), "platform: rotation about z"),
        Qn("vartheta", "deg", _p("A_vartheta") * cos(rt), "platform: rotation about y"),
        Qn("phi", "deg", _p("A_phi") * sin(radians(2 * t)), "platform: rotation about x"),
        *[Qn(n, "", e, f"rotation Q = Rz(psi) Ry(vartheta) Rx(phi), entry {n[2:]}",
             output=False) for n, e in zip(Q_NAMES, entries)],
        Qn("x_P5", "m", _p("l_5") * cos(a), "spherical joint P5, x (y = 0)", output=False),
        Qn("z_P5", "m", _p("l_5") * sin(a), "spherical joint P5, z", output=False),
        Qn("alpha_dot", "rad/s", radians(_p("A_alpha")) * cos(rt) * w, "rate of alpha",
           output=False),
        Qn("psi_dot", "rad/s", radians(_p("A_psi")) * cos(radians(t + 45)) * w, "rate of psi",
           output=False),
        Qn("vartheta_dot", "rad/s", -radians(_p("A_vartheta")) * sin(rt) * w,
           "rate of vartheta", output=False),
        Qn("phi_dot", "rad/s", 2 * radians(_p("A_phi")) * cos(radians(2 * t)) * w,
           "rate of phi", output=False),
        *_columns(("w_x", "w_y", "w_z"), "rad/s", spin,
                  "platform angular velocity psi' e_z + vartheta' Rz e_y + phi' Q e_x"),
        Qn("vx_P5", "m/s", -_v("z_P5") * _v("alpha_dot"), "velocity of P5, x", output=False),
        Qn("vz_P5", "m/s", _v("x_P5") * _v("alpha_dot"), "velocity of P5, z", output=False),
    ]


#: A leg whose reach discriminant K_i = A^2 + B^2 - C^2 is below (EDGE_FRACTION (l_i1 +
#: l_i2))^2 is at the edge of its reach (links i1 and i2 in the plane of d and the hinge
#: axis, a double root): its rate's denominator B cos theta - A sin theta = -+sqrt(K_i)
#: vanishes there.  K_i carries an absolute rounding of a few eps (l_i1 + l_i2)^2 (A, B, C
#: from the rounded joint positions), so the rate keeps a relative error of about
#: 0.05 eps (l_i1 + l_i2)^2 / K_i (measured against 50-digit mpmath: 7e-6 at K_i =
#: 2.6e-10 (l_i1 + l_i2)^2): outside the band <= 2e-11.  The row is flagged "singular" and
#: the leg's rate is #DIV/0! (its denominator is made 0).
EDGE_FRACTION = 1e-3


def _at_edge(i: int) -> Node:
    return le(_v(f"K_{i}"), (EDGE_FRACTION * (_p(f"l_{i}1") + _p(f"l_{i}2"))) ** 2)


def leg_quantities(i: int, sign: int) -> list[Quantity]:
    """Leg i: its platform joint, A, B, C, theta_i1 and its rate, O_i2."""
    P = _vv("", f"P{i}")
    vP = _vv("v", f"P{i}")
    d = sub(P, _hinge(i))
    A, B, C = _v(f"A_{i}"), _v(f"B_{i}"), _v(f"C_{i}")
    l1, l2 = _p(f"l_{i}1"), _p(f"l_{i}2")
    a_i = vec(_p(f"a_{i}"), _p(f"b_{i}"), _p(f"c_{i}"))
    velocity = add(vec(_v("vx_P5"), ZERO, _v("vz_P5")),
                   cross(vec(_v("w_x"), _v("w_y"), _v("w_z")), sub(P, P5)))
    K = _v(f"K_{i}")
    reach = atan2(C, root(K))
    th = radians(_v(f"theta_{i}1"))
    c, s = cos(th), sin(th)
    rate_a, rate_b, rate_c = vP[2], dot(vP, _h(i)), dot(d, vP) / l1
    o2 = add(_hinge(i), combine((l1, _frame(i)[0])))
    Qn = Quantity
    return [
        *_columns(_xyz(f"P{i}"), "m", _on_platform(a_i), f"spherical joint P{i}", output=True),
        *_columns(_xyz(f"P{i}", "v"), "m/s", velocity, f"velocity of P{i}"),
        Qn(f"A_{i}", "m", d[2], f"leg {i}: A = (P{i} - O_{i}1).e_z", output=False),
        Qn(f"B_{i}", "m", dot(d, _h(i)), f"leg {i}: B = (P{i} - O_{i}1).(sin gamma, -cos gamma, 0)",
           output=False),
        Qn(f"C_{i}", "m", (dot(d, d) + l1 ** 2 - l2 ** 2) / (2 * l1),
           f"leg {i}: C = (|P{i} - O_{i}1|^2 + l_{i}1^2 - l_{i}2^2) / (2 l_{i}1)", output=False),
        Qn(f"K_{i}", "m^2", A ** 2 + B ** 2 - C ** 2,
           f"leg {i}: A^2 + B^2 - C^2, the reach discriminant (< 0 out of reach, 0 at the "
           f"edge)", output=False),
        Qn(f"theta_{i}1", "deg",
           degrees(atan2(A, B) + reach if sign > 0 else atan2(A, B) - reach),
           f"leg {i}: drive angle of link {i}1 from z (branch {'+' if sign > 0 else '-'})"),
        Qn(f"omega_{i}1", "rad/s",
           (rate_c - rate_a * c - rate_b * s) / if_(_at_edge(i), 0, B * c - A * s),
           f"leg {i}: drive rate (#DIV/0! at the edge of the leg's reach, status "
           f"'singular')"),
        *_columns(_xyz(f"O{i}2"), "m", o2, f"leg {i}: universal joint O_{i}2"),
    ]


def _mass_points(balance: bool) -> list[tuple[str, Node, Vec3, str]]:
    """(column stem, mass, position trees, what) of every mass of the mechanism."""
    points = []
    for i in LEGS:
        l2 = _p(f"l_{i}2")
        o2, P = _vv("", f"O{i}2"), _vv("", f"P{i}")
        points += [
            (f"S{i}1", _p(f"m_{i}1"), _on_link_i1(i, _p(f"u_{i}1"), _p(f"v_{i}1"),
                                                  _p(f"w_{i}1")), f"link {i}1's centre of mass"),
            (f"S{i}2", _p(f"m_{i}2"), add(o2, combine((_p(f"xi_{i}") / l2, sub(P, o2)))),
             f"link {i}2's centre of mass"),
        ]
        if balance:
            points.append((f"Sc{i}", _p(f"m_c{i}"),
                           _on_link_i1(i, _p(f"u_c{i}"), _p(f"v_c{i}")),
                           f"counterweight on link {i}1"))
    e_alpha = vec(cos(radians(_v("alpha"))), ZERO, sin(radians(_v("alpha"))))
    points += [("SP", _p("m_P"), _on_platform(vec(_p("u_P"), _p("v_P"), _p("w_P"))),
                "platform's centre of mass"),
               ("S5", _p("m_5"), combine((_p("l_5c"), e_alpha)), "leg 5's centre of mass")]
    if balance:
        points += [("ScP", _p("m_cP"), _on_platform(vec(_p("u_cP"), _p("v_cP"), _p("w_cP"))),
                    "counterweight on the platform"),
                   ("Sc5", _p("m_c5"), combine((_p("s_c5"), e_alpha)),
                    "counterweight on leg 5")]
    return points


def mass_quantities(balance: bool) -> list[Quantity]:
    out, moments = [], [[], [], []]
    points = _mass_points(balance)
    for stem, m, position, what in points:
        for k, (axis, tree) in enumerate(zip("xyz", position)):
            if tree == ZERO:          # leg 5 stays in the plane y = 0
                continue
            out.append(Quantity(f"{axis}_{stem}", "m", tree, f"{what}, {axis}", output=False))
            moments[k].append(m * Var(f"{axis}_{stem}"))
    mass = total([m for _, m, _, _ in points])
    for k, axis in enumerate("xyz"):
        out.append(Quantity(f"{axis}_S", "m", total(moments[k]) / mass,
                            f"total centre of mass, {axis}"))
    return out


def quantities(branch: str = "++++", balance: bool = False) -> tuple[Quantity, ...]:
    legs = [q for i, s in zip(LEGS, branch) for q in leg_quantities(i, 1 if s == "+" else -1)]
    return tuple(pose_quantities() + legs + mass_quantities(balance))


def checks() -> tuple[Check, ...]:
    out = []
    for i in LEGS:
        l1, l2, om = _p(f"l_{i}1"), _p(f"l_{i}2"), _v(f"omega_{i}1")
        xi, eta, _ = _frame(i)      # O_i2 rebuilt from theta_i1: the check needs no O_i2
        link = sub(_vv("", f"P{i}"), add(_hinge(i), combine((l1, xi))))
        vP = _vv("v", f"P{i}")
        rate = dot(link, sub(vP, combine((l1 * om, eta))))
        size = l2 * (abs_(vP[0]) + abs_(vP[1]) + abs_(vP[2]) + l1 * abs_(om))
        out += [
            Check(f"leg{i}_closure", "position", (norm(link) - l2) / l2,
                  f"leg {i}: (|P{i} - O_{i}1 - l_{i}1 xi_{i}1(theta_{i}1)| - l_{i}2) / l_{i}2"),
            Check(f"leg{i}_closure_rate", "velocity", if_(eq(size, 0), 0, rate / size),
                  f"leg {i}: (P{i} - O_{i}2).(v_P{i} - l_{i}1 omega_{i}1 eta_{i}1), over "
                  f"l_{i}2 (|v_P{i}|_1 + l_{i}1 |omega_{i}1|)"),
        ]
    return tuple(out)




def status_for(keep: frozenset[str]) -> Node:
    """'cannot assemble' where a kept leg's drive angle is an error (out of reach),
    'singular' where a kept leg is at the edge of its reach, else 'ok'."""
    legs = [i for i in LEGS if f"theta_{i}1" in keep]
    if not legs:
        return wrap("ok")
    edge = [_at_edge(i) for i in legs]
    return if_(or_(*[iserror(_v(f"theta_{i}1")) for i in legs]), "cannot assemble",
               if_(or_(*edge), "singular", "ok"))


def charts() -> tuple[Chart, ...]:
    drives = tuple(f"theta_{i}1" for i in LEGS)
    rates = tuple(f"omega_{i}1" for i in LEGS)
    return (
        Chart("Drive angles", "t", drives, "theta_i1 [deg]"),
        Chart("Total centre of mass", "t", ("x_S", "y_S", "z_S"), "x_S, y_S, z_S [m]"),
        Chart("Drive rates", "t", rates, "omega_i1 [rad/s]"),
        Chart("Platform pose", "t", ("alpha", "psi", "vartheta", "phi"), "angle [deg]"),
        *(Chart(f"Path of P{i}", f"x_P{i}", (f"y_P{i}",), f"y_P{i} [m]", path=True)
          for i in LEGS),
    )


def _configure(template: Template, options: Mapping[str, object]) -> Template:
    branch, balance = str(options["branch"]), bool(options["balance"])
    conditions = balancing.conditions(balance)
    extra = counterweight_parameters() if balance else ()
    return dataclasses.replace(
        template, parameters=parameters() + extra,
        derived=balancing.counterweights() if balance else (),
        quantities=quantities(branch, balance), conditions=conditions,
        figures=balancing.condition_figures(conditions))


def _validate(p: Mapping[str, float]) -> tuple[str, str] | None:
    masses = [k for k in p if k.startswith("m_")]
    for name in masses:
        if p[name] < 0:
            return name, "must be >= 0"
    if sum(p[k] for k in masses) <= 0:
        return "m_P", "the masses must not all be zero"
    return None


def _why_not(p: Mapping[str, float]) -> str:
    return ("a platform joint P_i is farther from its hinge O_i1 than l_i1 + l_i2, or nearer "
            "than |l_i1 - l_i2|, at every pose of the path (check the leg lengths, the "
            "platform coordinates a_i, b_i, c_i and l_5)")


_BASE = Template(
    id="parallel_4dof",
    title="Spatial 4-DOF parallel mechanism: inverse kinematics and shaking-force balance",
    description="Four driven R-U-S legs and an undriven leg 5 carry a platform along a path "
                "of poses; drive angles and rates in closed form, centres of mass, the total "
                "centre of mass, the 12 balancing conditions; balance = true adds "
                "counterweights that keep the centre of mass still.",
    input=InputSpec("t", "deg", "path parameter (alpha, psi, vartheta, phi follow it)"),
    parameters=parameters(),
    quantities=quantities(),
    status=status_for(frozenset(f"theta_{i}1" for i in LEGS)),
    checks=checks(),
    charts=charts(),
    spans=(Span("total centre of mass, x spread", "x_S"),
           Span("total centre of mass, y spread", "y_S"),
           Span("total centre of mass, z spread", "z_S")),
    options=(OptionSpec("branch", "++++", "assembly of legs 1..4, one sign each: + gives "
                        "theta_i1 = ATAN2(A, B) + ACOS(C / sqrt(A^2 + B^2)), - the other root",
                        choices=BRANCHES),
             OptionSpec("balance", False, "counterweights of masses m_c1..m_c4, m_cP, m_c5 at "
                        "the positions the 12 balancing conditions require")),
    length_unit_m=1.0,
    configure=_configure,
    validate=_validate,
    status_for=status_for,
    assembly_failure=_why_not,
)

TEMPLATE = _configure(_BASE, _BASE.option_defaults)
