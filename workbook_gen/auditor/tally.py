"""The formula cells by verdict, each counted once: agree + disagree + not checked + by
contract = formula cells.

The formula cells are those the file stores with a formula (``AuditInputs.formula_count``):
an array formula counts at its anchor, and once more for each cell of its area that the
file gives an ``<f/>`` of its own; the other cells of its area count with their anchor.
- not checked: not recomputed, reads a cell that is not, or has no cached value to compare
  with (``NO_CACHED_VALUE``);
- by contract: a TODAY/NOW/RAND/RANDBETWEEN cell whose cached value keeps the function's
  contract (one that breaks it disagrees);
- disagree: its cached value (or a cell of its array's area) differs from a
  recalculation, at the source or following from one;
- agree: every other cell that was compared.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import compress, repeat
from operator import is_

Key = tuple[str, int, int]

NO_CACHED_VALUE = ("no cached value: the file holds no value for this formula (saved "
                   "without calculating), so there is nothing to compare with")


@dataclass
class Tally:
    agree: int = 0
    disagree: int = 0
    not_checked: int = 0
    by_contract: int = 0
    disagreements: int = 0  # at their source: an array formula's area once

    @property
    def checked(self) -> int:
        return self.agree + self.disagree + self.by_contract


def absent(cached: dict) -> list[Key]:
    """The cells whose cached value is absent (None: no <v>, or an empty <v/> of a number,
    boolean, error or shared string), not an empty text (a ``str`` cell's ``<v></v>``)."""
    return list(compress(cached, map(is_, cached.values(), repeat(None))))


def tally(inputs, compared, disagreeing, not_checked, contract_ok, disagreements: int) -> Tally:
    """Count the formula cells: ``compared`` the cells compared with their cached value
    (an array's area cell by cell), ``disagreeing`` those that differ (or would show
    another value if recalculated), ``not_checked`` and ``contract_ok`` formula cells.

    One set of the compared cells is made; the others are small (no Python code per
    agreeing cell: a workbook has 200,000 of them)."""
    area = {k for k in inputs.array_cells if inputs.is_formula(k)}
    # a data table's results count with its anchor (the one <f t="dataTable"> cell)
    tables = {cell: (t.sheet, t.row1, t.col1) for t in inputs.data_tables for cell in t.cells()}
    anchors = set(tables.values())

    def counts(key) -> bool:
        return (key in inputs.formulas or key in area or key in inputs.broken
                or key in inputs.opaque or key in anchors)

    fold = {**inputs.array_master, **tables} if tables else inputs.array_master

    def counted_as(key):  # a cell of an array's area without an <f> counts with its anchor
        return key if counts(key) else fold.get(key)

    skipped = {k for k in not_checked if counts(k)}
    disagree = {counted_as(k) for k in disagreeing} - {None} - skipped
    # (an array of draws, RANDARRAY, some cells of which break the contract: disagrees)
    by_contract = {k for k in contract_ok if counts(k)} - skipped - disagree
    counted = set(compared)
    if fold:
        folded = [k for k in fold if k in counted and not counts(k)]
        counted.difference_update(folded)
        counted.update(fold[k] for k in folded)
    agree = len(counted) - len(counted.intersection(disagree | skipped | by_contract))
    return Tally(agree, len(disagree), len(skipped), len(by_contract), disagreements)


def no_cached_findings(inputs, absent: list[Key], cell_name) -> list:
    """``no_cached_value`` findings: one per formula cell without a cached value, or a
    single one when no formula cell has any (a file saved without calculating, as
    openpyxl and pandas write them)."""
    from .structure import Finding
    cells = sorted(k for k in absent if inputs.is_formula(k))
    if not cells:
        return []
    if not any(v is not None for v in inputs.cached.values()):
        writer = inputs.book.application
        return [Finding(cell_name(cells[0]), "no_cached_value",
                        f"none of the {inputs.formula_count} formula cells holds a cached "
                        "value: the file was saved without calculating"
                        + (f" (by {writer})" if writer else "")
                        + "; the recomputed values are not checked against anything")]
    return [Finding(cell_name(k), "no_cached_value",
                    "the file holds no value for this formula: nothing to compare with")
            for k in cells]
