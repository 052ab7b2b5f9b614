"""workbook/sheets.py: the Parameters and About sheets as openpyxl reads them back: one
row per scene parameter (name, value, unit, description) in the template's order, each
defined name pointing at its own value cell, and About naming the mechanism, the
generator's version and the scene file."""

from __future__ import annotations

import openpyxl
import pytest

from workbook_gen import load_scene
from workbook_gen.version import VERSION


@pytest.fixture(scope="module")
def book(generate):
    scene = load_scene("templates/four_bar.toml", overrides={"l_AB": 121.5})
    return scene, openpyxl.load_workbook(generate("templates/four_bar.toml", overrides={"l_AB": 121.5}))


def test_parameters_one_row_each_and_their_names(book):
    scene, wb = book
    sheet = wb["Parameters"]
    rows = [[c.value for c in r] for r in sheet.iter_rows(min_row=2) if r[0].value]
    spec = {p.name: p for p in scene.template.parameters}
    listed = [r for r in rows if r[0] in scene.parameters]
    assert [r[0] for r in listed] == list(scene.parameters)        # the template's order
    for name, value, unit, description in (r[:4] for r in listed):
        assert value == pytest.approx(scene.parameters[name], rel=0, abs=0)
        assert unit == spec[name].unit and description == spec[name].description
    assert dict((r[0], r[1]) for r in listed)["l_AB"] == 121.5       # the override
    for name in scene.parameters:
        target = wb.defined_names[name].attr_text
        row = next(i for i, r in enumerate(sheet.iter_rows(), 1) if r[0].value == name)
        assert target == f"Parameters!$B${row}", (name, target)


def test_about_names_mechanism_version_and_scene(book):
    scene, wb = book
    about = {r[0].value: r[1].value for r in wb["About"].iter_rows() if r[0].value}
    assert about["mechanism"] == "four_bar"
    assert about["generator"] == f"workbook-gen {VERSION}"
    assert about["scene file"] == "templates/four_bar.toml"
    assert scene.title in about
