"""formula/functions/math/conditional.py: SUMIF against a Python filter, with Microsoft's
rule for a sum_range of another size: "the upper leftmost cell in the sum_range argument
as the beginning cell, and then ... cells that correspond in size and shape to the range
argument"; without sum_range the range itself is summed."""

from __future__ import annotations

import random

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse

RNG = random.Random(23)


def ev(text: str, cells: dict):
    return evaluate(parse(text), DictResolver(cells))


@pytest.mark.parametrize("seed", range(10))
def test_sum_range_resized_from_its_top_left(seed):
    rng = random.Random(seed)
    n = rng.randint(2, 12)
    xs = [float(rng.randint(-5, 5)) for _ in range(n)]
    ys = [float(rng.randint(-50, 50)) for _ in range(n + 10)]
    cells = {f"A{i}": v for i, v in enumerate(xs, 1)}
    cells.update({f"B{i}": v for i, v in enumerate(ys, 1)})
    threshold = rng.randint(-3, 3)
    keep = [i for i, x in enumerate(xs) if x > threshold]
    for start in (1, 2, 5):
        want = sum(ys[start - 1 + i] for i in keep)
        # a single cell, a one-row range and a full column all start at B<start>
        for sum_range in (f"B{start}", f"B{start}:B{start}", f"B{start}:B{start + n - 1}"):
            assert ev(f'=SUMIF(A1:A{n},">{threshold}",{sum_range})', cells) == want
    assert ev(f'=SUMIF(A1:A{n},">{threshold}")', cells) == sum(xs[i] for i in keep)
