"""parallel_4dof_balance: the counterweights the module's trees place (evaluated at 50
digits) make the total centre of mass stand still over the motion, as the 50-digit model
of tests/mp_parallel_4dof.py computes it from every mass's position; the 12 residuals."""

from __future__ import annotations

import mpmath
import pytest

from tests import mp_parallel_4dof as mp4
from workbook_gen.expr.precise import compile_mpmath
from workbook_gen.mechanisms.parallel_4dof_balance import (condition_figures, conditions,
                                                           counterweights, mu)
from workbook_gen.mechanisms.parallel_4dof_params import counterweight_parameters, parameters

SIGNS = {i: 1 for i in mp4.LEGS}
TS = [mpmath.radians(t) for t in (0, 50, 130, 220, 310)]


def _defaults():
    return {p.name: mpmath.mpf(p.default)
            for p in parameters() + counterweight_parameters()}


def _ev(node, params):
    with mpmath.workdps(50):
        return compile_mpmath(node)({}, params)


@pytest.fixture(scope="module")
def balanced():
    c = _defaults()
    for d in counterweights():  # each uses the parameters only
        c[d.name] = _ev(d.expr, c)
    return c


def _com(c, t, balance):
    with mpmath.workdps(50):
        row, _ = mp4._positions(c, t, SIGNS, balance)
    return [row[f"{a}_S"] for a in "xyz"]


def test_counterweights_hold_the_centre_of_mass_still(balanced):
    coms = [_com(balanced, t, True) for t in TS]
    assert all(v is not None for com in coms for v in com)
    for com in coms[1:]:
        assert max(abs(a - b) for a, b in zip(com, coms[0])) < mpmath.mpf(10) ** -40


def test_without_counterweights_it_moves():
    c = _defaults()
    coms = [_com(c, t, False) for t in TS]
    spread = max(abs(com[k] - coms[0][k]) for com in coms for k in range(3))
    assert spread > 1e-3


def test_one_counterweight_off_its_place_moves_it_again(balanced):
    for name in ("u_c2", "v_c3", "w_cP", "s_c5"):
        c = dict(balanced, **{name: balanced[name] + mpmath.mpf("0.01")})
        coms = [_com(c, t, True) for t in TS]
        assert max(abs(com[k] - coms[0][k]) for com in coms for k in range(3)) > 1e-6, name


def test_the_twelve_residuals_vanish_balanced_and_match_the_hand_sums(balanced):
    held = conditions(balance=True)
    assert len(held) == 12 and len({c.name for c in held}) == 12
    for cond in held:
        scale = _ev(cond.scale, balanced)
        assert scale >= 0 and abs(_ev(cond.expr, balanced)) <= mpmath.mpf(10) ** -45 * scale
    c = _defaults()
    free = {cond.name: _ev(cond.expr, c) for cond in conditions(balance=False)}
    # by hand, from the parameters' definitions (module docstring)
    m12 = c["m_12"] * c["l_11"] * (c["l_12"] - c["xi_1"]) / c["l_12"]
    assert free["leg1_xi"] == pytest.approx(float(c["m_11"] * c["u_11"] + m12), rel=1e-14, abs=0)
    assert free["leg2_eta"] == pytest.approx(float(c["m_21"] * c["v_21"]), rel=1e-14, abs=0)
    mus = {i: c[f"m_{i}2"] * c[f"xi_{i}"] / c[f"l_{i}2"] for i in mp4.LEGS}
    assert _ev(mu(3), c) == pytest.approx(float(mus[3]), rel=1e-15, abs=0)
    plat_z = c["m_P"] * (c["w_P"] - c["c_5"]) + sum(mus[i] * (c[f"c_{i}"] - c["c_5"])
                                                     for i in mp4.LEGS)
    assert free["platform_z"] == pytest.approx(float(plat_z), rel=1e-13, abs=0)
    leg5 = c["m_5"] * c["l_5c"] + c["l_5"] * (c["m_P"] + sum(mus.values()))
    assert free["leg5"] == pytest.approx(float(leg5), rel=1e-14, abs=0)


def test_figures_one_per_condition():
    conds = conditions(False)
    figs = condition_figures(conds)
    assert [f.label for f in figs] == [f"balancing condition {c.name}" for c in conds]
    assert all(f.unit == "kg*m" and f.needs == ("x_S", "y_S", "z_S") for f in figs)
