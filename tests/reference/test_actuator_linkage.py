"""reference/actuator_linkage.py: the actuator linkage solved by the reference solver agrees with the
50-digit mpmath reference of tests/mp_reference.py (tests/reference/agreement.py says
how) over a sweep, within 1e-9 of each column's magnitude."""

from __future__ import annotations

import numpy as np

from .agreement import check


def test_agrees_with_the_50_digit_reference():
    assert check("actuator_linkage", np.linspace(1.0, 1.687, 12)) > 20


def test_a_lever_near_its_limits():
    assert check("actuator_linkage", np.linspace(1.0, 1.687, 12), {"x_B": 0.5, "l_A1C": 0.3}) > 20
