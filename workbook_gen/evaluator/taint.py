"""Which formula cells cannot be recomputed, and which depend on such a cell.

A cell is a *source* when the evaluator cannot compute it (an unsupported function,
a formula that does not parse, an external reference, a circular reference, a defined
name that does not parse, a function whose value changes at every recalculation). A
cell that reads a source, directly or through other cells, is *not checked* as well:
its recomputed value says nothing about its own formula. The reads are followed at
cell precision inside a block of rows: ``SUM($A$1:A5)`` filled down is tainted only
from the row where its range first covers a source.

The consistency rule: a not-checked cell whose value the file caches passes no taint on.
Excel computed every cell in one recalculation, so the cached values are mutually
consistent: a reader recomputed from the cached value of a cell we cannot recompute (a
VBA function, an external reference, a LAMBDA we cannot evaluate, a cell reading such a
cell) is checked exactly as a reader of a constant typed there would be. A disagreement
it finds is a real one (the reader's formula does not give its cached value from the
cached values it reads); an agreement says the reader's formula is consistent with its
inputs, nothing about the unrecomputed cell, which stays "not checked" itself. A cell
without a cached value taints its readers as before.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Callable, Mapping
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

    def __init__(self, cached: Mapping | None = None,
                 put: Callable[[tuple, object], None] | None = None):
        self.intervals: dict[tuple[str, int], list[tuple[int, int, tuple]]] = defaultdict(list)
        self.cols: dict[str, set[int]] = defaultdict(set)
        self.cached = cached if put is not None else None  # (sheet, row, col) -> value
        self.put = put
        self.pending: list[tuple[tuple, object]] = []  # held cells, their values not yet put

    def mark(self, cell: tuple, origin: tuple) -> None:
        """``cell`` (sheet, row, col) is not checked because of ``origin``: it holds its
        cached value for its readers (the consistency rule), or taints them if it has
        none."""
        value = None if self.cached is None else self.cached.get(cell)
        if value is None:
            self.add(cell[0], cell[2], cell[1], cell[1], origin)
        else:
            self.pending.append((cell, value))

    def flush(self) -> None:
        """Put the held cells' cached values (after their own evaluation wrote theirs)."""
        for cell, value in self.pending:
            self.put(cell, value)
        self.pending.clear()

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
                # row i reads rows a_i..b_i in either order (B1:B$3 filled down past
                # row 3 is B3:B4, B3:B5 ...): it covers t1..t2 when one end is <= t2
                # (rows up to a last one) and one end is >= t1 (rows from a first one)
                hi = min(n - 1, max(_last_at_most(shape.row1, shape.rel1, t2, n),
                                    _last_at_most(shape.row2, shape.rel2, t2, n)))
                lo = max(0, min(_first_at_least(shape.row1, shape.rel1, t1, n),
                                _first_at_least(shape.row2, shape.rel2, t1, n)))
                if lo <= hi:
                    out.append((lo, hi, origin))
        return out


def _last_at_most(row: int, rel: bool, bound: int, n: int) -> int:
    """The last offset i (-1 if none) at which ``row`` (moving down with i if ``rel``)
    is at most ``bound``."""
    if rel:
        return bound - row
    return n - 1 if row <= bound else -1


def _first_at_least(row: int, rel: bool, bound: int, n: int) -> int:
    """The first offset i (``n`` if none) at which ``row`` is at least ``bound``."""
    if rel:
        return bound - row
    return 0 if row >= bound else n
