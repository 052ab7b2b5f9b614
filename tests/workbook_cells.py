"""Read a generated workbook's Table back as columns, for tests."""

from __future__ import annotations

import re

import numpy as np
import openpyxl

from workbook_gen.xlerror import ExcelError

_HEADER = re.compile(r"^(\w+)(?: \[.*\])?$")


def table_columns(path, data_only: bool = True) -> dict[str, list]:
    """{quantity name: [cell value per row]} of the Table sheet (cached values by default)."""
    sheet = openpyxl.load_workbook(path, data_only=data_only, read_only=True)["Table"]
    rows = list(sheet.iter_rows(values_only=True))
    names = [_HEADER.match(h).group(1) for h in rows[0]]
    return {name: [row[i] for row in rows[1:]] for i, name in enumerate(names)}


def as_float(values: list) -> np.ndarray:
    """Numbers as floats; Excel error texts as NaN (the reference's 'no value')."""
    out = []
    for v in values:
        if isinstance(v, str):
            assert ExcelError.from_text(v) is not None, f"unexpected text {v!r}"
            out.append(np.nan)
        else:
            out.append(float(v))
    return np.array(out)
