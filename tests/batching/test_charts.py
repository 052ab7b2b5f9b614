"""batching/charts.py: the Charts sheet of summary.xlsx for a 2 x 2 four-bar grid and for
one varied parameter, read back from the chart XML in the zip (ElementTree): the chart
titles from the template's spans and outputs with their units, one chart per plotted
quantity and varied number, series per value of the other grid parameter with the
ranges they read (the hidden ChartData sheet sorted by the second parameter, read back
by openpyxl) and the cached points (the values put in the table, by hand), max red and
solid, min blue and dashed, two charts a row for one parameter."""

from __future__ import annotations

import re
import zipfile
import xml.etree.ElementTree as ET

import openpyxl
import pytest

from workbook_gen.batching.charts import plotted
from workbook_gen.batching.summary import write_summaries
from workbook_gen.batching.table import Table
from workbook_gen.batching.variants import from_specs
from workbook_gen.pruning import select
from workbook_gen.scene import load_scene

C = "{http://schemas.openxmlformats.org/drawingml/2006/chart}"
A = "{http://schemas.openxmlformats.org/drawingml/2006/main}"
XDR = "{http://schemas.openxmlformats.org/drawingml/2006/spreadsheetDrawing}"


def _value(table, index: int, name: str) -> float:
    """The number put in column ``name`` of variant ``index`` (1-based): by hand."""
    return index * 10.0 + table.values.index(name) / 1000.0


def _summary(tmp_path, specs):
    scene = load_scene("templates/four_bar.toml")
    design = from_specs(specs, list(scene.parameters))
    table = Table(design, select(scene.template, scene.outputs),
                  dict(scene.parameters) | dict(scene.options))
    for v in design.variants:
        row = {name: _value(table, v.index, name) for name in table.values}
        row |= {"status": "ok", "file": f"v{v.index}.xlsx", "audit": "",
                "rows_flagged": 0, "rows_not_assembled": 0, "grashof_class": "x",
                "time_ratio": 1.0, "toggle_crank_and_coupler_extended": 1.0,
                "toggle_crank_and_coupler_folded": 1.0}
        table.put(v, row)
    path = tmp_path / "summary.xlsx"
    write_summaries(table, tmp_path / "summary.csv", path, [("command", "x")])
    with zipfile.ZipFile(path) as z:
        names = sorted((n for n in z.namelist() if re.fullmatch(r"xl/charts/chart\d+\.xml", n)),
                       key=lambda n: int(re.findall(r"\d+", n)[0]))
        charts = [ET.fromstring(z.read(n)) for n in names]
        drawing = ET.fromstring(z.read("xl/drawings/drawing1.xml"))
    return table, path, charts, drawing


def _series(chart):
    out = []
    for ser in chart.iter(f"{C}ser"):
        name = "".join(t.text for t in ser.find(f"{C}tx").iter(f"{C}v"))
        x_ref = ser.find(f"{C}xVal").find(f".//{C}f").text
        y = ser.find(f"{C}yVal")
        y_ref = y.find(f".//{C}f").text
        cached = [float(p.find(f"{C}v").text) for p in y.iter(f"{C}pt")]
        line = ser.find(f"{C}spPr/{A}ln")
        colour = line.find(f".//{A}srgbClr").get("val") if line is not None and \
            line.find(f".//{A}srgbClr") is not None else None
        dash = line.find(f"{A}prstDash").get("val") if line is not None and \
            line.find(f"{A}prstDash") is not None else None
        out.append((name, x_ref, y_ref, cached, colour, dash))
    return out


def _title(chart) -> str:
    return "".join(t.text for t in chart.find(f"{C}chart/{C}title").iter(f"{A}t"))


@pytest.fixture(scope="module")
def grid(tmp_path_factory):
    return _summary(tmp_path_factory.mktemp("grid"), ["l_O1A=30,40", "l_AB=100,120"])


def test_titles_by_hand(grid):
    table, _, charts, _ = grid
    titles = [t for t, _ in plotted(table)]
    assert titles[:2] == ["rocker swing [deg]", "coupler swing [deg]"]
    assert titles[4] == "theta_3 [deg]: max and min over the sweep"
    assert "omega_3 [rad/s]: max and min over the sweep" in titles
    # one chart per plotted quantity and varied parameter, in that order
    assert len(charts) == 2 * len(titles)
    assert [_title(c) for c in charts[:4]] == [titles[0]] * 2 + [titles[1]] * 2


def test_against_the_first_parameter_from_the_sorted_chart_data(grid):
    table, path, charts, _ = grid
    book = openpyxl.load_workbook(path)
    data = book["ChartData"]
    assert data.sheet_state == "hidden"
    # sorted by l_AB: variants 1 and 3 (l_AB = 100), then 2 and 4 (l_AB = 120)
    assert [data.cell(r, 1).value for r in range(2, 6)] == [30.0, 40.0, 30.0, 40.0]
    assert [data.cell(r, 2).value for r in range(2, 6)] == [
        _value(table, i, "rocker_swing") for i in (1, 3, 2, 4)]
    series = _series(charts[0])
    assert [s[0] for s in series] == ["l_AB = 100", "l_AB = 120"]
    assert [s[1] for s in series] == ["ChartData!$A$2:$A$3", "ChartData!$A$4:$A$5"]
    assert [s[2] for s in series] == ["ChartData!$B$2:$B$3", "ChartData!$B$4:$B$5"]
    assert [s[3] for s in series] == [[_value(table, i, "rocker_swing") for i in pair]
                                      for pair in ((1, 3), (2, 4))]


def test_against_the_second_parameter_from_the_variants_rows(grid):
    table, _, charts, _ = grid
    i = 2 * [t for t, _ in plotted(table)].index("theta_3 [deg]: max and min over the sweep")
    series = _series(charts[i + 1])
    x = "E"                       # variant, file, status, l_O1A, l_AB
    assert table.columns[4] == "l_AB"
    col = openpyxl.utils.get_column_letter(table.columns.index("theta_3_max") + 1)
    assert [s[0] for s in series] == ["max, l_O1A = 30", "min, l_O1A = 30",
                                      "max, l_O1A = 40", "min, l_O1A = 40"]
    assert series[0][1] == f"Variants!${x}$2:${x}$3"
    assert series[0][2] == f"Variants!${col}$2:${col}$3"
    assert series[2][2] == f"Variants!${col}$4:${col}$5"
    assert series[2][3] == [_value(table, i, "theta_3_max") for i in (3, 4)]
    assert series[1][3] == [_value(table, i, "theta_3_min") for i in (1, 2)]
    # max red and solid, min blue and dashed
    assert series[0][4] == "C00000" and series[0][5] == "solid"
    assert series[1][4] == "1F4E79" and series[1][5] == "dash"


def test_one_parameter_two_charts_a_row(tmp_path):
    table, _, charts, drawing = _summary(tmp_path, ["l_O1A=30,35,40"])
    titles = [t for t, _ in plotted(table)]
    assert len(charts) == len(titles) >= 4
    anchors = [(int(a.find(f"{XDR}from/{XDR}row").text), int(a.find(f"{XDR}from/{XDR}col").text))
               for a in drawing.iter(f"{XDR}twoCellAnchor")]
    assert anchors[:4] == [(0, 0), (0, 9), (19, 0), (19, 9)]
    series = _series(charts[0])
    assert len(series) == 1 and series[0][1] == "Variants!$D$2:$D$4"
    assert series[0][3] == [_value(table, i, "rocker_swing") for i in (1, 2, 3)]
