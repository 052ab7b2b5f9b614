"""xlmath/kernels.py: the kernels give Python's math (the C library) bit for bit, as the
scalar formula evaluator computes it, on random and extreme arguments, whichever of
numpy's or the C library's function the import-time probe chose; SIN, COS, TAN are
#NUM! from 2^27 on (Excel's limit); first_error keeps the leftmost error; fsum_rows is
math.fsum row by row."""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbook_gen.xlerror import TRIG_LIMIT, ExcelError
from workbook_gen.xlmath import kernels

RNG = np.random.default_rng(23)
XS = np.concatenate([RNG.uniform(-1, 1, 500), RNG.uniform(-1e4, 1e4, 500),
                     RNG.standard_normal(500) * 10.0 ** RNG.uniform(-12, 12, 500),
                     [0.0, -0.0, 1.0, -1.0, 2.0 ** 27 - 1, -(2.0 ** 27 - 1), 1e-300]])
MATH = {"SIN": math.sin, "COS": math.cos, "TAN": math.tan, "ASIN": math.asin,
        "ACOS": math.acos, "ATAN": math.atan, "SQRT": math.sqrt}


def libm(fn, *xs):
    try:
        r = fn(*xs)
    except (ValueError, OverflowError):
        return None
    return r if math.isfinite(r) else None


@pytest.mark.parametrize("name", sorted(MATH))
def test_unary_bit_for_bit_as_math(name):
    val, err = kernels.unary(name, XS.copy(), np.zeros(XS.size, np.uint8))
    for x, v, e in zip(XS, val, err):
        want = libm(MATH[name], float(x))
        if name in ("SIN", "COS", "TAN") and abs(x) >= TRIG_LIMIT:
            want = None
        if want is None:
            assert e == ExcelError.NUM.code, (name, x)
        else:
            assert e == 0 and v == want + 0.0, (name, x, v, want)   # bit for bit, no -0


def test_the_trig_limit_and_pow_atan2_as_math():
    big = np.array([TRIG_LIMIT, -TRIG_LIMIT, 1e300])
    assert (kernels.unary("SIN", big, np.zeros(3, np.uint8))[1] == ExcelError.NUM.code).all()
    x, y = np.abs(XS[:600]) + 0.5, XS[600:1200] / 7
    with np.errstate(all="ignore"):
        powers = kernels.POW(x, y)
    for a, b, got in zip(x, y, powers):
        want = libm(math.pow, float(a), float(b))
        assert (want is None and not math.isfinite(got)) or got == want, (a, b)
    assert np.array_equal(kernels.ATAN2_YX(y, x), [math.atan2(b, a) for a, b in zip(x, y)])


def test_first_error_and_fsum_rows():
    a = np.array([0, 3, 0, 7], np.uint8)
    b = np.array([2, 5, 0, 0], np.uint8)
    c = np.array([4, 0, 6, 1], np.uint8)
    assert kernels.first_error(a, b, c).tolist() == [2, 3, 6, 7]
    assert kernels.first_error(np.zeros(4, np.uint8), c).tolist() == c.tolist()
    rows = [RNG.standard_normal(50) * 10.0 ** RNG.integers(-10, 10, 50) for _ in range(7)]
    err = np.zeros(50, np.uint8)
    got = kernels.fsum_rows(rows, err)
    assert got.tolist() == [math.fsum(r[i] for r in rows) for i in range(50)]
