"""formula/functions/math/randarray.py: RANDARRAY's documented contract (Microsoft's page):
a rows x columns array of numbers in [min, max), whole numbers in [min, max] with
whole_number TRUE, 1 x 1 in [0, 1) by default; #VALUE! when min exceeds max; the draws
spread over the range (a chi-squared check of 20 bins, far from its critical value)."""

from __future__ import annotations

import numpy as np
from scipy import stats

from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula.arrays import evaluate_array
from workbook_gen.xlerror import ExcelError


def ev(text: str):
    value = evaluate_array(parse(text), DictResolver({}), "excel", None)
    return np.array(value.rows, dtype=object) if hasattr(value, "rows") else value


def test_shape_bounds_and_whole_numbers():
    a = ev("=RANDARRAY(4,7,-2.5,3)").astype(float)
    assert a.shape == (4, 7) and ((a >= -2.5) & (a < 3)).all()
    w = ev("=RANDARRAY(30,30,5,9,TRUE)").astype(float)
    assert set(np.unique(w)) == {5.0, 6.0, 7.0, 8.0, 9.0}
    one = ev("=RANDARRAY()")
    assert np.asarray(one, dtype=object).size == 1
    assert 0 <= float(np.asarray(one, dtype=object).reshape(-1)[0]) < 1
    assert ev("=RANDARRAY(2,2,5,1)") == ExcelError.VALUE


def test_draws_spread_evenly():
    a = ev("=RANDARRAY(100,100)").astype(float).reshape(-1)
    counts, _ = np.histogram(a, bins=20, range=(0, 1))
    chi2 = ((counts - 500) ** 2 / 500).sum()
    assert chi2 < stats.chi2.isf(1e-6, 19)    # fails once in a million honest runs
