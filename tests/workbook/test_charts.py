"""Charts a viewer that does not calculate can draw (issue 22 item 16): every series caches
its points, multi-series charts have a legend, the axes' labels sit outside the plot."""

from __future__ import annotations

import re
import zipfile

import numpy as np
import pytest

from workbook_cells import as_float, table_columns
from workbook_gen.reference import solve
from workbook_gen.scene import load_scene

_SERIES = re.compile(r"<c:f>Table!\$([A-Z]+)\$2:\$[A-Z]+\$(\d+)</c:f><c:numCache>"
                     r"<c:formatCode>General</c:formatCode><c:ptCount val=\"(\d+)\"/>(.*?)"
                     r"</c:numCache>")
_POINT = re.compile(r'<c:pt idx="(\d+)"><c:v>([^<]*)</c:v></c:pt>')


def _column_index(letters: str) -> int:
    n = 0
    for ch in letters:
        n = n * 26 + ord(ch) - 64
    return n - 1


def _charts(path) -> list[str]:
    with zipfile.ZipFile(path) as z:
        return [z.read(n).decode() for n in sorted(z.namelist())
                if n.startswith("xl/charts/chart")]


@pytest.mark.parametrize("scene_path, overrides", [
    ("templates/four_bar.toml", {}),
    ("templates/slider_crank.toml", {"l_AB": 40.0, "e": 10.0, "l_BC": 10.0}),  # error rows
])
def test_every_series_caches_the_reference_values(generate, scene_path, overrides):
    path = generate(scene_path, overrides=overrides)
    scene = load_scene(scene_path, overrides=overrides)
    cells = table_columns(path)
    names = list(cells)
    inputs = as_float(cells[names[0]])
    reference = solve(scene.template.id, scene.parameters, inputs)
    ok = np.array([s == "ok" for s in cells.pop("status")])
    charts = _charts(path)
    assert charts
    seen = 0
    for xml in charts:
        series = _SERIES.findall(xml)
        assert len(series) == xml.count("<c:f>"), "a series range without its cache"
        for letters, last, count, points in series:
            name = names[_column_index(letters)]
            assert int(count) == int(last) - 1 == len(inputs)
            cached = np.full(len(inputs), np.nan)
            for i, v in _POINT.findall(points):
                cached[int(i)] = float(v)
            if name == names[0]:
                assert np.array_equal(cached, inputs)
                continue
            ref = reference[name]
            # no point where the cell holds an error; the reference's value elsewhere
            assert np.array_equal(np.isnan(cached), np.isnan(as_float(cells[name]))), name
            # the rows the workbook vouches for (the reference's Newton keeps only half
            # its digits at a flagged tangent row, a double root)
            both = np.isfinite(cached) & np.isfinite(ref) & ok
            assert both.any()
            scale = np.max(np.abs(ref[both]))
            assert np.max(np.abs(cached[both] - ref[both])) <= 1e-9 * scale, name
            seen += 1
    assert seen >= 4


def test_legend_where_several_series_and_axes_cross_at_the_minimum(generate):
    path = generate("templates/four_bar.toml", overrides={})
    for xml in _charts(path):
        several = xml.count("<c:ser>") > 1
        assert ("<c:legend>" in xml) == several
        # both value axes cross the other at its minimum, labels low: outside the plot
        assert xml.count('<c:crosses val="min"/>') == 2, xml[-800:]
        assert xml.count('<c:tickLblPos val="low"/>') == 2


@pytest.mark.parametrize("vary, samples", [
    ({"l_BC": "95:105:5", "l_AB": "28,32"}, None),       # a grid: grouped series
    ({"l_AB": "normal:32:0.05", "l_BC": "uniform:99.9:100.1"}, 30),  # Statistics' chart too
])
def test_batch_summary_charts_cache_their_points(tmp_path, vary, samples):
    """The summary's charts cache the points the Variants and Statistics cells hold, as
    read back by openpyxl (issue 22 item 16: no empty charts in a preview)."""
    import openpyxl
    from workbook_gen.batching import batch
    options = {"samples": samples, "seed": 1} if samples else {}
    frame = batch("templates/sewing_machine.toml", vary=vary, out=str(tmp_path),
                  summary_only=True, **options)
    path = f"{frame.attrs['folder']}/summary.xlsx"
    book = openpyxl.load_workbook(path, data_only=True)
    series = 0
    with zipfile.ZipFile(path) as z:
        charts = [z.read(n).decode() for n in z.namelist() if n.startswith("xl/charts/chart")]
    ref = re.compile(r"<c:f>'?(\w+)'?!\$([A-Z]+)\$(\d+):\$[A-Z]+\$(\d+)</c:f>"
                     r"<c:(?:num|str)Cache>(.*?)</c:(?:num|str)Cache>")
    for xml in charts:
        for sheet, letters, first, last, cache in ref.findall(xml):
            cells = [book[sheet][f"{letters}{r}"].value for r in range(int(first), int(last) + 1)]
            points = {int(i): v for i, v in _POINT.findall(cache)}
            assert re.search(r'<c:ptCount val="(\d+)"/>', cache).group(1) == str(len(cells))
            for i, cell in enumerate(cells):
                if isinstance(cell, (int, float)):
                    assert float(points[i]) == pytest.approx(cell, rel=1e-15, abs=1e-300)
                elif isinstance(cell, str):
                    assert points[i] == cell
                else:
                    assert i not in points
            series += 1
    assert series >= 8


def test_kept_charts_and_their_xml_are_dropped_together_between_workbooks(tmp_path):
    """Chart objects are kept for the next workbook, with their XML.  When the kept XML
    was dropped (at its limit, in the middle of a long run) while the charts were kept,
    XlsxWriter assembled a kept chart a second time and its counters carried on: series
    idx from 1, more axis ids, a rotated axis title (found by the full suite).  Now both
    are dropped together, before a workbook: every build gives the same chart parts."""
    import re
    import zipfile

    from workbook_gen.scene import load_scene
    from workbook_gen.workbook import charts as chart_module, write_workbook

    def chart_parts(path):
        with zipfile.ZipFile(path) as z:
            return {n: z.read(n).decode() for n in z.namelist() if n.startswith("xl/charts/")}

    scene = load_scene("templates/slider_crank.toml", step=15.0)
    first = chart_parts(write_workbook(scene, tmp_path / "a"))      # kept from here on
    again = chart_parts(write_workbook(scene, tmp_path / "b"))      # kept charts, kept XML
    kept_xml = chart_module._kept().xml                             # the XML at its limit
    kept_xml.update({("other scene", i): "" for i in range(2 * chart_module._KEPT_LIMIT)})
    fresh = chart_parts(write_workbook(scene, tmp_path / "c"))
    assert first == again == fresh
    assert ("other scene", 0) not in chart_module._kept().xml       # dropped before "c"
    assert len(chart_module._kept().charts) == len(first)
    for xml in fresh.values():        # ECMA-376 21.2.2: series idx from 0, two axes each
        idx = [int(v) for v in re.findall(r'<c:idx val="(\d+)"/>', xml)]
        assert idx == list(range(len(idx)))
        assert len(set(re.findall(r'<c:axId val="(\d+)"/>', xml))) == 2
