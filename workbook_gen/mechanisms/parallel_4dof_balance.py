"""Shaking-force balance of the 4-DOF parallel mechanism (docs/mechanisms.md, parallel_4dof): the 12
conditions and the counterweights that satisfy them.

The paper's method (redundant generalized coordinates): write the total mass moment
sum m_k r_k as linear in functions of the coordinates that vary independently over the
motion, here cos and sin of each theta_i1, cos and sin of alpha and the nine entries of Q.
With O_i2 = O_i1 + l_i1 xi_i1 and link i2's centre of mass at O_i2 + (xi_i / l_i2)(P_i - O_i2),
link i2's mass is shared between O_i2 (factor (l_i2 - xi_i)/l_i2) and P_i (factor
mu_i = m_i2 xi_i / l_i2).  Collecting terms:

* cos/sin theta_i1 (through xi_i1 and eta_i1, each leg):
  m_i1 u_i1 + m_i2 l_i1 (l_i2 - xi_i)/l_i2 = 0  and  m_i1 v_i1 = 0  (8 conditions);
* Q (through P_i = P5 + Q (a_i - a5) and the platform's centre of mass P5 + Q (c_P - a5)):
  m_P (c_P - a5) + sum mu_i (a_i - a5) = 0  (3 conditions, c_P = (u_P, v_P, w_P));
* cos/sin alpha (through P5 = l_5 e(alpha) and leg 5's centre of mass l_5c e(alpha)):
  m_5 l_5c + l_5 (m_P + sum mu_i) = 0  (1 condition).

The w_i1 terms multiply the fixed hinge axis and the O_i1 terms are constant: they move
the centre of mass but never make it move.  With ``balance = true`` a counterweight of
given mass on each link i1 (at u_ci, v_ci in its frame), on the platform (at platform
coordinates u_cP, v_cP, w_cP) and on leg 5 (at s_c5 from O along it) enters these sums;
its position is the solution of its condition(s), a live formula on the Parameters sheet.
"""

from __future__ import annotations

from ..expr import Node, Param, abs_
from ..expr.vec import total
from .base import Condition, Derived, Figure
from .parallel_4dof_params import LEGS

COM = ("x_S", "y_S", "z_S")  # the conditions are shown with the total centre of mass
AXES = (("a", "u", "x"), ("b", "v", "y"), ("c", "w", "z"))


def _p(name: str) -> Param:
    return Param(name)


def mu(i: int) -> Node:
    """The share of link i2's mass carried at the platform joint P_i."""
    return _p(f"m_{i}2") * _p(f"xi_{i}") / _p(f"l_{i}2")


def _leg_terms(i: int, balance: bool) -> tuple[list[Node], list[Node]]:
    """The terms of leg i's two conditions (along xi_i1 and along eta_i1)."""
    along = [_p(f"m_{i}1") * _p(f"u_{i}1"),
             _p(f"m_{i}2") * _p(f"l_{i}1") * (_p(f"l_{i}2") - _p(f"xi_{i}")) / _p(f"l_{i}2")]
    across = [_p(f"m_{i}1") * _p(f"v_{i}1")]
    if balance:
        along.append(_p(f"m_c{i}") * _p(f"u_c{i}"))
        across.append(_p(f"m_c{i}") * _p(f"v_c{i}"))
    return along, across


def _platform_terms(axis: int, balance: bool) -> list[Node]:
    joint, com, _ = AXES[axis]
    origin = _p(f"{joint}_5")
    terms = [_p("m_P") * (_p(f"{com}_P") - origin)]
    terms += [mu(i) * (_p(f"{joint}_{i}") - origin) for i in LEGS]
    if balance:
        terms.append(_p("m_cP") * (_p(f"{com}_cP") - origin))
    return terms


def _leg5_terms(balance: bool) -> list[Node]:
    carried = [_p("m_P")] + [mu(i) for i in LEGS] + ([_p("m_cP")] if balance else [])
    terms = [_p("m_5") * _p("l_5c"), _p("l_5") * total(carried)]
    if balance:
        terms.append(_p("m_c5") * _p("s_c5"))
    return terms


def _condition(name: str, terms: list[Node], description: str) -> Condition:
    return Condition(name, "kg*m", total(terms), total([abs_(t) for t in terms]),
                     description, needs=COM)


def conditions(balance: bool) -> tuple[Condition, ...]:
    """The 12 balancing conditions' residuals (kg m), 0 when balanced."""
    out = []
    for i in LEGS:
        along, across = _leg_terms(i, balance)
        cw = f" + m_c{i} u_c{i}" if balance else ""
        out.append(_condition(f"leg{i}_xi", along,
                              f"leg {i}, along xi_{i}1: m_{i}1 u_{i}1 + m_{i}2 l_{i}1 "
                              f"(l_{i}2 - xi_{i})/l_{i}2{cw}"))
        cw = f" + m_c{i} v_c{i}" if balance else ""
        out.append(_condition(f"leg{i}_eta", across,
                              f"leg {i}, along eta_{i}1: m_{i}1 v_{i}1{cw}"))
    for axis, (joint, com, x) in enumerate(AXES):
        cw = f" + m_cP ({com}_cP - {joint}_5)" if balance else ""
        out.append(_condition(f"platform_{x}", _platform_terms(axis, balance),
                              f"platform, {joint}: m_P ({com}_P - {joint}_5) + sum mu_i "
                              f"({joint}_i - {joint}_5){cw}, mu_i = m_i2 xi_i / l_i2"))
    cw = " + m_c5 s_c5 + l_5 m_cP" if balance else ""
    out.append(_condition("leg5", _leg5_terms(balance),
                          f"leg 5: m_5 l_5c + l_5 (m_P + sum mu_i){cw}"))
    return tuple(out)


def condition_figures(items: tuple[Condition, ...]) -> tuple[Figure, ...]:
    """The conditions' residuals as Summary rows."""
    return tuple(Figure(f"balancing condition {c.name}", c.unit, c.expr,
                        f"residual, 0 when balanced: {c.description}", needs=c.needs)
                 for c in items)


def counterweights() -> tuple[Derived, ...]:
    """The counterweights' positions that satisfy the conditions, from their masses."""
    out = []
    for i in LEGS:
        along, across = _leg_terms(i, balance=False)
        out += [
            Derived(f"u_c{i}", "m", -total(along) / _p(f"m_c{i}"),
                    f"counterweight on link {i}1: position along xi_{i}1"),
            Derived(f"v_c{i}", "m", -total(across) / _p(f"m_c{i}"),
                    f"counterweight on link {i}1: position along eta_{i}1"),
        ]
    for axis, (joint, com, _) in enumerate(AXES):
        out.append(Derived(f"{com}_cP", "m",
                           _p(f"{joint}_5") - total(_platform_terms(axis, False)) / _p("m_cP"),
                           f"counterweight on the platform: platform coordinate {joint}"))
    carried = [_p("m_P"), _p("m_cP")] + [mu(i) for i in LEGS]
    out.append(Derived("s_c5", "m",
                       -(_p("m_5") * _p("l_5c") + _p("l_5") * total(carried)) / _p("m_c5"),
                       "counterweight on leg 5: position from O towards P5 (negative: beyond O)"))
    return tuple(out)
