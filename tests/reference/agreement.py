"""Shared by tests/reference/test_<mechanism>.py: a mechanism's reference solver
(workbook_gen.reference, float64 batched Newton) against tests/mp_reference.py (the
closure equations in mpmath at 50 digits, a textbook construction polished by findroot;
nothing shared with workbook_gen): every output both give, on a sweep of inputs, within
``rel`` of the column's magnitude; angles modulo a whole turn; rows that cannot assemble
NaN in one and None in the other."""

from __future__ import annotations

import math

import numpy as np

import mp_reference
from workbook_gen import reference
from workbook_gen.mechanisms import get_template


def check(mechanism: str, inputs, params=None, options=None, rel: float = 1e-9) -> int:
    """Compare; return how many values were compared."""
    template = get_template(mechanism)
    p = {q.name: q.default for q in template.parameters} | dict(params or {})
    want, singular = mp_reference.solve(mechanism, p, list(inputs), options)
    got = reference.solve(mechanism, p, np.asarray(inputs, dtype=float), *(
        [options] if options else []))
    compared = 0
    for name, column in want.items():
        quantity = next((q for q in template.quantities if q.name == name), None)
        if name not in got or quantity is None:
            continue
        period = {"deg": 360.0, "rad": 2 * math.pi}.get(quantity.unit) \
            if name.startswith(("theta", "phi", "alpha_0", "psi", "gamma")) else None
        values = [float(v) for v in column if v is not None]
        scale = max([abs(v) for v in values] + [1e-300])
        for i, v in enumerate(column):
            g = float(got[name][i])
            if v is None:
                assert math.isnan(g), (name, inputs[i], g)
                continue
            if singular[i] and name.startswith(("v", "a", "omega", "alpha", "dx", "dy")):
                continue   # no rates at a singular row
            d = g - float(v)
            if period:
                d = (d + period / 2) % period - period / 2
            assert abs(d) <= rel * scale, (name, inputs[i], g, float(v))
            compared += 1
    return compared
