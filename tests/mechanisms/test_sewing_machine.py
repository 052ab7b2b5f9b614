"""theta_5 is continuous over the sweep: no jump at +-180 deg, whichever side F is on."""

from __future__ import annotations

import numpy as np
import pytest

from workbook_gen.tabulate import compute
from workbook_gen.scene import load_scene


@pytest.mark.parametrize("overrides", [
    {},                                   # lever points right, angles near 0
    {"x_F": 60.0, "y_F": 0.0},            # lever points left: angles cross 180 deg
    {"x_F": 60.0, "y_F": -20.0},
    {"x_F": -10.0, "y_F": 60.0},          # lever hangs down from above
])
def test_lever_angle_continuous_across_180(overrides):
    table = compute(load_scene("templates/sewing_machine.toml", overrides=overrides, step=1.0))
    theta = table["theta_5 [deg]"].to_numpy()
    omega = table["omega_5 [rad/s]"].to_numpy()
    # the largest step between rows is what the angular velocity allows in 1 deg of crank
    steps = np.abs(np.diff(theta))
    bound = np.degrees(np.max(np.abs(omega))) / 360.0 * 1.05
    assert np.max(steps) <= bound
    if overrides.get("x_F", 0) > 0 and overrides.get("y_F") == 0.0:
        assert theta.min() < 180.0 < theta.max()  # it does cross 180 deg, smoothly
