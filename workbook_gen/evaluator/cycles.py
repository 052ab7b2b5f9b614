"""Cells that take part in a cycle of the reference graph, evaluated at cell precision.

The graph is built from the rectangles a formula mentions, so a cycle in it need not be a
cycle of the values: ``SUM(INDEX(Liste3,1,1):INDEX(Liste3,1,Indice-1))`` in a cell of
Liste3 reads only the cells to its left, and ``IF(A6,B6,1)`` never reads B6 while A6 is
FALSE. Excel follows the cells actually read and computes such cells; without iterative
calculation it reports only the cycles the values really take.

``settle`` finds out which: the component's cells are set to a placeholder and evaluated
round after round until a round changes nothing, twice, from two placeholders that no
formula can confuse (an error and a number). When every cell's value is one of the
cells actually read, both runs end on the same values, which are then exact (a value
computed from cells that are themselves final is final); when the values do depend on one
another, the placeholder shows through (or the rounds do not settle) and the two runs
differ: a real cycle, reported as before.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from workbook_gen.xlerror import ExcelError

MAX_CELLS = 400   # larger components are reported as cycles without trying
PLACEHOLDERS = (ExcelError.REF, -7.0e-77)


def settle(units: Sequence, cells_of: Callable, get: Callable, put: Callable,
           evaluate: Callable) -> bool:
    """Evaluate a cyclic component's ``units`` (``evaluate(unit)``) until they settle;
    True when the values do not depend on the placeholders (the store holds them), False
    for a real cycle (the store holds the last run's values: the caller overwrites)."""
    cells = [c for u in units for c in cells_of(u)]
    if len(cells) > MAX_CELLS:
        return False
    runs = []
    for placeholder in PLACEHOLDERS:
        for cell in cells:
            put(cell, placeholder)
        for _ in range(len(units) + 1):
            before = [get(c) for c in cells]
            for unit in units:
                evaluate(unit)
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
