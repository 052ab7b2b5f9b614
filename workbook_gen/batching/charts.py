"""The Charts sheet of summary.xlsx: each span and each output's max and min against
every varied parameter (docs/batch.md, summary.xlsx), native scatter charts over the Variants sheet.

- One chart per plotted quantity and varied parameter that is a number (an option that
  takes texts is no axis): one row of charts per quantity, one column per parameter (a
  single one: two charts a row).
- A grid of two names: against each number, one series per value of the other (a
  number or an option's value) when it has at most ``MAX_SERIES_VALUES`` values
  (against the first, from a hidden ChartData sheet sorted by the second; against the
  second, straight from the Variants rows, contiguous per value of the first).
- Max series in reds, min series in blues (dashed), spans in a categorical palette; a
  shape per value of the grouping parameter; a legend below each chart.  Lines join
  the points of a grid where they follow the parameter (one parameter, or a series
  per value of the other); markers only otherwise (random samples, a design file).
"""

from __future__ import annotations

from .rows import figure_columns, snake
from .specs import shown
from .table import Table

MAX_SERIES_VALUES = 8       # a grouping grid parameter with more values: one scatter
_CHART_COLUMNS = 2          # charts a row with one varied parameter
_REDS = ("#C00000", "#FF5050", "#7F0000", "#FF9999", "#E46C0A", "#A50021", "#FF7C80",
         "#5C0000")
_BLUES = ("#1F4E79", "#2E75B6", "#00B0F0", "#9DC3E6", "#203864", "#0070C0", "#7030A0",
          "#00B050")
_PALETTE = ("#1F77B4", "#FF7F0E", "#2CA02C", "#D62728", "#9467BD", "#8C564B", "#E377C2",
            "#7F7F7F")
_SHAPES = ("circle", "square", "diamond", "triangle", "x", "star", "plus", "short_dash")


def plotted(table: Table) -> list[tuple[str, list[str]]]:
    """(title, summary columns) of each chart: the spans (stroke, swing), then each
    output's max and min."""
    charts = []
    for span in table.model.spans:
        q = table.model.template.quantity(span.quantity)
        unit = f" [{q.unit}]" if q.unit else ""
        charts.append((f"{span.label}{unit}", [snake(span.label)]))
    for q in table.model.outputs():
        unit = f" [{q.unit}]" if q.unit else ""
        charts.append((f"{q.name}{unit}: max and min over the sweep",
                       [f"{q.name}_max", f"{q.name}_min"]))
    return charts


def _style(column: str, group: int, line: bool) -> dict:
    """A series' colours, marker and line: max red, min blue, others by group."""
    extreme = column.rsplit("_", 1)[-1] if column.endswith(("_max", "_min")) else ""
    colour = {"max": _REDS, "min": _BLUES}.get(extreme, _PALETTE)[group % 8]
    marker = {"type": _SHAPES[group % len(_SHAPES)], "size": 5,
              "border": {"color": colour}, "fill": {"color": colour}}
    if not line:
        return {"marker": marker, "line": {"none": True}}
    return {"marker": marker, "line": {"color": colour, "width": 1.5,
                                       "dash_type": "dash" if extreme == "min" else "solid"}}


