"""tabulate/summary.py: the Summary's values against pandas over the computed Table
(``compute``, the Table's own columns): each output's largest and smallest value over the
ok rows and the input of the first row holding it (where no other row ties), the row
counts, and the flagged rows by status; on templates and sweeps with flagged and
unassembled rows."""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest

from workbook_gen import load_scene
from workbook_gen.tabulate import compute, evaluate

SCENES = [("templates/four_bar.toml", {}), ("templates/slider_crank.toml", {"e": 95.0}),
          ("templates/sewing_machine.toml", {}), ("templates/five_bar.toml", {}),
          ("templates/actuator_linkage.toml", {}),
          ("templates/four_bar.toml", {"l_O1A": 70.0}),   # not a crank: rows that cannot assemble
          ("templates/slider_crank.toml", {"l_BC": 50.0}),   # the rod tangent: a dead centre
          ("templates/four_bar.toml", {"l_O1A": 40.0, "l_AB": 100.0, "l_O2B": 80.0,
                                       "l_O1O2": 140.0})]   # a toggle


@pytest.mark.parametrize("path, overrides", SCENES)
def test_summary_as_pandas(path, overrides):
    scene = load_scene(path, overrides=overrides)
    frame = compute(scene)
    values = evaluate(scene).summary
    status = frame["status"]
    ok = (status == "ok").to_numpy()
    inputs = frame[frame.columns[0]].to_numpy(dtype=float)
    assert values.rows == len(frame) and values.rows_ok == int(ok.sum())
    not_assembled = int(status.str.contains("assemble").sum())
    assert values.rows_not_assembled == not_assembled
    others = Counter(s for s in status if s != "ok" and "assemble" not in s)
    assert values.flagged == dict(sorted(others.items()))
    by_name = {c.split(" [")[0]: c for c in frame.columns}
    for name, found in values.outputs.items():
        column = frame[by_name[name]].to_numpy()
        numbers = np.array([isinstance(v, float) and np.isfinite(v) for v in column])
        rows = ok & numbers
        if not rows.any():
            continue
        x = column[rows].astype(float)
        assert found.hi == x.max() and found.lo == x.min(), name
        if not found.tied:
            assert found.at_hi == inputs[rows][np.argmax(x)], name
            assert found.at_lo == inputs[rows][np.argmin(x)], name
