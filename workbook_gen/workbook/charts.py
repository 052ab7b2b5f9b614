"""The Charts sheet: native scatter charts over Table ranges."""

from __future__ import annotations

import functools
import re
import threading
from functools import partial

import numpy as np

from ..cellref import a1
from ..tabulate import Evaluated
from .layout import A4, CHARTS, FIRST_ROW, TABLE, TableLayout, add_sheet
from .xlsxwriter_internals import (assemble_xml, assembly, replace_assembly, reuse_chart,
                                   write_xml)

_COLUMNS = 2
_ROWS_PER_CHART = 20
_COLS_PER_CHART = 9
# Printing: two rows of two charts per landscape A4 page at 65 % (the grid of 18
# columns and 40 rows is about 14 x 8.3 inches at 100 % in LibreOffice; the page
# leaves 10.3 x 6.8), a page break after every second row of charts, so that no
# chart is cut by a page break.  No fit-to-page: Excel ignores manual page breaks then.
_PRINT_SCALE = 65
_CHART_ROWS_PER_PAGE = 2


# The XML of a chart is a function of what it was given (series, axes, title, ...) and of
# its id in the workbook (its axis ids): the same for every design variant of a scene
# (the sheet's cells are not cached in the chart in constant_memory mode).  Each
# process keeps the XML it assembled, by those, instead of assembling it again.


# Each series' points, cached in the chart (<c:numCache>) as the cells hold them, so that
# a viewer that does not calculate (file previews, web viewers) draws the chart.  The XML
# kept above has none; they are spliced in after each <c:f> range, per workbook.
_RANGE = re.compile(r"<c:f>([^<]*)</c:f>(?:<c:numCache>.*?</c:numCache>)?</c:numRef>")


def _num_cache(values: np.ndarray, errors: np.ndarray) -> str:
    """A <c:numCache> of the column: a point per number, none where the cell holds an
    error (as Excel writes it)."""
    points = "".join(f'<c:pt idx="{i}"><c:v>{v!r}</c:v></c:pt>'
                     for i, (v, bad) in enumerate(zip(values.tolist(), errors.tolist()))
                     if not bad)
    return (f'<c:numCache><c:formatCode>General</c:formatCode>'
            f'<c:ptCount val="{len(values)}"/>{points}</c:numCache>')


def _with_caches(xml: str, caches: dict[str, str]) -> str:
    def cached(m: re.Match) -> str:
        found = caches.get(m.group(1))
        return m.group(0) if found is None else f"<c:f>{m.group(1)}</c:f>{found}</c:numRef>"
    return _RANGE.sub(cached, xml)


def _assemble_cached(chart, key: str, configure=None, caches=None) -> None:
    """The chart's XML, from the XML kept for ``key`` and its id, with the
    series' ``caches`` spliced in; ``configure()`` (the axes, title and legend, which only
    the XML reads) is called first when the XML must be assembled."""
    kept_xml = _kept().xml
    found = kept_xml.get((key, chart.id))
    if found is None:
        if configure is not None:
            configure()
        found = assemble_xml(chart)
        kept_xml[(key, chart.id)] = found
    write_xml(chart, _with_caches(found, caches or {}))


# The chart objects themselves, kept per thread by their position and key: building a
# chart (XlsxWriter's defaults, axes, series) costs more than its kept XML.  Nothing of a
# chart depends on the workbook it goes into but its id (set when packaged), the ranges'
# cached data (none in constant_memory mode: reset to "not gathered") and the flag that
# it is inserted.  Per thread: a chart is used by one workbook at a time.
# A kept chart is only ever assembled once: XlsxWriter counts up while it assembles (series
# idx, axis ids, axis titles' rotation), so the kept XML and the kept charts are dropped
# together, and only between workbooks (``_kept(fresh=True)``), never while one is packaged.
_KEPT = threading.local()
_KEPT_LIMIT = 256


def _kept(fresh: bool = False):
    """This thread's kept charts (``.charts``) and their XML (``.xml``); ``fresh``: before
    a workbook's charts, drop both when either has grown past its limit."""
    if not hasattr(_KEPT, "xml") or (fresh and (len(_KEPT.charts) >= _KEPT_LIMIT
                                                 or len(_KEPT.xml) >= 2 * _KEPT_LIMIT)):
        _KEPT.charts, _KEPT.xml = {}, {}
    return _KEPT


def _kept_chart(workbook, n: int, key: str, caches: dict[str, str]):
    """The chart kept for (n, key), added to ``workbook`` as ``add_chart`` adds one, with
    this workbook's series ``caches``, or None."""
    chart = _kept().charts.get((n, key))
    if chart is None or not reuse_chart(workbook, chart):
        return None
    assembly(chart).keywords["caches"] = caches
    return chart


