"""Which formula cells cannot be recomputed, and which depend on such a cell.

A cell is a *source* when the evaluator cannot compute it (an unsupported function,
a formula that does not parse, an external reference, a circular reference, a defined
name that does not parse, a function whose value changes at every recalculation). A
cell that reads a source, directly or through other cells, is *not checked* as well:
its recomputed value says nothing about its own formula. The reads are followed at
cell precision inside a block of rows: ``SUM($A$1:A5)`` filled down is tainted only
from the row where its range first covers a source.
"""

from __future__ import annotations

from collections import defaultdict
from typing import NamedTuple


class Shape(NamedTuple):
    """A rectangle a formula reads, as seen from the first row of its block: rows
    ``row1..row2`` move down with the block where ``rel1``/``rel2`` are set."""

    sheet: str
    row1: int
    col1: int
    row2: int
    col2: int
    rel1: bool
    rel2: bool


class Taint:
    """Row intervals of each (sheet, column) that hold a not-checked cell, each with the
    source cell it comes from (the first one found)."""

    def __init__(self):
        self.intervals: dict[tuple[str, int], list[tuple[int, int, tuple]]] = defaultdict(list)
        self.cols: dict[str, set[int]] = defaultdict(set)

    def __bool__(self) -> bool:
        return bool(self.intervals)

    def add(self, sheet: str, col: int, first: int, last: int, origin: tuple) -> None:
        self.intervals[(sheet, col)].append((first, last, origin))
        self.cols[sheet].add(col)

    def hits(self, shape: Shape, n: int) -> list[tuple[int, int, tuple]]:
        """Offsets ``i0..i1`` (within ``0..n-1``) of the block rows whose rectangle
        covers a tainted cell, each with that cell's origin."""
        out = []
        cols = self.cols.get(shape.sheet)
        if not cols:
            return out
        for col in cols:
            if not shape.col1 <= col <= shape.col2:
                continue
            for t1, t2, origin in self.intervals[(shape.sheet, col)]:
                lo, hi = 0, n - 1
                # row1 + i*rel1 <= t2  and  row2 + i*rel2 >= t1
                if shape.rel1:
                    hi = min(hi, t2 - shape.row1)
                elif shape.row1 > t2:
                    continue
                if shape.rel2:
                    lo = max(lo, t1 - shape.row2)
                elif shape.row2 < t1:
                    continue
                if lo <= hi:
                    out.append((lo, hi, origin))
        return out
