"""MMULT, MDETERM, MINVERSE, MUNIT, FREQUENCY and the SUMX* pairs (formula/functions/
matrix.py) against numpy's linear algebra and Microsoft's documented results."""

from __future__ import annotations

import numpy as np
import pytest

from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula.arrays import evaluate_array
from workbook_gen.xlerror import ExcelError

A = [[1.0, 3.0, 8.0, 5.0], [1.0, 3.0, 6.0, 1.0], [1.0, 1.0, 1.0, 0.0], [7.0, 3.0, 10.0, 2.0]]
B = [[4.0, -1.0, 2.5], [0.5, 3.0, -7.0], [2.0, 2.0, 9.0]]


def ev(text: str):
    value = evaluate_array(parse(text), DictResolver({}), "excel", None)
    return [list(r) for r in value.rows] if hasattr(value, "rows") else value


def literal(m) -> str:
    return "{" + ";".join(",".join(repr(x) for x in row) for row in m) + "}"


def test_mdeterm_matches_numpy_and_microsofts_example():
    # support.microsoft.com MDETERM: the determinant of A above is 88
    assert ev(f"=MDETERM({literal(A)})") == pytest.approx(88.0, rel=1e-12)
    assert ev(f"=MDETERM({literal(B)})") == pytest.approx(np.linalg.det(B), rel=1e-12)


def test_minverse_times_the_matrix_is_the_identity():
    inv = np.array(ev(f"=MINVERSE({literal(B)})"))
    np.testing.assert_allclose(inv, np.linalg.inv(B), rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(inv @ np.array(B), np.eye(3), atol=1e-12)


def test_a_singular_matrix_has_no_inverse():
    assert ev("=MINVERSE({1,2;2,4})") == ExcelError.NUM  # Microsoft: #NUM! when singular


def test_mmult_matches_numpy_and_refuses_mismatched_shapes():
    product = ev(f"=MMULT({literal(A)},{literal([[1.0], [2.0], [3.0], [4.0]])})")
    np.testing.assert_allclose(np.array(product), np.array(A) @ [[1], [2], [3], [4]])
    assert ev("=MMULT({1,2;3,4},{1,2,3})") == ExcelError.VALUE  # columns(a) != rows(b)


def test_munit_is_the_identity():
    assert ev("=MUNIT(3)") == np.eye(3).tolist()


def test_frequency_counts_by_bins_plus_an_overflow_bin():
    data = [79, 85, 78, 85, 50, 81, 95, 88, 97]   # Microsoft's FREQUENCY example
    bins = [70, 79, 89]
    got = [row[0] for row in ev(f"=FREQUENCY({literal([data])},{literal([[b] for b in bins])})")]
    # each bin counts lo < x <= hi (Microsoft's result: 1, 2, 4, 2)
    right = [sum(1 for x in data if lo < x <= hi) for lo, hi in
             zip([-np.inf, *bins], [*bins, np.inf])]
    assert got == [1, 2, 4, 2] == right


@pytest.mark.parametrize("name, fn", [
    ("SUMX2MY2", lambda x, y: np.sum(x**2 - y**2)),
    ("SUMX2PY2", lambda x, y: np.sum(x**2 + y**2)),
    ("SUMXMY2", lambda x, y: np.sum((x - y) ** 2)),
])
def test_sum_of_pairs(name, fn):
    x, y = np.array([2.0, 3, 9, 1, 8, 7, 5]), np.array([6.0, 5, 11, 7, 5, 4, 4])
    assert ev(f"={name}({literal([x.tolist()])},{literal([y.tolist()])})") == \
        pytest.approx(fn(x, y), rel=1e-15)
