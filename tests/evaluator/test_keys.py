"""evaluator/keys.py: cells grouped by column as a plain dictionary of lists groups them
(in the keys' order, the columns in the order of their first cell), on random keys."""

from __future__ import annotations

import random

import numpy as np
import pytest

from workbook_gen.evaluator.keys import column_groups, groups_by, pick


@pytest.mark.parametrize("seed", range(20))
def test_column_groups_as_a_dict_of_lists(seed):
    rng = random.Random(seed)
    sheets = ["Table", "Sheet 2", "Ü"][: rng.randint(1, 3)]
    keys = list({(rng.choice(sheets), rng.randint(1, 500), rng.randint(1, 16384))
                 for _ in range(rng.randint(0, 400))})
    rng.shuffle(keys)
    want: dict[tuple[str, int], list[int]] = {}
    for i, (sheet, _, col) in enumerate(keys):
        want.setdefault((sheet, col), []).append(i)
    groups, rows = column_groups(keys)
    assert [(s, c, g.tolist()) for s, c, g in groups] == \
        [(s, c, idx) for (s, c), idx in want.items()]
    assert rows.tolist() == [r for _, r, _ in keys]


def test_groups_by_and_pick():
    key = np.array([5, 3, 5, 3, 9, 5])
    assert [g.tolist() for g in groups_by(key)] == [[0, 2, 5], [1, 3], [4]]
    items = list("abcdef")
    assert pick(items, np.array([4, 0, 4])) == ["e", "a", "e"]
    assert pick(items, np.array([2])) == ["c"] and pick(items, np.array([], int)) == []
