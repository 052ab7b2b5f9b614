"""Cells of a cycle of the reference graph, evaluated as Excel does with iterative
calculation off.

The graph is built from the rectangles a formula mentions, so a cycle in it need not be a
cycle of the values: ``SUM(INDEX(Liste3,1,1):INDEX(Liste3,1,Indice-1))`` in a cell of
Liste3 reads only the cells to its left, and ``IF(A6,B6,1)`` never reads B6 while A6 is
FALSE. Excel follows the cells actually read: a cell is evaluated when a formula asks for
it, and a formula that asks for a cell whose evaluation is still under way has run into a
circular reference. With iteration off (``calcPr`` without ``iterate="1"``) Excel then
shows 0 in every cell on such a run-time cycle and in the cells whose value comes from
one (``B2=B2`` and ``E2=B2+1`` both cache 0), and computes every other cell normally,
even where its static references form a loop (``D6=IF(IF(A6,B6,TRUE),1,B6)`` with A6
FALSE caches 1). An array formula is one evaluation, but its cells are apart on the cycle:
in ``D10:D12=IF(A10:A12,B10:B12,1)`` with ``B11=IF(A11,C11,1)``, ``C11=D11`` and A11
TRUE, only D11 is on the cycle (B11 -> C11 -> D11 -> B11); D10 and D12 cache 1.
(formulas__circular.xlsx, saved by Excel, shows all of this; Excel marks exactly the cells
on a run-time cycle with ``ca="1"``.)

``settle`` first tries the cheap case where the values do not take the loop at all
(``SUM(INDEX(Liste3,1,1):INDEX(Liste3,1,Indice-1))`` in a cell of Liste3: INDEX gives
a reference, whose cells the on-demand pass below would count as read): the component's
cells are set to a placeholder and evaluated round after round until a round changes
nothing, twice, from two placeholders that no formula can confuse (an error and a
number); identical results are exact (a value computed from cells that are themselves
final is final).

Otherwise ``run`` reproduces Excel: the component's tasks are evaluated on demand (a read of a cell of
the component evaluates its task first), a read of a cell whose task is under way gives
:data:`CIRCULAR`, and the cells actually read are recorded. The strongly connected parts
of that run-time graph are the cells on a cycle: they are fixed to :data:`CIRCULAR` and the
component is evaluated again, until no new cycle shows (a pass with no cycle has read no
cell under way, so its values are final). :data:`CIRCULAR` behaves as an error (it flows
into what reads it, as Excel's 0 does into ``E2``) and is shown as Excel's 0, or as
LibreOffice's ``Err:522`` (exported as ``#VALUE!``), once everything is evaluated
(:func:`shown`).
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Sequence

from workbook_gen.evaluator.graph import is_cycle, order
from workbook_gen.xlerror import ExcelError

MAX_CELLS = 400   # larger components are reported as cycles without trying
CIRCULAR = ExcelError.CIRC
PLACEHOLDERS = (ExcelError.REF, -7.0e-77)
_RECURSION = 20000


def shown(dialect: str):
    """What a cell on (or fed by) a circular reference holds once saved."""
    return ExcelError.VALUE if dialect == "libreoffice" else 0.0


class _OnDemand:
    """The store as a formula of the component sees it: each read of a component cell
    first evaluates that cell's task (or notes the circular reference)."""

    def __init__(self, store, run: "_Run"):
        self._store, self._run = store, run

    def __getattr__(self, name):  # everything else: the store's own
        return getattr(self._store, name)

    def get(self, sheet, row, col):
        self._run.need_cell((sheet, row, col))
        return self._store.get(sheet, row, col)

    def rect(self, sheet, r1, c1, r2, c2):
        self._run.need_rect(sheet, *self._store.clip(sheet, r1, c1, r2, c2))
        return self._store.rect(sheet, r1, c1, r2, c2)

    def column_values(self, sheet, col, r1, r2):
        self._run.need_rect(sheet, r1, col, r2, col)
        return self._store.column_values(sheet, col, r1, r2)

    def block(self, sheet, col, first, last):
        self._run.need_rect(sheet, first, col, last, col)
        return self._store.block(sheet, col, first, last)

    def rect_scale(self, sheet, r1, c1, r2, c2):
        self._run.need_rect(sheet, *self._store.clip(sheet, r1, c1, r2, c2))
        return self._store.rect_scale(sheet, r1, c1, r2, c2)


