"""Shared bits of the extreme-case tests: grids of inputs and the assertion."""

from __future__ import annotations

from mp_reference import measure

TOL = 1e-8  # of each column's magnitude (docs/stability.md, Numerical soundness at the extremes)
EXACT = [0.0, 90.0, 180.0, 270.0, 360.0]


def near(centre: float, spans=(1e-6, 1e-4, 1e-2, 1.0)) -> list[float]:
    return [centre + s * k for s in spans for k in (-1, 1)] + [centre]


def grid(*centres: float, every: float = 15.0) -> list[float]:
    values = set(EXACT) | {every * k for k in range(int(360 / every) + 1)}
    for c in centres:
        values |= set(near(c))
    return sorted(values)


def assert_sound(mechanism, params, inputs, options=None):
    """Every output cell within TOL of its column's magnitude of the 50-digit reference,
    or flagged by the row's status; no singular row left unflagged with a number."""
    worst, unflagged, status = measure(mechanism, params, inputs, options)
    bad = {n: w for n, w in worst.items() if not w[0] <= TOL}
    assert not bad, f"{mechanism} {params} {options}: {bad}"
    assert not unflagged, f"singular rows neither flagged nor errors: {unflagged[:5]}"
    return worst, status
