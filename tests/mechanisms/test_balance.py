"""mechanisms/balance.py: the counterweights of a four-bar's full shaking-force balance.

Reference: the definition of full force balance (Berkof and Lowen, 1969): the total centre
of mass of the links and counterweights stands still over the motion. The counterweights'
derived values are evaluated at 50 digits (expr/precise.py); the linkage is then moved
through a full turn by tests/mp_reference.py's independent four-bar solution (theta_3,
theta_4 at 50 digits) and the total mass moment sum m_i r_i is summed here, link by link,
from each link's frame (crank from O1 along O1->A, coupler from A along A->B, rocker from
O2 along O2->B, v to the left): constant with the counterweights, varying without."""

from __future__ import annotations

import random

import mpmath
import pytest

from workbook_gen.errors import SceneError
from workbook_gen.expr.precise import compile_mpmath
from workbook_gen.mechanisms import TEMPLATES
from workbook_gen.mechanisms.balance import counterweights, required_moments
from workbook_gen.mechanisms.base import Mass

import mp_reference as ref

NORTON = {"crank": Mass(0.04, 20.0, 0.0), "coupler": Mass(0.12, 60.0, 8.0),
          "rocker": Mass(0.08, 40.0, 0.0)}       # templates/four_bar_balanced.toml
RNG = random.Random(1969)


def balanced(masses, radii=None):
    """The parameters (defaults, masses, radii) with the counterweights' derived values."""
    template = TEMPLATES["four_bar"]
    specs, points, derived = counterweights(template, masses)
    params = {p.name: p.default for p in template.parameters}
    for link, m in masses.items():
        params |= {f"m_{link}": m.m, f"u_{link}": m.u, f"v_{link}": m.v}
    params |= {s.name: s.default for s in specs} | (radii or {})
    for d in derived:                         # in order: each may use the ones before
        params[d.name] = compile_mpmath(d.expr)({}, params)
    return params, points


def moment(params, masses, theta, counterweighted=True):
    """sum m_i (x_i, y_i) of the links' and counterweights' masses at crank angle theta."""
    state, _ = ref.four_bar(params, theta)
    g, a = mpmath.mpf(params["l_O1O2"]), mpmath.mpf(params["l_O1A"])
    t = mpmath.radians(theta)
    th3, th4 = mpmath.radians(state["theta_3"]), mpmath.radians(state["theta_4"])
    ax, ay = a * mpmath.cos(t), a * mpmath.sin(t)
    frames = {"crank": ((0, 0), t), "coupler": ((ax, ay), th3), "rocker": ((g, 0), th4)}
    bodies = [(link, m.m, m.u, m.v) for link, m in masses.items()]
    if counterweighted:
        bodies += [(link, params[f"m_cw_{link}"], params[f"u_cw_{link}"],
                    params[f"v_cw_{link}"]) for link in ("crank", "rocker")]
    mx = my = mpmath.mpf(0)
    for link, m, u, v in bodies:
        (ox, oy), ang = frames[link]
        c, s = mpmath.cos(ang), mpmath.sin(ang)
        mx += m * (ox + u * c - v * s)
        my += m * (oy + u * s + v * c)
    return mx, my


def spread(params, masses, counterweighted=True):
    ms = [moment(params, masses, th, counterweighted) for th in range(0, 360, 15)]
    return max(max(abs(x - ms[0][0]), abs(y - ms[0][1])) for x, y in ms)


def test_the_templates_counterweights_hold_the_centre_of_mass_still():
    with mpmath.workdps(50):
        params, points = balanced(NORTON)
        assert spread(params, NORTON) < mpmath.mpf(10) ** -40
        assert spread(params, NORTON, counterweighted=False) > 1.0   # they are needed
        assert [p.label for p in points] == ["cw_crank", "cw_rocker"]


@pytest.mark.parametrize("seed", range(4))
def test_random_masses_and_radii(seed):
    rng = random.Random(seed)
    masses = {link: Mass(rng.uniform(0.01, 1), rng.uniform(-50, 150), rng.uniform(-20, 20))
              for link in ("crank", "coupler", "rocker")}
    radii = {"r_cw_crank": rng.uniform(5, 80), "r_cw_rocker": rng.uniform(5, 80)}
    with mpmath.workdps(50):
        params, _ = balanced(masses, radii)
        assert spread(params, masses) < mpmath.mpf(10) ** -38
        for link in ("crank", "rocker"):
            m, r = params[f"m_cw_{link}"], radii[f"r_cw_{link}"]
            phi = mpmath.radians(params[f"phi_cw_{link}"])
            # mass x radius = |W|; the angle places it: (u, v) = r (cos phi, sin phi)
            assert abs(m * r - mpmath.hypot(params[f"mx_cw_{link}"],
                                           params[f"my_cw_{link}"])) < 1e-40
            assert abs(params[f"u_cw_{link}"] - r * mpmath.cos(phi)) < 1e-40
            assert abs(params[f"v_cw_{link}"] - r * mpmath.sin(phi)) < 1e-40


def test_a_link_without_mass_counts_as_massless():
    masses = {"coupler": NORTON["coupler"]}
    with mpmath.workdps(50):
        params, _ = balanced(masses)
        assert spread(params, masses) < mpmath.mpf(10) ** -40
    nodes = required_moments({})
    with mpmath.workdps(50):
        values = [compile_mpmath(n)({}, {"l_O1A": 1, "l_AB": 2, "l_O2B": 3})
                  for pair in nodes.values() for n in pair]
    assert all(v == 0 for v in values)


def test_balanced_links_need_no_counterweight():
    """Each link's mass already at its pivot's side as the formula asks: W = 0, mass 0, the
    angle 0 and the counterweight at (r, 0) (no division by zero)."""
    # crank: m2 u2 = -m3 a (1 - 60/120) = -0.12*40/2 = -2.4 (0.06 * -40);
    # rocker: m4 u4 = -m3 c 60/120 = -0.12*80/2 = -4.8 (0.12 * -40)
    masses = {"crank": Mass(0.06, -40.0, 0.0), "coupler": Mass(0.12, 60.0, 0.0),
              "rocker": Mass(0.12, -40.0, 0.0)}
    with mpmath.workdps(50):
        params, _ = balanced(masses)
    for link in ("crank", "rocker"):
        assert abs(params[f"m_cw_{link}"]) < 1e-45
        assert params[f"phi_cw_{link}"] == 0 and params[f"v_cw_{link}"] == 0
        assert params[f"u_cw_{link}"] == params[f"r_cw_{link}"]


def test_a_mechanism_without_a_four_bars_links_is_refused():
    with pytest.raises(SceneError, match="balance = true needs a four-bar"):
        counterweights(TEMPLATES["slider_crank"], {})
