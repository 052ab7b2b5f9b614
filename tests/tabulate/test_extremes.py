"""tabulate/extremes.py: the extremes of a column over its ok rows and the input of
the first row that holds each, against a plain loop over the rows, on random columns
with errors, flagged rows and ties, several variants at once."""

from __future__ import annotations

import math
import random

import numpy as np
import pytest

from workbook_gen.tabulate.extremes import ok_extremes, ok_rows

STATUSES = ["ok", "ok", "ok", "toggle", "not assembled", "flagged", "dead centre"]


def loop(val, err, status, inputs):
    """(lo, lo_at, hi, hi_at, counted) of one variant by a loop: strict comparisons keep
    the first row holding an extreme."""
    lo = hi = lo_at = hi_at = math.nan
    counted = 0
    for v, e, s, x in zip(val, err, status, inputs):
        if e != 0 or s != "ok":
            continue
        counted += 1
        if counted == 1 or v < lo:
            lo, lo_at = v, x
        if counted == 1 or v > hi:
            hi, hi_at = v, x
    return lo, lo_at, hi, hi_at, counted


@pytest.mark.parametrize("seed", range(30))
def test_as_a_loop(seed):
    rng = random.Random(seed)
    n, variants = rng.randint(1, 30), rng.randint(1, 4)
    inputs = np.array(sorted(rng.uniform(-360, 360) for _ in range(n)))
    val = [float(rng.choice([rng.randint(-3, 3), rng.uniform(-1e3, 1e3)]))
           for _ in range(n * variants)]
    err = [rng.choice([0, 0, 0, 0, 2, 6]) for _ in range(n * variants)]
    val = [math.nan if e else v for v, e in zip(val, err)]
    status = [rng.choice(STATUSES) for _ in range(n * variants)]
    got = ok_extremes(np.array(val), np.array(err, dtype=np.uint8), np.array(status, dtype=object),
                      inputs, variants)
    for k in range(variants):
        part = slice(k * n, (k + 1) * n)
        want = loop(val[part], err[part], status[part], inputs)
        have = (got.lo[k], got.lo_at[k], got.hi[k], got.hi_at[k], got.counted[k])
        for a, b in zip(have, want):
            assert (math.isnan(a) and math.isnan(b)) or a == b, (k, have, want)


def test_ok_rows_is_exactly_ok():
    assert ok_rows(np.array(["ok", "OK", "ok ", "", "toggle"], dtype=object)).tolist() == \
        [True, False, False, False, False]
