"""Disagreements at their source, and what follows from them.

A cell whose cached value differs from its recomputation either is wrong itself (a
*source*: none of the cells it reads disagrees) or *follows* from a source it reads,
directly or through other cells: it would show another value if the file were
recalculated, because of that source. Each disagreement is counted once, at its source,
with the cells that follow from it listed; each follower names its sources.

- An array formula is one disagreement, at its anchor, with its area: the cells of its
  area that disagree are not counted apart.
- An aggregate (MAX, SUM, IF(MAX(..)..) over a range) is checked against what it makes of
  its range's cached values, which keeps the last bit of a residual from counting
  against it. When such a cell agrees with its cached precedents but a full
  recalculation, in which a source upstream changes, gives another value, it is listed
  too (``stale``): "all checks PASS" over a check that a stale cell makes fail.
  A full recalculation that differs with no disagreement upstream is rounding among
  the range's cells, not listed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import FormulaSyntaxError
from ..evaluator.relnames import at_cell
from ..formula import ast, parse
from ..formula.parser import parse_name
from .report import Mismatch

Key = tuple[str, int, int]

MAX_ROOT_SEARCH = 5000  # disagreeing cells beyond this are all listed as sources


def rectangles(node, sheet: str, names: dict[str, str], depth: int = 0,
               at: tuple[int, int] = (1, 1)):
    """The cell rectangles (sheet, r1, c1, r2, c2) a formula of the cell at row and column
    ``at`` reads (a name's relative references read from there: relnames)."""
    for n in ast.walk(node):
        if isinstance(n, ast.CellRef):
            yield (n.sheet or sheet, n.row, n.col, n.row, n.col)
        elif isinstance(n, ast.RangeRef):
            yield (n.sheet or sheet, min(n.first.row, n.last.row), min(n.first.col, n.last.col),
                   max(n.first.row, n.last.row), max(n.first.col, n.last.col))
        elif isinstance(n, ast.Name) and depth < 8:
            text = names.get(n.name) or next(
                (v for k, v in names.items() if k.upper() == n.name.upper()), None)
            if text is not None:
                try:
                    tree = at_cell(parse_name(text), *at, None)
                except FormulaSyntaxError:
                    continue
                yield from rectangles(tree, sheet, names, depth + 1, at)


@dataclass
class Stale:
    """An aggregate that agrees with its cached precedents but whose full recalculation
    differs: (its formula, cached value, the value a recalculation gives)."""

    formula: str
    cached: object
    recomputed: object


def arrays_once(inputs, mismatches: list[Mismatch], cell_name) -> list[Mismatch]:
    """One mismatch per array formula, at its anchor with its area (the cached and
    recomputed values shown are those of its first disagreeing cell, named in ``at``)."""
    out: list[Mismatch] = []
    by_master: dict[Key, Mismatch] = {}
    for m in mismatches:
        master = inputs.array_master.get(m.key)
        if master is None or master not in inputs.arrays:
            out.append(m)
            continue
        first = by_master.get(master)
        if first is not None:
            first.cells.append(m.cell)
            continue
        last = inputs.arrays[master][1]
        area = f"{inputs.ref(master)}:{inputs.ref((master[0], *last))}"
        grouped = Mismatch(cell_name(master), m.formula, m.cached, m.recomputed, m.abs_error,
                           area=area, at=None if m.key == master else m.cell,
                           cells=[m.cell], key=master)
        by_master[master] = grouped
        out.append(grouped)
    return out


def settle(inputs, mismatches: list[Mismatch], stale: dict[Key, Stale], cell_name
           ) -> list[Mismatch]:
    """The mismatches with each one's sources and followers set, and the ``stale``
    aggregates that follow from a disagreement added (see the module's docstring).

    ``mismatches`` are one per array formula already (``arrays_once``)."""
    if not mismatches or len(mismatches) > MAX_ROOT_SEARCH:
        return mismatches
    nodes: dict[Key, Mismatch | Stale] = {m.key: m for m in mismatches}
    for key, s in stale.items():
        nodes.setdefault(key, s)
    if len(nodes) < 2:
        return mismatches
    reads = _precedents(inputs, nodes)
    sources: dict[Key, set[Key]] = {}

    def source_of(key: Key) -> set[Key]:  # depth first, without recursion
        stack, on_path = [key], {key}
        while stack:
            top = stack[-1]
            pending = [p for p in reads[top] if p not in sources and p not in on_path]
            if pending:
                stack.extend(pending)
                on_path.update(pending)
                continue
            stack.pop()
            found: set[Key] = set()
            for p in reads[top]:
                found |= sources.get(p) or ({p} if not reads[p] else set())
            sources[top] = found
        return sources[key]

    out = list(mismatches)
    by_key = {m.key: m for m in mismatches}
    followers: dict[Key, list[Key]] = {}
    for key, node in nodes.items():
        if not reads[key]:
            continue
        found = source_of(key)
        real = sorted(k for k in found if k in by_key)
        if isinstance(node, Stale):
            if not real:
                continue  # rounding among its range's cells: nothing upstream disagrees
            node = Mismatch(cell_name(key), node.formula, node.cached, node.recomputed,
                            stale=True, key=key)
            out.append(node)
        node.root = False
        node.sources = [cell_name(k) for k in (real or sorted(found))]
        for k in real:
            followers.setdefault(k, []).append(key)
    for key, keys in followers.items():
        by_key[key].followers = [cell_name(k) for k in sorted(keys)]
    return out


def _precedents(inputs, nodes: dict) -> dict[Key, list[Key]]:
    """For each node, the other nodes it reads (the cells of an array's area stand for
    their array's anchor)."""
    positions: dict[str, tuple[np.ndarray, np.ndarray, list[Key]]] = {}
    spots: dict[str, list] = {}
    for key, node in nodes.items():
        cells = [key]
        if isinstance(node, Mismatch) and node.area:
            last = inputs.arrays[key][1]
            cells = [(key[0], r, c) for r in range(key[1], last[0] + 1)
                     for c in range(key[2], last[1] + 1)]
        for cell in cells:
            spots.setdefault(cell[0], []).append((cell[1], cell[2], key))
    for sheet, items in spots.items():
        positions[sheet] = (np.array([i[0] for i in items]), np.array([i[1] for i in items]),
                            [i[2] for i in items])
    names = inputs.book.defined_names
    reads: dict[Key, list[Key]] = {}
    for key in nodes:
        found: dict[Key, None] = {}
        text = inputs.text_of(key).removeprefix("{=").removesuffix("}")
        try:
            node = parse(text)
        except FormulaSyntaxError:
            reads[key] = []
            continue
        for s, r1, c1, r2, c2 in rectangles(node, key[0], names, 0, key[1:]):
            where = positions.get(s)
            if where is None:
                continue
            rows, cols, owners = where
            hit = np.flatnonzero((rows >= r1) & (rows <= r2) & (cols >= c1) & (cols <= c2))
            for i in hit.tolist():
                if owners[i] != key:
                    found[owners[i]] = None
        reads[key] = list(found)
    return reads
