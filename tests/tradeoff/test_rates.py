"""tradeoff/rates.py: the finite differences are the textbook schemes (checked on a sine,
within their truncation bounds), and each chain it lists is right: the tabulated
position, differenced over a fine sweep and scaled by ``time_factor`` and
``position_factor``, gives the velocity column, and the velocity the acceleration
(every template with chains, its default scene at a fine step)."""

from __future__ import annotations

import numpy as np
import pytest

from workbook_gen import compute, load_scene
from workbook_gen.tradeoff.rates import (CHAINS, chains_for, differences, position_factor,
                                         time_factor)


def test_the_schemes_within_their_truncation_error():
    for h in (0.1, 0.01, 0.001):
        x = np.arange(0, 6.3, h)
        y = np.sin(x)
        d1, d2 = differences(y, h, "central")
        inner = slice(1, -1)
        assert np.isnan(d1[0]) and np.isnan(d1[-1])
        # central: |error| <= h^2/6 max|y3| and h^2/12 max|y4|, plus rounding
        assert np.max(np.abs(d1[inner] - np.cos(x[inner]))) <= h * h / 6 + 1e-12 / h
        assert np.max(np.abs(d2[inner] + np.sin(x[inner]))) <= h * h / 12 + 1e-15 / h ** 2
        f1, f2 = differences(y, h, "forward")
        # forward: |error| <= h/2 max|y2|; the second one is central at x + h:
        # h max|y3| + h^2/12 max|y4| (yk: the k-th derivative)
        assert np.max(np.abs(f1[:-1] - np.cos(x[:-1]))) <= h / 2 + 1e-12 / h
        assert np.max(np.abs(f2[:-2] + np.sin(x[:-2]))) <= h + h * h / 12 + 1e-15 / h ** 2
    with pytest.raises(ValueError):
        differences(np.zeros(3), 1.0, "backward")


FINE = {"sewing_machine": 0.02, "slider_crank": 0.02, "four_bar": 0.02, "walking_beam": 0.02,
        "actuator_linkage": 0.00005}


def column(frame, name: str) -> np.ndarray:
    (key,) = [c for c in frame.columns if c.split(" [")[0] == name]
    return frame[key].to_numpy(dtype=float)


@pytest.mark.parametrize("template", sorted(CHAINS))
def test_each_chain_differentiates_to_its_rates(template):
    scene = load_scene(f"templates/{template}.toml", step=FINE[template])
    frame = compute(scene)
    t = scene.template
    names = tuple(q.name for q in t.quantities if q.output)
    rate, chains = chains_for(t, names)
    assert rate == CHAINS[template][0] and chains == CHAINS[template][1]
    h = scene.sweep.step
    ok = frame["status"].to_numpy() == "ok"
    for chain in chains:
        y = column(frame, chain.position)
        if t.quantity(chain.position).unit == "deg":
            y = np.unwrap(y, period=360.0)
        y = y * position_factor(t, chain.position)
        v, a = column(frame, chain.velocity), column(frame, chain.acceleration)
        d1, _ = differences(y, h, "central")
        d1 = d1 * time_factor(t, scene.parameters)
        dv, _ = differences(v, h, "central")
        dv = dv * time_factor(t, scene.parameters)
        rows = ok & np.roll(ok, 1) & np.roll(ok, -1) & np.isfinite(d1) & np.isfinite(dv)
        assert rows.sum() > 0.9 * len(rows) - 2, chain
        scale_v, scale_a = np.max(np.abs(v[rows])), np.max(np.abs(a[rows]))
        assert np.max(np.abs(d1[rows] - v[rows])) <= 1e-5 * scale_v, chain
        assert np.max(np.abs(dv[rows] - a[rows])) <= 1e-5 * scale_a, chain
