"""What :func:`evaluate_cells <workbook_gen.evaluator.engine.evaluate_cells>` gives back:
an :class:`Evaluation`, every formula cell's value and operand scale, what could not be
checked and why, and the values column by column for a comparison as arrays
(:meth:`Evaluation.numbers`)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from workbook_gen.evaluator import volatile as vol
from workbook_gen.evaluator.store import Store

Cell = tuple[str, int, int]


@dataclass
class GroupStats:
    vector_groups: int = 0    # runs evaluated as arrays
    vector_cells: int = 0     # formula cells in those runs
    scalar_cells: int = 0     # formula cells evaluated one by one


class CellMap(Mapping):
    """Read-only {(sheet, row, col): value} over the formula cells, backed by the store."""

    def __init__(self, keys: Mapping, getter):
        self._keys, self._get = keys, getter

    def __getitem__(self, key):
        if key not in self._keys:
            raise KeyError(key)
        return self._get(*key)

    def __contains__(self, key):  # without reading the value (Mapping's would)
        return key in self._keys

    @property
    def keyset(self):
        """The keys, for membership tests without a Python call each."""
        return self._keys

    def __iter__(self):
        return iter(self._keys)

    def __len__(self):
        return len(self._keys)


@dataclass
class Evaluation:
    values: Mapping[Cell, object]
    operands_scale: Mapping[Cell, float]
    cycles: list[list[Cell]] = field(default_factory=list)
    unsupported: dict[Cell, list[str]] = field(default_factory=dict)
    # cells among ``unsupported`` whose evaluation took no branch calling one, or that
    # call only unknown names (``unknown``) and cache #NAME? (the value of an unknown
    # name; an add-in's or a macro's function would give another): recomputed
    avoided: set[Cell] = field(default_factory=set)
    unknown: dict[Cell, str] = field(default_factory=dict)  # calling only names Excel
    # lacks: the reason they are not checked
    syntax_errors: dict[Cell, str] = field(default_factory=dict)
    volatile: dict[Cell, list[str]] = field(default_factory=dict)
    external: list[Cell] = field(default_factory=list)
    # every cell that cannot be recomputed or reads one: (sheet, row, col) -> reason
    not_checked: dict[Cell, str] = field(default_factory=dict)
    bad_names: dict[str, str] = field(default_factory=dict)  # name -> why it does not parse
    # cells calling TODAY/NOW/RAND/RANDBETWEEN checked against the function's contract
    # (agreeing or not); those it could not settle are in not_checked
    contract: dict[Cell, vol.Outcome] = field(default_factory=dict)
    groups: GroupStats = field(default_factory=GroupStats)
    seconds: dict[str, float] = field(default_factory=dict)  # grouping, graph, vector, scalar
    store: Store | None = None  # the values column by column, for array-wise comparison
    runs: list = field(default_factory=list)  # (sheet, col, first, last, tree) of every formula

    # -- the values column by column (what the audit compares as arrays) ------------------

    def numbers(self, sheet: str, col: int, rows: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Rows ``rows`` of a column that holds formula cells: (whether each holds a
        number, neither an error nor text, a boolean or nothing; the values, NaN where it
        does not; the operand scales)."""
        return self.store.numbers(sheet, col, rows)

    def column_values(self, sheet: str, col: int, r1: int, r2: int) -> list:
        """The values of rows ``r1..r2`` of a column (constants and formula cells), as
        Python values."""
        return self.store.column_values(sheet, col, r1, r2)

    def clip(self, sheet: str, r1: int, c1: int, r2: int, c2: int
             ) -> tuple[int, int, int, int]:
        """A rectangle of a sheet (named in any case) taller than 65,536 rows or wider
        than 1,024 columns (``A:A``) cut to the sheet's used rows and columns, as the
        evaluator reads it."""
        return self.store.clip(self.store.sheet(sheet), r1, c1, r2, c2)
