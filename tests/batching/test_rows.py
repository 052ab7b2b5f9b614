"""batching/rows.py: the summary's figures for a block of variants (flattened, variant
after variant) against the four-bar worked out independently (tests/fourbar_figures.py:
extremes over the rows the 50-digit reference solves, Norton's Grashof class and time
ratio by the law of cosines), and the column names, units and headers by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

import fourbar_figures as ref
from workbook_gen import xlmath as xm
from workbook_gen.expr import Param, Var
from workbook_gen.expr.numeric import compile_numpy
from workbook_gen.pruning import select
from workbook_gen.scene import load_scene
from workbook_gen.batching.rows import (ROW_COUNTS, as_columns, column_units, figure_columns,
                                        figure_values, header, param_columns, snake,
                                        summarise, text_figures, value_columns)
from workbook_gen.tabulate.table import evaluate_table
import mp_reference

INPUTS = [float(x) for x in range(0, 360, 15)]
VARIANTS = [ref.NORTON, ref.NORTON | {"l_O1A": 30.0},
            ref.NORTON | {"l_O1A": 60.0, "l_AB": 40.0, "l_O2B": 60.0}]   # the last: partial


@pytest.fixture(scope="module")
def block():
    """(model, the block's summary) of the three variants, columns concatenated."""
    tables = [evaluate_table(mp_reference.scene_at("four_bar", p, INPUTS)) for p in VARIANTS]
    model = tables[0].model
    names = [q.name for q in model.outputs()]
    columns = {n: xm.XArray(np.concatenate([t.columns[n].val for t in tables]),
                            np.concatenate([t.columns[n].err for t in tables]))
               for n in names}
    status = np.concatenate([t.status for t in tables])
    params = {k: np.array([t.params[k] for t in tables]) for k in tables[0].params}
    figures = figure_values(model, params, len(VARIANTS))
    return model, summarise(model, np.array(INPUTS), columns, status, figures, len(VARIANTS))


def test_names_by_hand():
    assert snake("needle stroke, exact") == "needle_stroke_exact"
    assert snake("Grashof class") == "grashof_class"
    assert snake("  coupler point, x range ") == "coupler_point_x_range"
    assert header("y_C_max", {"y_C_max": "mm"}) == "y_C_max [mm]"
    assert header("status", {}) == "status"


def test_columns_of_the_four_bar():
    scene = load_scene("templates/four_bar.toml")
    model = select(scene.template, scene.outputs)
    names = value_columns(model)
    assert names[:4] == ["theta_3_min", "theta_3_min_at", "theta_3_max", "theta_3_max_at"]
    assert names[-2:] == list(ROW_COUNTS) == ["rows_flagged", "rows_not_assembled"]
    assert figure_columns(model)[:4] == ["rocker_swing", "coupler_swing",
                                         "coupler_point_x_range", "coupler_point_y_range"]
    assert "grashof_class" in text_figures(model) and "rocker_swing" not in text_figures(model)
    units = column_units(model, ["l_O1A", "omega_2"])
    assert units["l_O1A"] == "mm" and units["omega_2"] == "rad/s"
    assert units["y_C_max"] == "mm" and units["y_C_max_at"] == "deg"
    assert units["omega_3_min"] == "rad/s" and units["rocker_swing"] == "deg"
    assert "grashof_class" not in units


def test_parameters_as_columns():
    tree = as_columns(Param("a") * Param("b") + Var("x"))
    columns = param_columns({"a": np.array([2.0, 3.0]), "b": np.array([10.0, 100.0])}, 3)
    columns["x"] = xm.array(np.arange(6.0))
    got = compile_numpy(tree)(columns, {}, 6)
    assert got.val.tolist() == [20.0, 21.0, 22.0, 303.0, 304.0, 305.0]


def test_extremes_of_each_variant(block):
    model, out = block
    for v, params in enumerate(VARIANTS):
        found, missing = ref.extremes(params, INPUTS)
        for name, (lo, lo_at, hi, hi_at) in found.items():
            assert ref.close(out[f"{name}_min"][v], lo) and ref.close(out[f"{name}_max"][v], hi)
            assert out[f"{name}_min_at"][v] == lo_at and out[f"{name}_max_at"][v] == hi_at
        assert out["rows_not_assembled"][v] == missing
        assert out["status"][v] == ("partial" if missing else "ok")
        xs = found["x_C"]
        assert ref.close(out["coupler_point_x_range"][v], xs[2] - xs[0], scale=100)
    assert out["status"] == ["ok", "ok", "partial"]
    assert out["rows_flagged"] == [0, 0, 0]


def test_figures_of_each_variant(block):
    _, out = block
    assert out["grashof_class"] == [ref.grashof_class(p) for p in VARIANTS]
    assert out["grashof_class"][2] == "non-Grashof triple-rocker"
    for v in (0, 1):
        assert math.isclose(out["time_ratio"][v], ref.time_ratio(VARIANTS[v]), rel_tol=1e-12)
    assert math.isclose(out["time_ratio"][0], 1.3556, rel_tol=1e-4)   # Norton's example
    assert out["time_ratio"][2].startswith("n/a")


def test_flagged_rows_are_left_out_and_counted():
    inputs = np.array([0.0, 1.0, 2.0, 3.0])
    column = xm.array(np.array([5.0, 9.0, -1.0, 2.0]))
    model = select(load_scene("templates/four_bar.toml").template, ("y_C",))
    status = np.array(["ok", "toggle", "cannot assemble", "ok"], dtype=object)
    figures = {name: [None] for name in text_figures(model)}   # not under test here
    out = summarise(model, inputs, {"y_C": column}, status, figures, 1)
    assert (out["y_C_min"], out["y_C_min_at"], out["y_C_max"], out["y_C_max_at"]) == \
        ([2.0], [3.0], [5.0], [0.0])
    assert out["rows_flagged"] == [1] and out["rows_not_assembled"] == [1]
    assert out["status"] == ["partial"]
