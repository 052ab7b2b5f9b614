"""reference/walking_beam.py: the walking beam (two four-bars and the parallelogram) solved by the reference solver agrees with the
50-digit mpmath reference of tests/mp_reference.py (tests/reference/agreement.py says
how) over a sweep, within 1e-9 of each column's magnitude."""

from __future__ import annotations

import numpy as np

from .agreement import check


def test_agrees_with_the_50_digit_reference():
    assert check("walking_beam", np.linspace(-180.0, 345.0, 15)) > 20