def charts_sheet(book, sheet, table: Table) -> None:
    sheet.set_landscape()
    sheet.fit_to_pages(1, 0)
    design = table.design
    names = list(design.names)
    numbers = [n for n in names if table.kind(n) == "number"]
    if not numbers:  # only options that are texts vary: nothing to draw against
        return
    grid2 = design.kind == "grid" and len(names) == 2
    numeric = set(table.columns) - set(figure_columns(table.model)) | {
        snake(s.label) for s in table.model.spans}
    charts = [(t, cols) for t, cols in plotted(table) if all(c in numeric for c in cols)]
    by_second = None
    if grid2 and names[0] in numbers and len(design.levels[1]) <= MAX_SERIES_VALUES:
        data = book.add_worksheet("ChartData")
        data.hide()
        by_second = _write_groups(data, table, [c for _, cols in charts for c in cols])
    line = design.kind == "grid"
    size = len(design)
    for n, (title, cols) in enumerate(charts):
        for p, x_name in enumerate(numbers):
            x_at = names.index(x_name)
            x = table.columns.index(x_name)
            chart = book.add_chart({"type": "scatter"})  # lines (or none) set per series
            if grid2 and x_at == 0 and by_second is not None:
                _grouped_series(chart, table, cols, names[1], by_second)
            elif grid2 and x_at == 1 and len(design.levels[0]) <= MAX_SERIES_VALUES:
                k = len(design.levels[1])  # the Variants rows of each first value, in order
                by_first = {value: ("Variants", 1 + i * k, (i + 1) * k,
                                    {c: table.columns.index(c) for c in cols}, x,
                                    list(range(i * k, (i + 1) * k)), x_name)
                            for i, value in enumerate(design.levels[0])}
                _grouped_series(chart, table, cols, names[0], by_first)
            else:
                for c in cols:
                    y = table.columns.index(c)
                    chart.add_series({"name": table.headers[y],
                                      "categories": ["Variants", 1, x, size, x],
                                      "values": ["Variants", 1, y, size, y],
                                      "categories_data": _cache(table, x_name),
                                      "values_data": _cache(table, c),
                                      **_style(c, 0, line and len(names) == 1)})
            grid = {"visible": True, "line": {"color": "#D9D9D9"}}
            chart.set_x_axis({"name": table.headers[x], "label_position": "low",
                              "major_gridlines": grid})
            chart.set_y_axis({"crossing": "min", "major_gridlines": grid})
            chart.set_title({"name": title, "name_font": {"size": 11}})
            chart.set_legend({"position": "bottom"})
            chart.set_size({"width": 560, "height": 360})
            if len(numbers) == 1:
                row, col = divmod(n, _CHART_COLUMNS)
            else:
                row, col = n, p
            sheet.insert_chart(row * 19, col * 9, chart)


#: Series of at most this many points cache them in the chart (<c:numCache>), as Excel
#: does, so that a viewer that does not calculate (a file preview) draws them; a larger
#: batch's charts are left for the spreadsheet to fill (their XML would outweigh the data).
CACHED_POINTS = 50_000


def _cache(table: Table, name: str, rows: list[int] | None = None) -> list | None:
    """The points of a series (column ``name``, its ``rows`` or all) as XlsxWriter
    caches them: a number, or None for a cell that holds none (a refused variant).
    A series too long to cache reads no values (a --summary-only table reads them
    back from its Parquet file)."""
    if (len(table.design) if rows is None else len(rows)) > CACHED_POINTS:
        return None
    column = table.data[name]
    values = list(column) if rows is None else [column[i] for i in rows]
    return [v if isinstance(v, (int, float)) and not isinstance(v, bool) and v == v else None
            for v in values]


def _level(value: object) -> str:
    return f"{value:g}" if isinstance(value, float) else str(shown(value))


def _grouped_series(chart, table: Table, cols: list[str], g_name: str, groups: dict) -> None:
    """One series per value of the grouping parameter and plotted column; ``groups``:
    value -> (sheet, first row, last row, column of each plotted name, x column, the
    variants' indices in those rows, the x parameter's name)."""
    for g, (value, (sheet_name, first, last, col_of, x, rows, x_name)) \
            in enumerate(groups.items()):
        for c in cols:
            extreme = c.rsplit("_", 1)[-1] if c.endswith(("_max", "_min")) else ""
            chart.add_series({
                "name": f"{extreme + ', ' if extreme else ''}{g_name} = {_level(value)}",
                "categories": [sheet_name, first, x, last, x],
                "values": [sheet_name, first, col_of[c], last, col_of[c]],
                "categories_data": _cache(table, x_name, rows),
                "values_data": _cache(table, c, rows),
                **_style(c, g, True)})


def _write_groups(sheet, table: Table, wanted: list[str]):
    """The data of a two-parameter grid sorted by the second parameter, so each of its
    values is a contiguous range (a chart series against the first)."""
    design = table.design
    x_name, g_name = design.names
    sheet.write_row(0, 0, [x_name] + wanted)
    col_of = {c: i + 1 for i, c in enumerate(wanted)}
    groups = {}
    row = 1
    k = len(design.levels[1])
    for j, value in enumerate(design.levels[1]):
        first = row
        indices = [i * k + j for i in range(len(design.levels[0]))]
        for i in range(len(design.levels[0])):
            index = i * k + j
            sheet.write_number(row, 0, table.data[x_name][index])
            for c in wanted:
                v = table.data[c][index]
                if isinstance(v, (int, float)) and v == v and v is not None:
                    sheet.write_number(row, col_of[c], v)
            row += 1
        groups[value] = ("ChartData", first, row - 1, col_of, 0, indices, x_name)
    return groups
