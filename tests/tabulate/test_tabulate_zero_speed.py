"""Zero input speed is legal (issue 12 item 1): positions as at any speed, every rate 0,
the Checks pass (rate residuals measured per unit speed, not 0/0) and the audit is clean;
and a failed generation leaves no folder behind."""

from __future__ import annotations

import numpy as np
import openpyxl
import pytest

from workbook_gen import audit
from workbook_gen.cli import main
from workbook_gen.tabulate import evaluate
from workbook_gen.reference import solve
from workbook_gen.scene import load_scene
from workbook_gen.workbook import write_workbook

SPEEDS = [("slider_crank", "omega_1"), ("sewing_machine", "omega_1"), ("four_bar", "omega_2"),
          ("walking_beam", "omega_2")]


def _is_rate(unit: str) -> bool:
    return "/s" in unit


@pytest.mark.parametrize("name, speed", SPEEDS)
def test_zero_speed_gives_positions_rates_zero_and_a_clean_audit(tmp_path, name, speed):
    scene = load_scene(f"templates/{name}.toml", overrides={speed: 0.0}, step=10.0)
    result = evaluate(scene)
    # positions: the independent reference model (it knows nothing of the speed's role
    # in the workbook's formulas) at the default speed, which positions do not depend on
    default = load_scene(f"templates/{name}.toml", step=10.0)
    ref = solve(default.template.id, default.parameters, result.inputs)
    ok = result.status == "ok"
    rates = positions = 0
    for q in result.model.columns:
        values = result.columns[q.name].val.astype(float)[ok]
        if _is_rate(q.unit):
            assert np.all(values == 0.0), q.name
            rates += 1
        elif q.name in ref and q.unit in ("mm", "deg"):
            expected = np.asarray(ref[q.name], dtype=float)[ok]
            scale = max(float(np.nanmax(np.abs(expected))), 1.0)
            assert np.nanmax(np.abs(values - expected)) <= 1e-9 * scale, q.name
            positions += 1
    assert rates >= 2 and positions >= 2
    path = write_workbook(scene, tmp_path)
    checks = openpyxl.load_workbook(path, data_only=True)["Checks"]
    assert checks["B2"].value == "PASS"
    assert audit(path).ok


def test_failed_generation_creates_no_folder(tmp_path, capsys):
    out = tmp_path / "new" / "folder"
    code = main(["generate", "templates/slider_crank.toml", "--set", "e=500",
                 "--out", str(out)])
    assert code == 2
    assert "cannot be assembled" in capsys.readouterr().err
    assert not out.exists() and not out.parent.exists()
