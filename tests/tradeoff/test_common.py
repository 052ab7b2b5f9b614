"""tradeoff.common: the error measures by hand, the 50-digit difference against the
known binary expansion of 0.1, the columns' NaNs where tests/mp_reference.py says no row
assembles, and a workbook's cost read back with openpyxl."""

from __future__ import annotations

import json
from pathlib import Path

import mpmath
import numpy as np
import openpyxl

from tests import mp_reference
from workbook_gen.scene import load_scene
from workbook_gen.tabulate import evaluate
from workbook_gen.tradeoff.common import (Row, cost, floats, mp_diff, mp_floats, relative,
                                          studied, worst)
from workbook_gen.xlerror import ExcelError

NAN = float("nan")


def test_relative_is_the_worst_difference_over_the_largest_reference():
    diff = np.array([1.0, -3.0, NAN, 7.0])
    ref = np.array([10.0, -20.0, 5.0, NAN])
    assert relative(diff, ref) == 3.0 / 20.0
    assert np.isnan(relative(np.array([NAN]), np.array([1.0])))
    assert relative(np.array([2e-17, -4e-17]), np.zeros(2)) == 4e-17  # no scale: absolute


def test_worst_skips_undefined_errors():
    assert worst({"a": 1e-9, "b": NAN, "c": 3e-12}) == 1e-9
    assert worst({"a": NAN}) is None and worst({}) is None


def test_mp_diff_is_taken_before_rounding():
    # float 0.1 = 0.1000000000000000055511151231257827021181583404541015625 exactly
    with mpmath.workdps(50):
        ref = [{"x": mpmath.mpf(1) / 10}, {"x": ExcelError.NUM}, {"x": mpmath.mpf(2)}]
    d = mp_diff(np.array([0.1, 1.0, NAN]), ref, "x")
    assert abs(d[0] / 5.551115123125782702118158340454e-18 - 1) < 1e-15
    assert np.isnan(d[1]) and np.isnan(d[2])
    f = mp_floats(ref, "x")
    assert f[0] == 0.1 and np.isnan(f[1]) and f[2] == 2.0


def test_row_json_has_no_nan():
    row = Row("step", "10 deg", NAN, 1.5, 10, 2000, 37, {"y": NAN, "v": 1e-9}, float("inf"))
    data = json.loads(json.dumps(row.to_json(), allow_nan=False))
    assert data["max_error"] is None and data["abs_error"] is None
    assert data["errors"] == {"y": None, "v": 1e-9} and data["seconds"] == 1.5
    assert data["cpu_seconds"] is None and data["rows"] == 37


def test_floats_are_nan_where_no_row_assembles():
    # R_path 0.7: C leaves the five-bar's reach on part of its circle
    scene = load_scene("templates/five_bar.toml", {"R_path": 0.7}, step=15.0)
    result = evaluate(scene)
    theta = floats(result, "theta_1")
    with mpmath.workdps(30):
        reached = [mp_reference.five_bar(scene.parameters, x)[0] is not None
                   for x in result.inputs]
    assert not all(reached) and any(reached)
    assert list(np.isfinite(theta)) == reached
    ok = [i for i, r in enumerate(reached) if r]
    with mpmath.workdps(30):
        ref = [float(mp_reference.five_bar(scene.parameters, result.inputs[i])[0]["theta_1"])
               for i in ok]
    assert np.allclose(np.mod(theta[ok] - ref + 180, 360) - 180, 0, atol=1e-9)
    # the status rule: ok_only drops flagged rows as well, never adds one
    everything = floats(result, "theta_1", ok_only=False)
    assert np.all(np.isfinite(everything) >= np.isfinite(theta))


def test_studied_leaves_out_iterates_and_unitless_columns():
    scene = load_scene("templates/actuator_linkage.toml")
    names = studied(scene)
    assert "phi_2_iter" in scene.outputs and "phi_2_iter" not in names
    assert "halvings_used" not in names and "below_gamma_min" not in names
    assert "phi_2" in names and "alpha_3" in names


def test_cost_counts_the_workbooks_formulas(tmp_path, monkeypatch):
    scene = load_scene("templates/sewing_machine.toml", step=90.0)
    kept = []
    from workbook_gen import workbook
    real = workbook.write_workbook

    def keep(scene, out_dir, **kw):
        path = real(scene, tmp_path, **kw)
        kept.append(Path(path))
        return path
    monkeypatch.setattr(workbook, "write_workbook", keep)
    spent = cost(scene)
    (path,) = kept
    book = openpyxl.load_workbook(path)
    formulas = sum(1 for ws in book.worksheets for row in ws.iter_rows()
                   for c in row if c.data_type == "f")
    assert spent.cells == formulas
    assert spent.bytes == path.stat().st_size and spent.rows == 5 and spent.audit_ok
    assert spent.seconds == spent.generate + spent.audit > 0


def test_floats_masks_errors_and_flagged_rows_whatever_the_value_slot_holds():
    from types import SimpleNamespace
    column = SimpleNamespace(err=np.array([0, 6, 0, 0]), val=np.array([1.0, 0.0, 3.0, 4.0]))
    result = SimpleNamespace(columns={"y": column},
                             status=np.array(["ok", "ok", "dead centre", "ok"], dtype=object))
    all_rows = floats(result, "y", ok_only=False)
    assert all_rows[0] == 1.0 and np.isnan(all_rows[1]) and list(all_rows[2:]) == [3.0, 4.0]
    ok = floats(result, "y")
    assert ok[0] == 1.0 and np.isnan(ok[1]) and np.isnan(ok[2]) and ok[3] == 4.0
