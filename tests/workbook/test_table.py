"""workbook/table.py: the Table sheet as openpyxl reads it back: a header "name [unit]"
for the input and each column in the template's order, then the status; one row per
sweep point, the input column holding numpy's sweep as numbers; every other cell a live
formula, and every cached value the scene's computed table to the bit."""

from __future__ import annotations

import numpy as np
import openpyxl
import pytest

from workbook_gen import compute, load_scene

SCENE = "templates/slider_crank.toml"


@pytest.fixture(scope="module")
def sheets(generate):
    path = generate(SCENE, step=7.5)
    return (openpyxl.load_workbook(path)["Table"],
            openpyxl.load_workbook(path, data_only=True)["Table"])


def test_headers_rows_and_live_formulas(sheets):
    formulas, _ = sheets
    scene = load_scene(SCENE, step=7.5)
    frame = compute(scene)
    header = [c.value for c in formulas[1]]
    assert header == list(frame.columns)
    assert header[0] == f"{scene.template.input.name} [{scene.template.input.unit}]"
    assert header[-1] == "status"
    sweep = np.arange(scene.sweep.start, scene.sweep.stop + 1e-9, scene.sweep.step)
    assert formulas.max_row == len(sweep) + 1
    for row in formulas.iter_rows(min_row=2):
        assert isinstance(row[0].value, (int, float))            # the input: numbers
        for cell in row[1:]:
            assert isinstance(cell.value, str) and cell.value.startswith("="), cell


def test_cached_values_are_the_computed_table(sheets):
    _, values = sheets
    scene = load_scene(SCENE, step=7.5)
    frame = compute(scene)
    sweep = np.arange(scene.sweep.start, scene.sweep.stop + 1e-9, scene.sweep.step)
    cached = [[c.value for c in row] for row in values.iter_rows(min_row=2)]
    assert [row[0] for row in cached] == pytest.approx(sweep.tolist(), rel=0, abs=1e-12)
    for j, name in enumerate(frame.columns):
        column = frame[name].to_numpy()
        for i, got in enumerate(row[j] for row in cached):
            want = column[i]
            if isinstance(want, float) and np.isnan(want):
                assert isinstance(got, str) and got.startswith("#"), (name, i, got)
            else:
                assert got == want, (name, i, got, want)