def _keep_chart(n: int, key: str, chart) -> None:
    _kept().charts[(n, key)] = chart


def write_charts(workbook, result: Evaluated, layout: TableLayout) -> None:
    _kept(fresh=True)
    sheet = add_sheet(workbook, CHARTS)
    sheet.set_landscape()
    sheet.set_paper(A4)
    sheet.set_print_scale(_PRINT_SCALE)
    pages = -(-len(result.model.charts) // (_COLUMNS * _CHART_ROWS_PER_PAGE))
    if not pages:  # no output asked for is charted: no print area (rows 1..0 are no range)
        sheet.write_string(0, 0, "No chart: none of the scene's outputs is plotted by the "
                                 "template's charts.")
        return
    sheet.set_h_pagebreaks([p * _CHART_ROWS_PER_PAGE * _ROWS_PER_CHART for p in range(1, pages)])
    sheet.print_area(0, 0, pages * _CHART_ROWS_PER_PAGE * _ROWS_PER_CHART - 1,
                     _COLUMNS * _COLS_PER_CHART - 1)
    model = result.model
    first, last = FIRST_ROW - 1, layout.last_row - 1
    index = {name: i for i, name in enumerate(model.names)}
    template = model.template
    @functools.cache
    def cache(i: int) -> str:
        """Column i's <c:numCache>, formatted once per workbook (the charts share the
        input column and some outputs)."""
        if i == 0:
            values = np.asarray(result.inputs, dtype=float)
            return _num_cache(values, np.zeros(len(values), dtype=bool))
        column = result.columns[model.names[i]]
        return _num_cache(np.asarray(column.val, dtype=float), column.err != 0)

    for n, spec in enumerate(model.charts):
        kind = {"type": "scatter", "subtype": "straight"}
        x = index[spec.x]
        caches = {_range(first, i, last): cache(i) for i in [x] + [index[y] for y in spec.ys]}
        series = [{
            "name": template.quantity(y).header,
            "categories": [TABLE, first, x, last, x],
            "values": [TABLE, first, index[y], last, index[y]],
            "line": {"width": 1.75},
        } for y in spec.ys]
        x_title = (f"{spec.x} [{template.input.unit}]" if spec.x == template.input.name
                   else template.quantity(spec.x).header)
        # Both axes cross at the other's minimum, their labels outside the plot: a path
        # chart's x runs through 0 mid-plot, and so does a sweep from -540 to 0.
        x_axis = {"name": x_title, "label_position": "low", "crossing": "min",
                  "major_gridlines": {"visible": True, "line": {"color": "#D9D9D9"}}}
        if spec.x == template.input.name:
            sweep = result.scene.sweep
            x_axis.update(min=sweep.start, max=result.inputs[-1])
            if sweep.stop - sweep.start == 360:
                x_axis["major_unit"] = 30
        y_axis = {"name": spec.y_title, "crossing": "min", "label_position": "low",
                  "major_gridlines": {"visible": True, "line": {"color": "#D9D9D9"}}}
        title = {"name": spec.title, "name_font": {"size": 12}}
        # a legend names the series where there are several (theta_3 and theta_4, vx and vy)
        legend = {"position": "bottom"} if len(series) > 1 else {"none": True}
        size = {"width": 560, "height": 380}
        # everything the chart is given, as text: its key in the kept XML (with its id)
        key = repr((kind, series, x_axis, y_axis, title, legend, size))
        row, col = divmod(n, _COLUMNS)
        chart = _kept_chart(workbook, n, key, caches)
        if chart is not None:
            sheet.insert_chart(row * _ROWS_PER_CHART, col * _COLS_PER_CHART, chart)
            continue
        chart = workbook.add_chart(kind)
        for options in series:
            chart.add_series(dict(options))
        chart.set_size(size)

        def configure(chart=chart, x_axis=x_axis, y_axis=y_axis, title=title, legend=legend):
            chart.set_x_axis(x_axis)
            chart.set_y_axis(y_axis)
            chart.set_title(title)
            chart.set_legend(legend)
        if any(str(o.get("name", "")).startswith("=") for o in (x_axis, y_axis, title)):
            configure()   # a formula name is chart data the workbook gathers before
            configure = None
        else:
            _keep_chart(n, key, chart)
        replace_assembly(chart, partial(_assemble_cached, chart, key, configure,
                                        caches=caches))
        sheet.insert_chart(row * _ROWS_PER_CHART, col * _COLS_PER_CHART, chart)


def _range(first: int, col: int, last: int) -> str:
    """The series range as XlsxWriter writes it in <c:f>: Table!$A$2:$A$38."""
    return f"{TABLE}!{a1(first + 1, col + 1, True)}:{a1(last + 1, col + 1, True)}"