class _Run:
    """One on-demand pass over a component, with the cells in ``fixed`` held circular."""

    def __init__(self, tasks, cells_of, store, evaluate, fixed: set):
        self.tasks, self.store, self.evaluate, self.fixed = tasks, store, evaluate, fixed
        self.cells = [list(cells_of(u)) for u in tasks]
        self.owner = {c: i for i, cs in enumerate(self.cells) for c in cs}
        self.state: dict[int, bool] = {}    # task -> done (False: under way)
        self.stack: list[int] = []
        self.reads: list[set] = [set() for _ in tasks]
        self.view = _OnDemand(store, self)

    def need_cell(self, cell) -> None:
        u = self.owner.get(cell)
        if u is None:
            return
        if self.stack:
            self.reads[self.stack[-1]].add(cell)
        if cell not in self.fixed and u not in self.state:
            self.compute(u)

    def need_rect(self, sheet, r1, c1, r2, c2) -> None:
        for cell in [c for c in self.owner
                     if c[0] == sheet and r1 <= c[1] <= r2 and c1 <= c[2] <= c2]:
            self.need_cell(cell)

    def compute(self, u: int) -> None:
        self.state[u] = False
        for cell in self.cells[u]:
            self.store.put(*cell, CIRCULAR)
        self.store.forget_rects()
        self.stack.append(u)
        try:
            self.evaluate(self.tasks[u], self.view)
        finally:
            self.stack.pop()
        for cell in self.cells[u]:
            if cell in self.fixed:
                self.store.put(*cell, CIRCULAR)
        self.store.forget_rects()
        self.state[u] = True

    def all(self) -> None:
        for cell in self.fixed:
            self.store.put(*cell, CIRCULAR)
        for u in range(len(self.tasks)):
            if u not in self.state and not all(c in self.fixed for c in self.cells[u]):
                self.compute(u)

    def graph(self) -> dict:
        """cell -> the component cells it read (an array formula's cells all read what the
        formula read)."""
        return {c: self.reads[u] for u, cs in enumerate(self.cells) for c in cs
                if c not in self.fixed}


def settle(tasks: Sequence, cells_of: Callable, get: Callable, put: Callable,
           evaluate: Callable) -> bool:
    """Evaluate a cyclic component's ``tasks`` (``evaluate(task)``) until they settle;
    True when the values do not depend on the placeholders (the store holds them), False
    when they do (the store holds the last round's values: ``run`` overwrites them)."""
    cells = [c for u in tasks for c in cells_of(u)]
    runs = []
    for placeholder in PLACEHOLDERS:
        for cell in cells:
            put(cell, placeholder)
        for _ in range(len(tasks) + 1):
            before = [get(c) for c in cells]
            for task in tasks:
                evaluate(task)
            after = [get(c) for c in cells]
            if _same(before, after):
                break
        else:
            return False
        runs.append(after)
    return _same(*runs)


def _same(a: list, b: list) -> bool:
    return len(a) == len(b) and all(
        x is y or (type(x) is type(y) and x == y) for x, y in zip(a, b))


def run(tasks: Sequence, cells_of: Callable, store, evaluate: Callable) -> list[list]:
    """Evaluate a cyclic component's ``tasks`` (``evaluate(task, store_view)``) as Excel
    does; the store ends with every value (cells on a cycle hold :data:`CIRCULAR`).
    Returns the run-time cycles, each a sorted list of cells (none: the values do not
    take the static cycle). RecursionError when the chain of reads is too deep."""
    fixed: set = set()
    found: list[list] = []
    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(max(limit, _RECURSION))
    try:
        while True:
            one = _Run(tasks, cells_of, store, evaluate, fixed)
            one.all()
            new = [part for part in _strong_parts(one.graph()) if not fixed.intersection(part)]
            if not new:
                return found
            for part in new:
                fixed.update(part)
                found.append(sorted(part))
    finally:
        sys.setrecursionlimit(limit)
        store.forget_rects()


def _strong_parts(graph: dict) -> list[set]:
    """The strongly connected parts of ``graph`` that hold a cycle (two cells or more, or
    a cell that reads itself): graph.order's Tarjan over the cells numbered in ``graph``'s
    order, reads of cells outside ``graph`` left out."""
    cells = list(graph)
    number = {cell: k for k, cell in enumerate(cells)}
    deps = [[number[c] for c in graph[cell] if c in number] for cell in cells]
    return [{cells[k] for k in part} for part in order(deps) if is_cycle(part, deps)]
