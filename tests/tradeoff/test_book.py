"""tradeoff.book: the Tradeoff workbook read back with openpyxl (rows in dimension order,
closed form first, numbers and formats), its charts read from the package's XML
(DrawingML c:scatterChart, c:logBase, ECMA-376 Part 1 section 21.2), and the naming rules
by hand."""

from __future__ import annotations

import re
import zipfile
from types import SimpleNamespace

import openpyxl
import pytest

from workbook_gen.errors import OutputExistsError
from workbook_gen.tradeoff.book import family, output_path, series, step_of, write_tradeoff_workbook
from workbook_gen.tradeoff.common import Row
from workbook_gen.tradeoff.measure import Tradeoff

SCENE = SimpleNamespace(name="demo", title="Demo", source="templates/demo.toml",
                        template=SimpleNamespace(id="five_bar"))
ROWS = [
    Row("precision", "float64, whole table", 3e-16, 0.01, 370, None, 37, {"y": 3e-16}),
    Row("step", "10 deg", 1e-3, 1.0, 100, 9000, 37, {"y": 1e-3, "v": float("nan")}),
    Row("step", "1 deg", 1e-5, 2.0, 1000, 90000, 361, {"y": 1e-5}),
    Row("method", "newton 1", 1e-2, 1.5, 200, 9500, 37),
    Row("method", "newton 2", 1e-5, 1.6, 220, 9600, 37),
    Row("method", "closed form", 1e-15, 1.2, 180, 9400, 37),
    Row("derivative", "forward, 10 deg", 1e-2, 0.9, 120, 8000, 37),
    Row("derivative", "analytic, 10 deg", 1e-14, 1.0, 100, 9000, 37),
    Row("derivative", "central, 10 deg", 1e-3, 0.9, 120, 8000, 37),
    Row("derivative", "analytic, 1 deg", 1e-14, 2.0, 1000, 90000, 361),
]


def test_naming_rules_by_hand():
    assert family("central, 1 deg") == "central" and family("newton 3") == "newton"
    assert family("epsilon 1e-05") == "epsilon" and family("closed form") == ""
    assert series(Row("step", "2 deg", 0, 0, 0, 0)) == "step"
    assert series(Row("method", "closed form", 0, 0, 0, 0)) == "closed form"
    assert step_of(Row("derivative", "central, 0.5 deg", 0, 0, 0, 0)) == 0.5
    assert step_of(Row("step", "1e-05", 0, 0, 0, 0)) == 1e-05
    assert step_of(Row("method", "newton 3", 0, 0, 0, 0)) is None
    assert output_path(SCENE, "out").as_posix() == "out/demo_tradeoff.xlsx"


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    out = tmp_path_factory.mktemp("book")
    return write_tradeoff_workbook(Tradeoff(SCENE, list(ROWS), {}, 5.0), out)


def test_rows_read_back_in_dimension_order(written):
    sheet = openpyxl.load_workbook(written)["Tradeoff"]
    table = [[c.value for c in row] for row in sheet.iter_rows(min_row=1, max_row=11)]
    assert table[0] == ["dimension", "setting", "max error", "seconds", "cells", "bytes",
                        "rows", "note", "step"]
    assert [r[1] for r in table[1:]] == [
        "10 deg", "1 deg", "closed form", "newton 1", "newton 2", "analytic, 10 deg",
        "analytic, 1 deg", "central, 10 deg", "forward, 10 deg", "float64, whole table"]
    assert table[1][2:7] == [1e-3, 1.0, 100, 9000, 37] and table[1][8] == 10
    assert table[10][5] is None and table[10][8] is None  # no bytes, no step
    assert sheet["C2"].number_format == "0.00E+00" and sheet["E2"].number_format == "#,##0"
    assert sheet["A13"].value.startswith("max error: worst over the outputs")


def test_errors_sheet_one_line_per_quantity(written):
    sheet = openpyxl.load_workbook(written)["Errors"]
    lines = [[c.value for c in row] for row in sheet.iter_rows(min_row=2)]
    assert lines[:2] == [["step", "10 deg", "y", 1e-3], ["step", "10 deg", "v", None]]
    assert lines[-1] == ["precision", "float64, whole table", "y", 3e-16]
    assert len(lines) == 4


def test_one_logarithmic_scatter_chart_per_dimension(written):
    with zipfile.ZipFile(written) as z:
        charts = sorted(n for n in z.namelist() if re.fullmatch(r"xl/charts/chart\d+\.xml", n))
        xml = [z.read(n).decode() for n in charts]
    assert len(charts) == 4
    assert all("<c:scatterChart>" in x and 'c:logBase val="10"' in x for x in xml)
    step = next(x for x in xml if "demo: step" in x)
    assert "Tradeoff!$I$2:$I$3" in step and "Tradeoff!$C$2:$C$3" in step  # error by step
    assert "Tradeoff!$D$2:$D$3" in step  # seconds on the second axis
    method = next(x for x in xml if "demo: method" in x)
    assert "Tradeoff!$D$5:$D$6" in method and "Tradeoff!$I$" not in method  # against time


def test_refuses_to_overwrite(written):
    with pytest.raises(OutputExistsError):
        write_tradeoff_workbook(Tradeoff(SCENE, list(ROWS), {}, 5.0), written.parent)
    write_tradeoff_workbook(Tradeoff(SCENE, list(ROWS), {}, 5.0), written.parent, force=True)


def test_a_unitless_input_has_its_step_too(tmp_path):
    """The actuator's input is unitless ('-'): its step rows are labelled "0.0687 -" by
    steps.step_label; their chart is error against the step all the same."""
    from workbook_gen.scene import load_scene
    from workbook_gen.tradeoff.steps import step_label, step_settings
    scene = load_scene("templates/actuator_linkage.toml")
    labels = [step_label(scene, s) for s in step_settings(scene)[:3]]
    assert labels[0] == "0.0687 -"
    assert [step_of(Row("step", x, 0, 0, 0, 0)) for x in labels] == [0.0687, 0.03435, 0.01374]
    assert step_of(Row("derivative", "central, 6.87e-05 -", 0, 0, 0, 0)) == 6.87e-05
    rows = [Row("step", x, 10.0 ** -k, 1.0 + k, 10, 10, 10) for k, x in enumerate(labels)]
    demo = SimpleNamespace(name="act", title="A", source="a.toml",
                           template=SimpleNamespace(id="actuator_linkage"))
    path = write_tradeoff_workbook(Tradeoff(demo, rows, {}, 1.0), tmp_path)
    sheet = openpyxl.load_workbook(path)["Tradeoff"]
    assert [sheet.cell(i, 9).value for i in (2, 3, 4)] == [0.0687, 0.03435, 0.01374]
    with zipfile.ZipFile(path) as z:
        xml = z.read("xl/charts/chart1.xml").decode()
    assert "Tradeoff!$I$2:$I$4" in xml
