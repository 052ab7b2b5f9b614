"""The Parameters and About sheets."""

from __future__ import annotations

import json

from ..tabulate import Evaluated
from .layout import (ABOUT, LINE_HEIGHT, PARAMETERS, add_sheet, excel_text, print_wide,
                     wrapped_lines)

_DESCRIPTION_WIDTH = 60  # characters: the Parameters sheet's descriptions wrap within it
_VALUE_WIDTH = 100  # characters: the About sheet's values wrap within it


def write_parameters(workbook, formats, result: Evaluated) -> None:
    sheet = add_sheet(workbook, PARAMETERS)
    for c, text in enumerate(("Name", "Value", "Unit", "Description")):
        sheet.write_string(0, c, text, formats["header"])
    sheet.set_column(0, 0, 12)
    sheet.set_column(1, 1, 20)
    sheet.set_column(2, 2, 8)
    sheet.set_column(3, 3, _DESCRIPTION_WIDTH)
    sheet.freeze_panes(1, 0)
    print_wide(sheet, 0)
    row = 0
    for row, spec in enumerate(result.scene.template.parameters, start=1):
        sheet.write_string(row, 0, spec.name)
        sheet.write_number(row, 1, result.scene.parameters[spec.name], formats["param"])
        sheet.write_string(row, 2, spec.unit)
        sheet.write_string(row, 3, spec.description)
        workbook.define_name(spec.name, f"={PARAMETERS}!$B${row + 1}")
    for row, item in enumerate(result.scene.template.derived, start=row + 1):
        sheet.write_string(row, 0, item.name)
        sheet.write_formula(row, 1, excel_text(item.expr), None, result.derived[item.name])
        sheet.write_string(row, 2, item.unit)
        # wrapped within the column: a longer line would widen the printed page
        text = f"{item.description} (computed from the parameters above)"
        sheet.write_string(row, 3, text, formats["wrap"])
        lines = wrapped_lines(text, _DESCRIPTION_WIDTH)
        if lines > 1:
            sheet.set_row(row, LINE_HEIGHT * lines)
        workbook.define_name(item.name, f"={PARAMETERS}!$B${row + 1}")


def write_about(workbook, formats, result: Evaluated, version: str, filename: str) -> None:
    sheet = add_sheet(workbook, ABOUT)
    scene = result.scene
    sheet.set_column(0, 0, 22)
    sheet.set_column(1, 1, _VALUE_WIDTH)
    print_wide(sheet)
    sheet.write_string(0, 0, scene.title, formats["title"])
    rows = [
        ("mechanism", scene.template.id),
        ("options", json.dumps(dict(scene.options), sort_keys=True)),
        ("generator", f"workbook-gen {version}"),
        ("scene file", scene.source),
        ("overrides", " ".join(scene.overrides) or "none"),
        ("sweep", f"{scene.sweep.start:g} to {scene.sweep.stop:g} by {scene.sweep.step:g} "
                  f"{scene.template.input.unit} ({result.rows} rows)"),
        ("outputs", ", ".join(scene.outputs)),
        ("audit", f"workbook-gen audit {filename}"),
        ("units", "lengths in the scene's unit (mm unless stated), input angles in degrees, "
                  "formulas in radians, angular rates in rad/s and rad/s^2"),
    ]
    for r, (key, value) in enumerate(rows, start=2):
        sheet.write_string(r, 0, key, formats["label"])
        # wrapped: a five-bar's 74 outputs ran 700 characters to the right, and the
        # sheet, fitted to the page width, printed at 2 pt
        sheet.write_string(r, 1, value, formats["note"])
        lines = wrapped_lines(value, _VALUE_WIDTH)
        if lines > 1:
            sheet.set_row(r, LINE_HEIGHT * lines)
    r = len(rows) + 3
    sheet.write_string(r, 0, "scene as given", formats["label"])
    for i, line in enumerate(scene.text.splitlines()):
        sheet.write_string(r + i, 1, line)
