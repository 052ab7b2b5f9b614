"""Cell keys ``(sheet, row, col)`` by column, sorted by numpy rather than bucketed by
Python code per cell (the audit's collections of formulas, cached values and constants
hold a few hundred thousand keys)."""

from __future__ import annotations

from operator import itemgetter

import numpy as np


def pick(items: list, idx) -> list:
    """``[items[i] for i in idx]`` (``idx`` a numpy array of indexes), in a C loop."""
    where = idx.tolist()
    if len(where) < 2:
        return [items[i] for i in where]
    return list(itemgetter(*where)(items))


def column_groups(keys: list[tuple[str, int, int]]
                  ) -> tuple[list[tuple[str, int, np.ndarray]], np.ndarray]:
    """``([(sheet, col, indexes)], rows)``: the indexes into ``keys`` of each column's cells
    in the order of ``keys``, the columns in the order of their first cell, and the row of
    every key (numpy sorts them: no Python code per cell but a few C loops)."""
    if not keys:
        return [], np.zeros(0, np.int64)
    n = len(keys)  # (zip(*keys) would take ten times as long on 200,000 keys)
    sheets = list(map(_SHEET, keys))
    index = {name: i for i, name in enumerate(dict.fromkeys(sheets))}
    key = np.fromiter(map(index.__getitem__, sheets), np.int64, n) * (1 << 15)
    key += np.fromiter(map(_COL, keys), np.int64, n)
    return ([(keys[g[0]][0], keys[g[0]][2], g) for g in groups_by(key)],
            np.fromiter(map(_ROW, keys), np.int64, n))


_SHEET, _ROW, _COL = itemgetter(0), itemgetter(1), itemgetter(2)


def groups_by(key: np.ndarray) -> list[np.ndarray]:
    """The indexes of the entries of ``key`` (integers) equal to each other, in their
    order, the groups in the order of their first entry."""
    order = np.argsort(key, kind="stable")
    groups = np.split(order, np.flatnonzero(np.diff(key[order])) + 1)
    groups.sort(key=lambda g: g[0])
    return groups
