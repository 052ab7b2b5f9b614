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


def column_error(name: str, ours: np.ndarray, ref: np.ndarray,
                 assembled: np.ndarray | None = None, always_defined=()) -> float:
    """Worst |ours - ref| over the column's magnitude, after checking that both hold
    values in the same rows and that ours holds an error wherever nothing assembles
    (unless the column is defined regardless, like the crank pin)."""
    assert np.array_equal(np.isfinite(ours), np.isfinite(ref)), name
    if assembled is not None and name not in always_defined:
        assert np.all(np.isnan(ours[~assembled])), name
    both = np.isfinite(ours)
    if not both.any():
        return 0.0
    scale = max(float(np.max(np.abs(ref[both]))), 1e-300)
    return float(np.max(np.abs(ours[both] - ref[both])) / scale)
