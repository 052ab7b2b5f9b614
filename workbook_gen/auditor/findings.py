"""Findings: the mistakes spreadsheet checkers look for, beside cached-against-recomputed.

Each finding names a cell, a kind and a message; none fails the audit on its own.

- ``inconsistent_formula``: a formula whose R1C1 form differs from the formulas on both
  sides of it in its column (or row), which agree with each other. As Excel's background
  check "formula inconsistent with formulas in the region" and ExceLint's comparison of
  reference shapes with the neighbours', with three guards against false alarms: the cell
  must sit *inside* a run (a change of formula at a run's end is a block boundary), it
  must not agree with its own neighbours the other way (a subtotal row across a table is
  deliberate), and a pattern that alternates (A B A B) is a layout, not a slip.
- ``constant_in_formula_run``: a number typed where the cells on both sides hold the same
  formula (an overwritten formula).
- ``formula_omits_adjacent_cells``: SUM, AVERAGE, MIN, MAX, ... over a range of one row or
  column that stops next to another number of the same block (same kind of cell: a
  constant beside constants, or the same formula beside the range's last formula).
- ``number_stored_as_text``: a text constant that reads as a number, where numbers are
  expected (inside a range an aggregate reads, which skips text, or among numbers).
- ``reference_to_empty_cell``: a formula that uses the value of an empty cell that lies
  in an empty column of its sheet, or outside the sheet's used range (a test such
  as ISBLANK, IF's condition or ``=""`` is not a use). An empty cell amid filled rows and
  columns is most often an input left blank on purpose (Excel's own check for this is off
  by default for that reason): not reported.
- ``error_value``: a cell whose value is an error, reported where the error starts, with
  the cells it spoils (that show an error only because they read it).
"""

from __future__ import annotations

import math
import re
from collections import defaultdict
from itertools import compress
from operator import itemgetter

from ..evaluator.store import type_mask
from ..formula import ast
from ..cellref import column_letters
from ..xlerror import ExcelError
from .grid import ERROR, FORMULA, NUMBER, TEXT, Grid, Key, value_kind
from .grid import show_value
from .structure import Finding

_ERROR = frozenset({ExcelError})

KINDS = ("inconsistent_formula", "constant_in_formula_run", "formula_omits_adjacent_cells",
         "number_stored_as_text", "reference_to_empty_cell", "error_value")

AGGREGATES = frozenset({
    "SUM", "AVERAGE", "AVERAGEA", "MIN", "MAX", "MINA", "MAXA", "COUNT", "PRODUCT", "MEDIAN",
    "STDEV", "STDEV.S", "STDEV.P", "STDEVA", "STDEVP", "VAR", "VAR.S", "VAR.P", "VARP",
    "SUMSQ", "GEOMEAN", "HARMEAN", "SUBTOTAL", "AGGREGATE", "MODE", "MODE.SNGL",
})
_NUMERIC_TEXT = re.compile(
    r"\s*[+-]?(?:(?:\d{1,3}(?:,\d{3})+|\d+)(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?%?\s*")
_LEADING_ZERO = re.compile(r"\s*[+-]?0\d")
MAX_SPOILED_LISTED = 5


def find(inputs, runs, cell_name) -> list[Finding]:
    """Every finding of the workbook (``runs``: the evaluator's runs of formulas)."""
    grid = Grid(inputs, runs)
    checks = _Checks(grid, cell_name)
    checks.shapes()
    checks.ranges_and_references()
    checks.numbers_as_text()
    checks.errors()
    return checks.findings


def _segments(tokens: dict, cells: list[Key], along: int) -> list[tuple[int, int, tuple]]:
    """Runs of adjacent cells of a line (sorted along index ``along``) with one token."""
    out: list[list] = []
    last = None
    for key in cells:
        pos, token = key[along], tokens[key]
        if last is not None and last[1] == pos - 1 and last[2] == token:
            last[1] = pos
        else:
            last = [pos, pos, token]
            out.append(last)
    return out


