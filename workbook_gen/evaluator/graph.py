"""The dependency graph of evaluation tasks, in topological order, with cycles found.

A task computes a block of rows of one column (a single cell is a block of one).
Its inputs are rectangles ``(sheet, row1, col1, row2, col2)``; the graph joins each task
to the tasks that produce any cell of its rectangles, found by bisection in each
column's sorted blocks. :func:`order` is Tarjan's algorithm, iterative (no recursion
limit on a 100,000-cell chain): strongly connected components come out dependencies
first, which is the evaluation order, and a component of several tasks (or a task
reading itself) is a cycle.
"""

from __future__ import annotations

import bisect
from collections import defaultdict

Rect = tuple[str, int, int, int, int]


class Producers:
    """Which tasks write which cells: per (sheet, column), sorted disjoint row blocks."""

    def __init__(self, blocks: list[tuple[str, int, int, int]], extra=()):
        """``blocks[u] = (sheet, col, first, last)`` for task ``u``; ``extra``: more
        ``(task, sheet, col, first, last)`` (an array formula fills several columns)."""
        per_col: dict[tuple[str, int], list[tuple[int, int, int]]] = defaultdict(list)
        for task, (sheet, col, first, last) in [*enumerate(blocks), *(
                (u, rest) for u, *rest in extra)]:
            per_col[(sheet, col)].append((first, last, task))
        self.cols: dict[tuple[str, int], tuple[list[int], list[int], list[int]]] = {}
        self.sheet_cols: dict[str, list[int]] = defaultdict(list)
        for (sheet, col), items in per_col.items():
            items.sort()
            self.cols[(sheet, col)] = ([a for a, _, _ in items], [b for _, b, _ in items],
                                       [u for _, _, u in items])
            self.sheet_cols[sheet].append(col)
        for cols in self.sheet_cols.values():
            cols.sort()

    def tasks(self, rect: Rect):
        """The tasks that write any cell of ``rect``."""
        sheet, r1, c1, r2, c2 = rect
        cols = self.sheet_cols.get(sheet)
        if not cols:
            return
        lo, hi = bisect.bisect_left(cols, c1), bisect.bisect_right(cols, c2)
        for col in cols[lo:hi]:
            starts, ends, tasks = self.cols[(sheet, col)]
            a = bisect.bisect_left(ends, r1)
            b = bisect.bisect_right(starts, r2)
            yield from tasks[a:b]


def build(blocks: list[tuple[str, int, int, int]], inputs: list[list[Rect]],
          extra=()) -> list[list[int]]:
    """``deps[u]``: the tasks whose cells task ``u`` reads (``u`` itself if it does)."""
    producers = Producers(blocks, extra)
    deps = []
    for rects in inputs:
        seen: set[int] = set()
        for rect in rects:
            seen.update(producers.tasks(rect))
        deps.append(sorted(seen))
    return deps


def order(deps: list[list[int]]) -> list[list[int]]:
    """Strongly connected components, each after every component it depends on."""
    n = len(deps)
    index = [-1] * n
    low = [0] * n
    on_stack = [False] * n
    stack: list[int] = []
    out: list[list[int]] = []
    counter = 0
    for root in range(n):
        if index[root] != -1:
            continue
        work = [(root, 0)]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack[root] = True
        while work:
            v, i = work[-1]
            if i < len(deps[v]):
                work[-1] = (v, i + 1)
                w = deps[v][i]
                if index[w] == -1:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on_stack[w] = True
                    work.append((w, 0))
                elif on_stack[w]:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[v])
            if low[v] == index[v]:
                component = []
                while True:
                    w = stack.pop()
                    on_stack[w] = False
                    component.append(w)
                    if w == v:
                        break
                out.append(component)
    return out


def is_cycle(component: list[int], deps: list[list[int]]) -> bool:
    """A component of several tasks, or one task that reads itself."""
    return len(component) > 1 or component[0] in deps[component[0]]
