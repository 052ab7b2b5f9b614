"""parallel_4dof_params: the defaults describe a mechanism that assembles without a
singular leg over the whole path (tests/mp_parallel_4dof.py at 50 digits), each leg's
parameters are named by the leg, and only lengths and counterweight masses must be > 0."""

from __future__ import annotations

import mpmath
import pytest

from tests import mp_parallel_4dof as mp4
from workbook_gen.mechanisms import get_template
from workbook_gen.mechanisms.parallel_4dof_params import (LEG_DEFAULTS, LEGS,
                                                          counterweight_parameters, parameters)

PER_LEG = ("x_{i}0 y_{i}0 z_{i}0 gamma_{i} l_{i}1 l_{i}2 a_{i} b_{i} c_{i} m_{i}1 u_{i}1 "
           "v_{i}1 w_{i}1 m_{i}2 xi_{i}").split()


def test_names_units_and_counts():
    specs = parameters()
    names = [p.name for p in specs]
    assert len(names) == len(set(names)) == 16 + 4 * 15
    for i in LEGS:
        assert [n.format(i=i) for n in PER_LEG] == [n for n in names if _leg_of(n) == i]
    units = {p.name: p.unit for p in specs}
    assert {units[f"gamma_{i}"] for i in LEGS} == {"deg"}
    assert {units[f"m_{i}1"] for i in LEGS} | {units["m_P"], units["m_5"]} == {"kg"}
    positive = {p.name for p in specs if p.positive}
    assert positive == {"l_5"} | {f"l_{i}{k}" for i in LEGS for k in (1, 2)}
    cw = counterweight_parameters()
    assert [p.name for p in cw] == ["m_c1", "m_c2", "m_c3", "m_c4", "m_cP", "m_c5"]
    assert all(p.positive and p.unit == "kg" and p.default > 0 for p in cw)


def _leg_of(name):
    for i in LEGS:
        if name in {n.format(i=i) for n in PER_LEG}:
            return i
    return None


def test_the_template_takes_these_defaults():
    t = get_template("parallel_4dof")
    assert {p.name: p.default for p in parameters()}.items() <= t.defaults.items()
    o, gamma = LEG_DEFAULTS[3][:2]
    assert (t.defaults["x_30"], t.defaults["y_30"], t.defaults["gamma_3"]) == (o[0], o[1], gamma)


@pytest.mark.parametrize("t_deg", range(0, 360, 45))
def test_the_defaults_assemble_without_a_singular_leg(t_deg):
    p = {s.name: s.default for s in parameters()}
    with mpmath.workdps(30):
        row, singular = mp4.solve(p, t_deg)
    for i in LEGS:
        assert row[f"theta_{i}1"] is not None, (i, t_deg)
        assert row[f"omega_{i}1"] is not None, (i, t_deg)
    assert not singular


def test_the_layout_is_asymmetric():
    """A symmetric layout is singular at home (the module's note): the hinge axes' angles
    are not a multiple of 90 deg apart, and no two legs are mirror images."""
    gammas = [LEG_DEFAULTS[i][1] for i in LEGS]
    assert any((b - a) % 90 for a, b in zip(gammas, gammas[1:]))
    assert len({LEG_DEFAULTS[i][2] for i in LEGS}) > 1
