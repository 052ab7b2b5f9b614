"""The four-bar's summary figures worked out independently of the trees, for the
batching tests: each output's extremes over the rows the 50-digit reference
(tests/mp_reference.py) solves, with where they occur, Norton's Grashof class and the
crank-rocker's time ratio from the law of cosines (Norton, Design of Machinery, ch. 2-3)."""

from __future__ import annotations

import math

import mp_reference

NORTON = {"l_O1O2": 100.0, "l_O1A": 40.0, "l_AB": 120.0, "l_O2B": 80.0, "l_AC": 60.0,
          "delta_C": 30.0, "omega_2": 10.0}


def extremes(params, inputs, names=("x_C", "y_C", "omega_4")):
    """{name: (lo, lo_at, hi, hi_at)} over the rows that assemble (and are not singular),
    the first row holding each extreme; and how many rows do not assemble."""
    ref, singular = mp_reference.solve("four_bar", params, inputs, {"branch": "open"})
    out = {}
    for name in names:
        rows = [i for i, v in enumerate(ref[name]) if v is not None and not singular[i]]
        vals = [float(ref[name][i]) for i in rows]
        lo, hi = min(vals), max(vals)
        out[name] = (lo, inputs[rows[vals.index(lo)]], hi, inputs[rows[vals.index(hi)]])
    missing = sum(v is None for v in ref["theta_3"])
    return out, missing


def grashof_class(p) -> str:
    links = [p["l_O1O2"], p["l_O1A"], p["l_AB"], p["l_O2B"]]
    s, l = min(links), max(links)
    excess = s + l - (sum(links) - s - l)
    if abs(excess) <= 1e-12 * sum(links):
        return "change point"
    if excess > 0:
        return "non-Grashof triple-rocker"
    if p["l_AB"] == s:
        return "Grashof double-rocker"
    if p["l_O1O2"] == s:
        return "Grashof double-crank"
    return "Grashof crank-rocker"


def time_ratio(p) -> float:
    """Crank-rocker: the crank turns 180 + d one way between the toggles and 180 - d
    back, d the angle between O1B at the extended (a + b) and folded (b - a) toggles."""
    g, a, b, c = p["l_O1O2"], p["l_O1A"], p["l_AB"], p["l_O2B"]
    ext = math.degrees(math.acos((g * g + (a + b) ** 2 - c * c) / (2 * g * (a + b))))
    fold = math.degrees(math.acos((g * g + (b - a) ** 2 - c * c) / (2 * g * (b - a))))
    d = abs(fold - ext)
    return (180 + d) / (180 - d)


def close(a: float, b: float, scale: float = 1.0, rel: float = 1e-11) -> bool:
    return abs(a - b) <= rel * max(abs(b), scale)
