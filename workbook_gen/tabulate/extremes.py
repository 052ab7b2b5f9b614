"""Extremes of a Table column over its ok rows, and where they occur: the one rule of the
workbook's Summary (docs/workbook.md, Summary), the batch summary and the tradeoff (a
flagged row, a toggle, a dead centre, a row not converged or one that cannot be assembled,
never sets an extreme).

A row counts when its status is ``ok`` and the column holds a number there.  The
location is the input of the first such row that holds the extreme, which is what the
Summary's ``INDEX(inputs, MATCH(1, (column=extreme)*(status="ok"), 0))`` finds.
``ok_extremes`` takes one variant's rows (the workbook) or many variants' at once
(``--summary-only``), with the same code.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .table import STATUS_OK as OK
from .table import Table


@dataclass(frozen=True)
class Extremes:
    """Per variant (one entry each): the extremes and their inputs, NaN where no row
    counts, how many rows counted, and the rows (within the variant) holding the
    extremes (0 where no row counts)."""

    lo: np.ndarray
    lo_at: np.ndarray
    hi: np.ndarray
    hi_at: np.ndarray
    counted: np.ndarray
    lo_row: np.ndarray
    hi_row: np.ndarray


def ok_rows(status: np.ndarray) -> np.ndarray:
    """True where a row's status text is ``ok``."""
    return np.asarray(status, dtype=object) == OK


def ok_extremes(val: np.ndarray, err: np.ndarray, status: np.ndarray, inputs: np.ndarray,
                variants: int = 1) -> Extremes:
    """``val``/``err``: a column of ``variants`` blocks of ``len(inputs)`` rows;
    ``status``: the rows' status texts, in the same order."""
    n = len(inputs)
    counts = (np.asarray(err).reshape(variants, n) == 0) \
        & ok_rows(status).reshape(variants, n)
    val = np.asarray(val, dtype=float).reshape(variants, n)
    any_row = counts.any(axis=1)
    lo_val = np.where(counts, val, np.inf)
    hi_val = np.where(counts, val, -np.inf)
    i_lo, i_hi = np.argmin(lo_val, axis=1), np.argmax(hi_val, axis=1)
    each, nan = np.arange(variants), np.full(variants, np.nan)
    return Extremes(np.where(any_row, lo_val[each, i_lo], nan),
                    np.where(any_row, inputs[i_lo], nan),
                    np.where(any_row, hi_val[each, i_hi], nan),
                    np.where(any_row, inputs[i_hi], nan),
                    counts.sum(axis=1), i_lo, i_hi)


def output_extremes(table: Table) -> dict[str, Extremes]:
    """The extremes of each output column of one scene's Table, by name."""
    found = {}
    for q in table.model.outputs():
        column = table.columns[q.name]
        found[q.name] = ok_extremes(column.val, column.err, table.status, table.inputs)
    return found
