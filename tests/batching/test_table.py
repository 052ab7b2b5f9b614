"""batching/table.py: the summary table of a four-bar grid (docs/batch.md's columns):
its columns, headers with the template's units, the varied values filled in by hand,
rows put one by one or in blocks, the column kinds, the tallies (kept or not, the
same counts by hand), the DataFrame (None as NaN, counts as Int64), and the merged
columns of two option combinations (each model's order kept)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbook_gen.batching.rows import value_columns
from workbook_gen.batching.table import Table, merged_columns
from workbook_gen.batching.variants import from_specs
from workbook_gen.pruning import select
from workbook_gen.scene import load_scene


def _model(path, overrides=None):
    scene = load_scene(path, overrides)
    return scene, select(scene.template, scene.outputs)


@pytest.fixture(scope="module")
def grid():
    scene, model = _model("templates/four_bar.toml")
    design = from_specs(["l_O1A=30,40", "l_AB=100,120"], list(scene.parameters))
    return design, model, dict(scene.parameters) | dict(scene.options)


def _row(status, y_max, ratio, audit="", flagged=0, missing=0):
    return {"file": "f.xlsx", "status": status, "y_C_max": y_max, "time_ratio": ratio,
            "grashof_class": "Grashof crank-rocker", "audit": audit,
            "rows_flagged": flagged, "rows_not_assembled": missing}


ROWS = [_row("ok", 91.5, 1.25), _row("partial", 80.0, "n/a: needs a crank-rocker",
                                     missing=3),
        _row("refused: l_AB must be positive", None, None, flagged=None, missing=None),
        _row("ok", 70.0, 1.5, "fail")]


def test_columns_headers_and_varied_values(grid):
    design, model, defaults = grid
    table = Table(design, model, defaults)
    assert table.columns[:5] == ["variant", "file", "status", "l_O1A", "l_AB"]
    assert table.columns[5:-1] == value_columns(model) and table.columns[-1] == "audit"
    heads = dict(zip(table.columns, table.headers))
    assert heads["l_O1A"] == "l_O1A [mm]" and heads["y_C_max_at"] == "y_C_max_at [deg]"
    assert heads["status"] == "status" and heads["grashof_class"] == "grashof_class"
    # a grid: the last name varies fastest
    assert table.data["l_O1A"] == [30.0, 30.0, 40.0, 40.0]
    assert table.data["l_AB"] == [100.0, 120.0, 100.0, 120.0]
    assert table.data["variant"] == ["1", "2", "3", "4"]
    assert not table.complete


def _filled(grid, keep, blocks):
    design, model, defaults = grid
    table = Table(design, model, defaults, keep=keep)
    variants = list(design.variants)
    if blocks:
        for part in (slice(0, 2), slice(2, 4)):
            chosen = variants[part]
            block = {name: [ROWS[v.index - 1].get(name) for v in chosen]
                     for name in table.values + ["file", "status", "audit"]}
            table.put_block(chosen, block)
    else:
        for v in reversed(variants):
            table.put(v, ROWS[v.index - 1])
    return table


@pytest.mark.parametrize("keep,blocks", [(True, False), (True, True), (False, True)])
def test_tallies_by_hand(grid, keep, blocks):
    table = _filled(grid, keep, blocks)
    assert table.complete
    statuses, audits = table.tally()
    assert dict(statuses) == {"ok": 2, "partial": 1, "refused": 1} and audits == 1
    assert table.failed_count() == 3          # partial, refused, the failing audit
    assert table.kind("time_ratio") == "mixed"
    assert table.kind("grashof_class") == "text"
    assert table.kind("y_C_max") == "number" and table.kind("status") == "text"
    assert table.kind("l_O1A") == "number"


def test_the_frame(grid):
    frame = _filled(grid, True, False).frame()
    assert list(frame.columns) == _filled(grid, True, True).columns
    assert frame["y_C_max"].tolist()[:2] == [91.5, 80.0] and math.isnan(frame["y_C_max"][2])
    assert str(frame["rows_not_assembled"].dtype) == "Int64"
    assert frame["rows_not_assembled"].tolist()[:2] == [0, 3]
    assert frame["rows_not_assembled"].isna().tolist() == [False, False, True, False]
    assert frame["time_ratio"].tolist()[1] == "n/a: needs a crank-rocker"
    assert frame["audit"].tolist() == ["", "", "", "fail"]
    assert frame.attrs["units"]["l_AB"] == "mm"
    assert np.isnan(frame["theta_3_min"]).all()   # never put: no number


def test_merged_columns_keep_each_models_order():
    _, bare = _model("templates/four_bar_balanced.toml", {"balance": False})
    _, balanced = _model("templates/four_bar_balanced.toml")
    a, b = value_columns(bare), value_columns(balanced)
    merged = merged_columns([bare, balanced])
    assert len(merged) == len(set(a) | set(b)) == len(set(merged))
    for order in (a, b):
        positions = [merged.index(name) for name in order]
        assert positions == sorted(positions)
    assert merged.index("x_S_cw_crank_min") > merged.index(
        b[b.index("x_S_cw_crank_min") - 1])
