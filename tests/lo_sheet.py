"""A one-sheet workbook of given cells, written with openpyxl and recalculated by
LibreOffice headless: the reference most audit tests compare with."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import openpyxl

from workbook_gen.engines.libreoffice import recalculate


def recalculated_sheet(folder: Path, title: str, cells: Mapping[str, object]) -> Path:
    """``cells`` ({"A1": 3, "B1": "=A1*2", ...}) on sheet ``title`` of a new workbook in
    ``folder``, recalculated by LibreOffice; the path of the recalculated copy."""
    wb = openpyxl.Workbook()
    ws = wb.active
    ws.title = title
    for ref, value in cells.items():
        ws[ref] = value
    source = folder / f"{title.lower()}.xlsx"
    wb.save(source)
    return recalculate(source, folder / "out")
