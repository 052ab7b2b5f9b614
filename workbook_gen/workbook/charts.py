"""The Charts sheet: native scatter charts over Table ranges."""

from __future__ import annotations

from ..compute import Evaluated
from .layout import A4, CHARTS, FIRST_ROW, TABLE, TableLayout, add_sheet

_COLUMNS = 2
_ROWS_PER_CHART = 20
_COLS_PER_CHART = 9
# Printing: two rows of two charts per landscape A4 page at 65 % (the grid of 18
# columns and 40 rows is about 14 x 8.3 inches at 100 % in LibreOffice; the page
# leaves 10.3 x 6.8), a page break after every second row of charts, so that no
# chart is cut by a page break.  No fit-to-page: Excel ignores manual page breaks then.
_PRINT_SCALE = 65
_CHART_ROWS_PER_PAGE = 2


def write_charts(workbook, result: Evaluated, layout: TableLayout) -> None:
    sheet = add_sheet(workbook, CHARTS)
    sheet.set_landscape()
    sheet.set_paper(A4)
    sheet.set_print_scale(_PRINT_SCALE)
    pages = -(-len(result.model.charts) // (_COLUMNS * _CHART_ROWS_PER_PAGE))
    sheet.set_h_pagebreaks([p * _CHART_ROWS_PER_PAGE * _ROWS_PER_CHART for p in range(1, pages)])
    sheet.print_area(0, 0, pages * _CHART_ROWS_PER_PAGE * _ROWS_PER_CHART - 1,
                     _COLUMNS * _COLS_PER_CHART - 1)
    model = result.model
    first, last = FIRST_ROW - 1, layout.last_row - 1
    index = {name: i for i, name in enumerate(model.names)}
    template = model.template
    for n, spec in enumerate(model.charts):
        chart = workbook.add_chart({"type": "scatter", "subtype": "straight"})
        x = index[spec.x]
        for y in spec.ys:
            chart.add_series({
                "name": template.quantity(y).header,
                "categories": [TABLE, first, x, last, x],
                "values": [TABLE, first, index[y], last, index[y]],
                "line": {"width": 1.75},
            })
        x_title = (f"{spec.x} [{template.input.unit}]" if spec.x == template.input.name
                   else template.quantity(spec.x).header)
        x_axis = {"name": x_title, "label_position": "low", "major_gridlines": {"visible": True,
                                                       "line": {"color": "#D9D9D9"}}}
        if spec.x == template.input.name:
            sweep = result.scene.sweep
            x_axis.update(min=sweep.start, max=result.inputs[-1])
            if sweep.stop - sweep.start == 360:
                x_axis["major_unit"] = 30
        chart.set_x_axis(x_axis)
        chart.set_y_axis({"name": spec.y_title, "crossing": "min",
                          "major_gridlines": {"visible": True, "line": {"color": "#D9D9D9"}}})
        chart.set_title({"name": spec.title, "name_font": {"size": 12}})
        chart.set_legend({"none": True})
        chart.set_size({"width": 560, "height": 380})
        row, col = divmod(n, _COLUMNS)
        sheet.insert_chart(row * _ROWS_PER_CHART, col * _COLS_PER_CHART, chart)
