"""A one-sheet workbook of given cells, written with openpyxl and recalculated by
LibreOffice headless: the reference most audit tests compare with."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
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


def same(a, b) -> bool:
    """A LibreOffice-cached value and ours agree: booleans exactly (TRUE is not 1 unless
    both are numbers), numbers to 1e-9 relative (1e-12 absolute), empty and "" alike."""
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b or (isinstance(a, (int, float)) and isinstance(b, (int, float)) and a == b)
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)
    if a in (None, "") and b in (None, ""):
        return True
    return type(a) is type(b) and a == b


def family_disagreements(inputs, result, cases: Sequence[tuple[str, str]], family: str,
                         differs=()) -> list[str]:
    """The cases of ``family`` (row r of sheet Cases, column C, holds case r's formula)
    whose LibreOffice-cached value and our recomputation disagree, ``differs`` left out."""
    wrong = []
    for r, (fam, formula) in enumerate(cases, start=1):
        if fam != family or formula in differs:
            continue
        key = ("Cases", r, 3)
        cached, ours = inputs.cached.get(key), result.values[key]
        if not same(cached, ours):
            wrong.append(f"={formula}: LibreOffice {cached!r}, ours {ours!r}")
    return wrong