class _Checks:
    def __init__(self, grid: Grid, cell_name):
        self.grid, self.name = grid, cell_name
        self.findings: list[Finding] = []
        self.flagged: set[tuple[str, Key]] = set()
        self.aggregate_ranges: list[tuple[str, int, int, int, int]] = []

    def add(self, kind: str, key: Key, message: str) -> None:
        if (kind, key) not in self.flagged:
            self.flagged.add((kind, key))
            self.findings.append(Finding(cell=self.name(key), kind=kind, message=message))

    def text(self, key: Key) -> str:
        grid = self.grid
        if key in grid.formulas:
            return "=" + grid.formulas[key]
        value = grid.constants.get(key)
        return show_value(value)

    # inconsistent_formula, constant_in_formula_run -----------------------------------
    def token(self, key: Key):
        """What a cell is, for comparing neighbours: a formula's R1C1 form or its kind;
        None for an empty cell."""
        grid = self.grid
        if key in grid.array:
            return (FORMULA, key)  # a cell an array formula fills: equal to nothing
        run = grid.run_index(key)
        if run is not None:
            return (FORMULA, grid.key_of_run[run])
        if key in grid.formulas:
            return (FORMULA, key)  # unparsed: equal to nothing
        if key in grid.constants:
            return (value_kind(grid.constants[key]),)
        return None

    def shapes(self) -> None:
        """Down each column, from the runs (a run is a stretch of one formula) and the
        constants; along rows, around the cells that could differ from both sides (a
        formula in a run of two or more rows agrees with the row above or below)."""
        grid = self.grid
        columns: dict[tuple[str, int], list] = defaultdict(list)
        for i, run in enumerate(grid.runs):
            columns[(run.sheet, run.col)].append([run.first, run.last,
                                                  (FORMULA, grid.key_of_run[i])])
        for key in grid.unparsed:
            columns[(key[0], key[2])].append([key[1], key[1], (FORMULA, key)])
        candidates = [(run.sheet, run.first, run.col) for run in grid.runs
                      if run.first == run.last]
        for key in grid.constants:
            token = self.token(key)
            columns[(key[0], key[2])].append([key[1], key[1], token])
            if token[0] == NUMBER:
                candidates.append(key)
        for (sheet, col), items in columns.items():
            if len(items) < 3 and sum(b - a + 1 for a, b, _ in items) < 3:
                continue
            items.sort(key=itemgetter(0))
            segments = [items[0]]
            for item in items[1:]:
                last = segments[-1]
                if item[0] == last[1] + 1 and item[2] == last[2]:
                    last[1] = item[1]
                else:
                    segments.append(item)
            sample = (sheet, 0, col)
            for i in range(1, len(segments) - 1):
                self._check(segments, i, sample, 1)
        for key in candidates:
            sheet, row, col = key
            window = [(sheet, row, c) for c in range(max(1, col - 6), col + 7)]
            tokens = {k: t for k in window if (t := self.token(k)) is not None}
            segments = _segments(tokens, list(tokens), 2)
            i = next(n for n, seg in enumerate(segments) if seg[0] <= col <= seg[1])
            if 0 < i < len(segments) - 1:
                self._check(segments, i, key, 2)

    def _check(self, segments, i: int, sample: Key, along: int) -> None:
        """Is segment ``i`` of a line a slip inside the run around it?"""
        n = len(segments)
        before, this, after = segments[i - 1], segments[i], segments[i + 1]
        if not (before[1] == this[0] - 1 and after[0] == this[1] + 1):
            return
        if before[2] != after[2] or before[2][0] != FORMULA or this[2] == before[2]:
            return
        length = this[1] - this[0] + 1
        sizes = (before[1] - before[0] + 1, after[1] - after[0] + 1)
        # alternating layouts: the same token two segments away, adjacent
        if (i >= 2 and segments[i - 2][2] == this[2] and segments[i - 2][1] == before[0] - 1) \
                or (i + 2 < n and segments[i + 2][2] == this[2]
                    and segments[i + 2][0] == after[1] + 1):
            return
        if along == 1:   # down a column
            if length > 2 or (length == 2 and min(sizes) < 2):
                return
        elif length > 1 or sum(sizes) < 3:   # along a row: stricter, rows mix quantities
            return
        for pos in range(this[0], this[1] + 1):
            key = _at(sample, along, pos)
            self._shape_finding(key, this[2], along, before, after)

    def _shape_finding(self, key: Key, token, along: int, before, after) -> None:
        grid = self.grid
        across = 2 if along == 1 else 1
        side = [_step(key, across, -1), _step(key, across, 1)]
        where = "above and below" if along == 1 else "left and right"
        neighbour = _at(key, along, before[1])
        if token[0] == FORMULA:
            if any(self.token(k) == token for k in side):
                return  # the same formula the other way: a row (column) of its own
            if not self._has_refs(key) and not self._has_refs(neighbour):
                return  # constant expressions (=2*3.5): values typed as formulas
            if self._row_differs(key, along, before, after):
                return  # its row (column) is laid out differently: a block boundary
            other = grid.r1c1(neighbour)
            self.add("inconsistent_formula", key,
                     f"{self.text(key)} differs from the formulas {where} it "
                     f"({self.text(neighbour)} in R1C1 {other}; this one is {token[1]})")
        elif token[0] == NUMBER:
            if along == 2 and any(grid.kind(k) == NUMBER for k in side):
                return  # a column of numbers crossing a row of formulas
            self.add("constant_in_formula_run", key,
                     f"the number {self.text(key)} is typed where the cells {where} it hold "
                     f"the same formula ({self.text(neighbour)}): an overwritten formula?")

    def _has_refs(self, key: Key) -> bool:
        return next(self.grid.refs(key), None) is not None

    def _row_differs(self, key: Key, along: int, before, after) -> bool:
        """Does the cell's row (for a column run) hold other kinds of cells beside it than
        the rows above and below do? Then it is a row of another block (a group's total
        row inside a list of items), not a slip."""
        grid = self.grid
        across = 2 if along == 1 else 1
        up, down = _at(key, along, before[1]), _at(key, along, after[0])
        for by in (-1, 1):
            mine = grid.kind(_step(key, across, by))
            theirs = grid.kind(_step(up, across, by)), grid.kind(_step(down, across, by))
            if theirs[0] == theirs[1] and mine != theirs[0]:
                return True
        return False

    # formula_omits_adjacent_cells, reference_to_empty_cell -------------------------------
    def ranges_and_references(self) -> None:
        grid = self.grid
        omits: list = []
        for run in grid.runs:
            home = run.sheet
            first_key = (home, run.first, run.col)
            refs = list(grid.refs(first_key))
            if not refs:
                continue
            length = run.last - run.first + 1
            for ref in refs:
                moves = _row_relative(ref.node)
                if ref.single:
                    if not ref.guarded:
                        self._empty(run, ref, moves)
                    continue
                if ref.function not in AGGREGATES:
                    continue
                top = ref.r2 + (length - 1 if moves else 0)
                self.aggregate_ranges.append((ref.sheet, ref.r1, ref.c1, top, ref.c2))
                if ref.guarded or (moves and length > 1 and ref.c1 == ref.c2):
                    continue  # a moving window or a running total down its own run
                for dr in range(length):
                    r1, r2 = (ref.r1 + dr, ref.r2 + dr) if moves else (ref.r1, ref.r2)
                    omits.append(((home, run.first + dr, run.col), ref, r1, r2))
        by_sheet: dict[str, list] = defaultdict(list)
        for sheet, *rect in self.aggregate_ranges:
            by_sheet[sheet].append(rect)
        for key, ref, r1, r2 in omits:
            self._omits(key, ref, r1, r2, by_sheet[ref.sheet])

    def _empty(self, run, ref, moves: bool) -> None:
        """The run's cells whose reference ``ref`` lands on a notable empty cell."""
        grid = self.grid
        if ref.sheet.lower() not in grid.sheets:
            return
        length = run.last - run.first + 1
        last = ref.r1 + (length - 1 if moves else 0)
        for row, where in grid.notable_empty(ref.sheet, ref.c1, ref.r1, last):
            target = (ref.sheet, row, ref.c1)
            rows = [run.first + row - ref.r1] if moves else range(run.first, run.last + 1)
            for r in rows:
                key = (run.sheet, r, run.col)
                self.add("reference_to_empty_cell", key,
                         f"{self.text(key)} reads {self.name(target)}, which is empty "
                         f"({where}; it counts as 0 or \"\")")

    def _omits(self, key: Key, ref, r1: int, r2: int, ranges: list) -> None:
        vertical = ref.c1 == ref.c2 and r2 > r1
        if not vertical and not (r1 == r2 and ref.c2 > ref.c1):
            return
        s = ref.sheet
        if vertical:
            ends = [((s, r2, ref.c1), (s, r2 + 1, ref.c1)), ((s, r1, ref.c1), (s, r1 - 1, ref.c1))]
        else:
            ends = [((s, r1, ref.c2), (s, r1, ref.c2 + 1)), ((s, r1, ref.c1), (s, r1, ref.c1 - 1))]
        for end, beyond in ends:
            if beyond == key or min(beyond[1], beyond[2]) < 1 or not self._same_block(
                    end, beyond, vertical):
                continue
            if any(_inside(beyond, r) and not _inside(end, r) for r in ranges):
                continue  # another aggregate reads from there: the sheet's own blocks
            if any(other.sheet == s and _inside(beyond, (other.r1, other.c1, other.r2, other.c2))
                   for other in self.grid.refs(key) if other.node is not ref.node):
                continue  # the formula reads it another way (=MAX(C1:H1,I1))
            span = (f"{column_letters(ref.c1)}{r1}:{column_letters(ref.c2)}{r2}")
            self.add("formula_omits_adjacent_cells", key,
                     f"{self.text(key)} reads {span}, which stops next to "
                     f"{self.name(beyond)} ({self.text(beyond)}), a number of the same block "
                     "that it leaves out")
            return

    def _same_block(self, end: Key, beyond: Key, vertical: bool) -> bool:
        """Is ``beyond`` a number of the same kind as ``end``, the range's last cell?"""
        grid = self.grid
        kind = grid.kind(beyond)
        if kind != grid.kind(end) or not _is_number(grid.value(beyond)) \
                or not _is_number(grid.value(end)):
            return False
        if kind == FORMULA:
            return grid.r1c1(beyond) is not None and grid.r1c1(beyond) == grid.r1c1(end)
        if kind != NUMBER:
            return False
        value = grid.value(beyond)
        if value == int(value):   # a label: a year or an index in a sequence across
            across = 2 if vertical else 1
            for k in (_step(beyond, across, -1), _step(beyond, across, 1)):
                other = grid.value(k) if grid.kind(k) == NUMBER else None
                if other is not None and abs(other - value) == 1:
                    return False
        return True

    # number_stored_as_text -----------------------------------------------------------
    def numbers_as_text(self) -> None:
        grid = self.grid
        by_sheet: dict[str, list] = defaultdict(list)
        for sheet, *rect in self.aggregate_ranges:
            by_sheet[sheet].append(rect)
        for key, value in grid.constants.items():
            if not isinstance(value, str) or not _looks_numeric(value) or key in grid.array:
                continue
            read = next((r for r in by_sheet.get(key[0], ())
                         if r[0] <= key[1] <= r[2] and r[1] <= key[2] <= r[3]), None)
            if read is not None:
                self.add("number_stored_as_text", key,
                         f"{value!r} is text that reads as a number, inside a range an "
                         "aggregate (SUM, AVERAGE, ...) reads, which skips text")
                continue
            above, below = grid.kind(_step(key, 1, -1)), grid.kind(_step(key, 1, 1))
            left, right = grid.kind(_step(key, 2, -1)), grid.kind(_step(key, 2, 1))
            vertical = NUMBER in (above, below) and TEXT not in (above, below)
            horizontal = left == right == NUMBER
            if vertical or horizontal:
                self.add("number_stored_as_text", key,
                         f"{value!r} is text that reads as a number, among numbers")

    # error_value ---------------------------------------------------------------------
    def errors(self) -> None:
        grid = self.grid
        cached = grid.cached  # (the error values first, in C loops: 200,000 cells)
        errors = {k: v for k, v in compress(cached.items(), type_mask(cached.values(), _ERROR))
                  if grid.kind(k) == FORMULA}
        errors.update((k, v) for k, v in grid.constants.items()
                      if grid.kind(k) == ERROR)
        if not errors:
            return
        index: dict[tuple[str, int], list[int]] = defaultdict(list)
        for sheet, row, col in errors:
            index[(sheet, col)].append(row)
        precedents: dict[Key, list[Key]] = {}
        for key in errors:
            found = []
            for ref in grid.refs(key):
                for col in range(ref.c1, ref.c2 + 1):
                    found.extend((ref.sheet, r, col) for r in index.get((ref.sheet, col), ())
                                 if ref.r1 <= r <= ref.r2 and (ref.sheet, r, col) != key)
            precedents[key] = found
        followers: dict[Key, list[Key]] = defaultdict(list)
        for key, found in precedents.items():
            for p in found:
                followers[p].append(key)
        reached: set[Key] = set()
        sources = sorted(k for k in errors if not precedents[k])
        spoiled_by = {k: _reach(k, followers) for k in sources}
        for spoiled in spoiled_by.values():
            reached |= spoiled
        # errors only on a cycle of errors have no source: each reports itself
        sources += sorted(k for k in errors if k not in reached and k not in spoiled_by)
        for key in sources:
            if _deliberate_na(grid, key, errors[key]):
                continue
            spoiled = sorted(spoiled_by.get(key, set()) - {key})
            message = f"{self.text(key)} shows {errors[key].value}"
            if spoiled:
                listed = ", ".join(self.name(k) for k in spoiled[:MAX_SPOILED_LISTED])
                more = len(spoiled) - MAX_SPOILED_LISTED
                message += (f"; it spoils {len(spoiled)} cell{'s' * (len(spoiled) > 1)} that "
                            f"read it: {listed}" + (f" (+{more})" if more > 0 else ""))
            self.add("error_value", key, message)


