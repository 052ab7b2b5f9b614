"""The private names of XlsxWriter and zipfile the writer relies on (issue 23 item 4): a
new release that drops or renames one fails here, naming it, before any workbook comes out
wrong.  Where each is used: workbook/package.py (the packaging, kept drawing XML, the
in-memory row buffer), workbook/rows.py (rows written as blocks of bytes),
workbook/charts.py (kept chart XML and the series caches), batching/summary.py (the
Variants sheet streamed), batching/charts.py and statistics.py (series caches).  The tested
range is pinned in pyproject.toml."""

from __future__ import annotations

import inspect
import re
import zipfile
from pathlib import Path

import pytest
import xlsxwriter
import xlsxwriter.chart
import xlsxwriter.drawing
import xlsxwriter.format
import xlsxwriter.workbook
import xlsxwriter.worksheet
import xlsxwriter.xmlwriter

PRIVATE = [
    (xlsxwriter.workbook, "ZipFile"),                          # package.py: the zip class
    (xlsxwriter.workbook.Workbook, "_store_workbook"),
    (xlsxwriter.workbook.Workbook, "_prepare_drawings"),
    (xlsxwriter.worksheet.Worksheet, "_initialize"),
    (xlsxwriter.worksheet.Worksheet, "_write_single_row"),
    (xlsxwriter.worksheet.Worksheet, "_check_dimensions"),
    (xlsxwriter.format.Format, "_get_xf_index"),
    (xlsxwriter.xmlwriter.XMLwriter, "_escape_control_characters"),
    (xlsxwriter.xmlwriter.XMLwriter, "_xml_close"),
    (xlsxwriter.xmlwriter.XMLwriter, "_xml_start_tag"),
    (xlsxwriter.xmlwriter.XMLwriter, "_xml_end_tag"),
    (xlsxwriter.xmlwriter.XMLwriter, "_xml_empty_tag"),
    (xlsxwriter.chart.Chart, "_assemble_xml_file"),
    (xlsxwriter.drawing.Drawing, "_assemble_xml_file"),
    (zipfile.ZipFile, "_writecheck"),
]


@pytest.mark.parametrize("owner, name", PRIVATE,
                         ids=[f"{getattr(o, '__name__', o)}.{n}" for o, n in PRIVATE])
def test_private_name_exists(owner, name):
    assert hasattr(owner, name), f"{owner.__name__}.{name} is gone: see the module docstring"


def test_instance_attributes_the_charts_reset():
    """charts.py re-uses a chart object: it resets these attributes per workbook."""
    book = xlsxwriter.Workbook(None, {"in_memory": True})
    chart = book.add_chart({"type": "scatter"})
    chart.add_series({"categories": "=Table!$A$2:$A$3", "values": "=Table!$B$2:$B$3",
                      "categories_data": [0.0, 1.0], "values_data": [1.0, 2.0]})
    for name in ("fh", "internal_fh", "formula_data", "formula_ids", "already_inserted",
                 "date_1904", "remove_timezone", "id"):
        assert hasattr(chart, name), f"Chart.{name} is gone"
    assert chart.formula_data == [[0.0, 1.0], [1.0, 2.0]]   # the series' cached points
    info = zipfile.ZipInfo("x")
    assert hasattr(info, "_compresslevel"), "ZipInfo._compresslevel is gone"


def test_add_series_still_reads_the_cache_options():
    source = inspect.getsource(xlsxwriter.chart.Chart.add_series)
    for key in ("values_data", "categories_data", "name_data"):
        assert f'"{key}"' in source, f"add_series no longer reads {key}"


def test_the_pinned_range_is_the_installed_version():
    pinned = re.search(r'"XlsxWriter>=([\d.]+),<([\d.]+)"',
                       (Path(__file__).resolve().parents[2] / "pyproject.toml").read_text())
    assert pinned, "XlsxWriter is not pinned to a tested range in pyproject.toml"
    have = tuple(int(x) for x in xlsxwriter.__version__.split(".")[:2])
    low = tuple(int(x) for x in pinned.group(1).split(".")[:2])
    high = tuple(int(x) for x in pinned.group(2).split(".")[:2])
    assert low <= have < high, (xlsxwriter.__version__, pinned.group(0))
