"""Centres of mass, shaking force and shaking moment of any template
(docs/mechanisms.md, Shaking force and balance).

Each link with a mass gets three parameters, ``m_<link>`` (kg) and ``u_<link>``,
``v_<link>`` (the template's length unit): the centre of mass S lies at u along
the link from its first joint and v to the left of it.  With the link's frame
e = (cos angle, sin angle), n = (-sin angle, cos angle) and r = u e + v n:

    S = joint + r,     a_S = a_joint + alpha (-r_y, r_x) - omega^2 r.

Sign conventions (point masses, no rotary inertia of the links):

* shaking force ``F = -sum m_i a_Si`` (N): the resultant of the links' inertia
  forces, i.e. the force the moving mechanism exerts on its frame;
* shaking moment ``M_S = -sum m_i (x_Si a_ySi - y_Si a_xSi)`` (N*m): the moment of
  those inertia forces about the origin (the crank pivot), counter-clockwise positive.

Lengths are converted to metres with the template's ``length_unit_m``.  The
total centre of mass is ``S = sum m_i S_i / sum m_i`` and its acceleration
``a_S = sum m_i a_Si / sum m_i``; a check row verifies ``sum m_i a_S + F = 0``.
For the four-bar, ``[options] balance = true`` adds counterweights (balance.py)
that enter these sums like any other mass.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Mapping

from ..errors import SceneError
from ..expr import Neg, Node, Num, Param, Var, abs_, cos, eq, if_, sin, sqrt, wrap
from .balance import counterweights
from .base import (Chart, Check, Derived, Figure, Link, Mass, ParamSpec, PointMass, Quantity, Span,
                   Template)


def point_trees(link: Link, u: Node, v: Node) -> tuple[Node, Node, Node, Node]:
    """Position and acceleration of the point (u, v) of ``link``: the one builder."""
    c, s = cos(link.angle), sin(link.angle)
    rx, ry = _add(u * c, -(v * s)), _add(u * s, v * c)
    w2 = None if _zero(link.omega) else wrap(link.omega) ** 2
    ax, ay = wrap(link.joint_acc[0]), wrap(link.joint_acc[1])
    if not _zero(link.alpha):
        ax, ay = _add(ax, -(wrap(link.alpha) * ry)), _add(ay, wrap(link.alpha) * rx)
    if w2 is not None:
        ax, ay = _add(ax, -(w2 * rx)), _add(ay, -(w2 * ry))
    return _add(link.joint[0], rx), _add(link.joint[1], ry), ax, ay


def _zero(node: object) -> bool:
    return wrap(node) == Num(0.0)


def _add(a: object, b: Node) -> Node:
    """a + b, dropping a literal zero; a + (-x) is written a - x."""
    if _zero(a):
        return b
    if isinstance(b, Neg):
        return wrap(a) - b.operand
    return wrap(a) + b


def _sum(terms: list[Node]) -> Node:
    total = terms[0]
    for term in terms[1:]:
        total = total + term
    return total


def _mass_params(template: Template, masses: Mapping[str, Mass]) -> tuple[ParamSpec, ...]:
    unit = _length_unit(template)
    specs = []
    for link in template.links:
        if link.name in masses:
            mass = masses[link.name]
            specs += [
                ParamSpec(f"m_{link.name}", mass.m, "kg", f"mass of the {link.name}"),
                ParamSpec(f"u_{link.name}", mass.u, unit,
                          f"{link.name}'s centre of mass: along the link from its first joint"),
                ParamSpec(f"v_{link.name}", mass.v, unit,
                          f"{link.name}'s centre of mass: to the left of the link"),
            ]
    return tuple(specs)


def _length_unit(template: Template) -> str:
    return {1e-3: "mm", 1.0: "m"}.get(template.length_unit_m, "")


def _point_quantities(points: list[PointMass], unit: str) -> list[Quantity]:
    out = []
    for p in points:
        x, y, ax, ay = point_trees(p.link, p.u, p.v)
        out += [
            Quantity(f"x_S_{p.label}", unit, x, f"centre of mass of the {p.description}, x"),
            Quantity(f"y_S_{p.label}", unit, y, f"centre of mass of the {p.description}, y"),
            Quantity(f"ax_S_{p.label}", f"{unit}/s^2", ax,
                     f"centre of mass of the {p.description}, x acceleration"),
            Quantity(f"ay_S_{p.label}", f"{unit}/s^2", ay,
                     f"centre of mass of the {p.description}, y acceleration"),
        ]
    return out


def _total_quantities(points: list[PointMass], unit: str, metres: float) -> list[Quantity]:
    def moment(prefix: str) -> Node:   # sum m_i * <prefix>_S_i
        return _sum([p.m * Var(f"{prefix}_S_{p.label}") for p in points])

    total = _sum([p.m for p in points])
    moment_s = _sum([p.m * (Var(f"x_S_{p.label}") * Var(f"ay_S_{p.label}")
                            - Var(f"y_S_{p.label}") * Var(f"ax_S_{p.label}")) for p in points])
    f_x, f_y = Var("F_x"), Var("F_y")
    return [
        Quantity("x_S", unit, moment("x") / total, "total centre of mass, x"),
        Quantity("y_S", unit, moment("y") / total, "total centre of mass, y"),
        Quantity("ax_S", f"{unit}/s^2", moment("ax") / total,
                 "total centre of mass, x acceleration"),
        Quantity("ay_S", f"{unit}/s^2", moment("ay") / total,
                 "total centre of mass, y acceleration"),
        Quantity("F_x", "N", -moment("ax") * metres,
                 "shaking force on the frame, x: -sum m_i a_Si"),
        Quantity("F_y", "N", -moment("ay") * metres,
                 "shaking force on the frame, y: -sum m_i a_Si"),
        Quantity("F_abs", "N", sqrt(f_x ** 2 + f_y ** 2), "magnitude of the shaking force"),
        Quantity("M_S", "N*m", -moment_s * metres ** 2,
                 "shaking moment about the origin (inertia forces of point masses), "
                 "counter-clockwise"),
    ]


def _check(points: list[PointMass], metres: float) -> Check:
    """sum m_i a_S + F = 0, over the sum of |m_i a_Si| (0 where nothing accelerates)."""
    total = _sum([p.m for p in points])
    scale = _sum([p.m * (abs_(Var(f"ax_S_{p.label}")) + abs_(Var(f"ay_S_{p.label}")))
                  for p in points]) * metres
    residual = (abs_(total * Var("ax_S") * metres + Var("F_x"))
                + abs_(total * Var("ay_S") * metres + Var("F_y")))
    return Check("shaking_force", "acceleration", if_(eq(scale, 0), 0, residual / scale),
                 "total mass times the total centre of mass's acceleration plus F, "
                 "over sum m_i |a_Si|")


def _validate(template: Template, labels: list[str]):
    earlier = template.validate

    def validate(p: Mapping[str, float]) -> tuple[str, str] | None:
        for label in labels:
            if p[f"m_{label}"] < 0:
                return (f"m_{label}", "must be >= 0")
        if labels and sum(p[f"m_{label}"] for label in labels) <= 0:
            return (f"m_{labels[0]}", "the masses must not all be zero")
        return earlier(p)
    return validate


def add_dynamics(template: Template, masses: Mapping[str, Mass],
                 options: Mapping[str, object]) -> Template:
    """``template`` with mass parameters, centre-of-mass columns, shaking force and moment
    for the links named in ``masses`` (and the counterweights of ``balance = true``)."""
    if not template.links:
        raise SceneError(f"{template.id}: declares no moving links for [masses]")
    unit, metres = _length_unit(template), template.length_unit_m
    params = _mass_params(template, masses)
    points = [PointMass(link.name, link, Param(f"m_{link.name}"), Param(f"u_{link.name}"),
                        Param(f"v_{link.name}"), link.name)
              for link in template.links if link.name in masses]
    derived: tuple[Derived, ...] = ()
    if options.get("balance"):
        extra_params, extra_points, derived = counterweights(template, masses)
        params += extra_params
        points += extra_points
    quantities = _point_quantities(points, unit) + _total_quantities(points, unit, metres)
    input_name = template.input.name
    return dataclasses.replace(
        template,
        parameters=template.parameters + params,
        derived=template.derived + derived,
        quantities=template.quantities + tuple(quantities),
        checks=template.checks + (_check(points, metres),),
        charts=template.charts + (
            Chart("Shaking force", input_name, ("F_x", "F_y"), "F [N]"),
            Chart("Shaking force polar", "F_x", ("F_y",), "F_y [N]", path=True),
            Chart("Shaking moment", input_name, ("M_S",), "M_S [N*m]"),
            Chart("Path of the total centre of mass", "x_S", ("y_S",), f"y_S [{unit}]",
                  path=True),
        ),
        spans=template.spans + (Span("shaking force x, range", "F_x"),
                                Span("shaking force y, range", "F_y"),
                                Span("shaking moment, range", "M_S")),
        figures=template.figures + (
            Figure("total moving mass", "kg", _sum([p.m for p in points]),
                   "sum of the link masses (and counterweights)"),),
        validate=_validate(template, [link.name for link in template.links
                                      if link.name in masses]),
    )
