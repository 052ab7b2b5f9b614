"""How a file batch cuts its variants into the chunks a runner is given (api.workbook_chunks)."""

import pytest

from workbook_gen.batching.api import workbook_chunks


@pytest.mark.parametrize("count, jobs", [(0, 2), (1, 2), (2, 1), (5, 4), (30, 2), (1000, 2),
                                         (1001, 3)])
def test_chunks_keep_every_variant_in_order_first_alone_small_tail(count, jobs):
    variants = list(range(count))
    chunks = workbook_chunks(variants, jobs)
    assert [v for chunk in chunks for v in chunk] == variants
    if not count:
        assert chunks == []
        return
    sizes = [len(c) for c in chunks]
    assert sizes[0] == 1 and min(sizes) >= 1 and max(sizes) <= 8
    # the last chunks (two per worker's worth) hold at most 2 variants each
    tail = [s for s in sizes[-2 * jobs:]]
    assert max(tail) <= 2
    if count >= 1000:   # a big batch: few, full chunks for the bulk of the work
        assert sizes.count(8) * 8 >= 0.9 * count