def _reach(start: Key, followers) -> set[Key]:
    seen, stack = {start}, [start]
    while stack:
        for nxt in followers.get(stack.pop(), ()):
            if nxt not in seen:
                seen.add(nxt)
                stack.append(nxt)
    return seen


def _deliberate_na(grid: Grid, key: Key, error) -> bool:
    """``=NA()`` or ``#N/A`` written in the formula: a gap left on purpose (charts)."""
    if error is not ExcelError.NA or key not in grid.formulas:
        return False
    run = grid.run_index(key)
    if run is None:
        return False
    return any((isinstance(n, ast.Func) and n.name == "NA")
               or (isinstance(n, ast.ErrorLit) and n.error is ExcelError.NA)
               for n in ast.walk(grid.runs[run].node))


def _row_relative(node) -> bool:
    if isinstance(node, ast.CellRef):
        return not node.row_abs
    return not (node.first.row_abs and node.last.row_abs)


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) \
        and math.isfinite(value)


def _looks_numeric(text: str) -> bool:
    return (len(text) <= 30 and any(ch.isdigit() for ch in text)
            and _NUMERIC_TEXT.fullmatch(text) is not None
            and _LEADING_ZERO.match(text) is None)


def _inside(key: Key, rect) -> bool:
    return rect[0] <= key[1] <= rect[2] and rect[1] <= key[2] <= rect[3]


def _at(key: Key, along: int, pos: int) -> Key:
    return (key[0], pos, key[2]) if along == 1 else (key[0], key[1], pos)


def _step(key: Key, along: int, by: int) -> Key:
    return _at(key, along, key[along] + by)
