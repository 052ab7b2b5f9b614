"""The slider-crank's time ratio keeps its digits up to its limit l_BC = l_AB + |e|
(issue 12 item 14): against 50-digit mpmath of the textbook ASIN form."""

from __future__ import annotations

import mpmath as mp
import pytest

from workbook_gen.expr.numeric import compile_numpy
from workbook_gen.mechanisms.slider_crank import TIME_RATIO


def _mp_ratio(l_ab: float, l_bc: float, e: float) -> mp.mpf:
    with mp.workdps(50):
        r, l, e = mp.mpf(l_ab), mp.mpf(l_bc), mp.mpf(e)
        between = mp.degrees(mp.asin(e / (l - r)) - mp.asin(e / (l + r)))
        return (180 + between) / (180 - between)


def _ours(l_ab: float, l_bc: float, e: float) -> float:
    value = compile_numpy(TIME_RATIO)({}, {"l_AB": l_ab, "l_BC": l_bc, "e": e}, 1)
    return float(value.val[0])


CASES = [(40.0, 120.0, 10.0), (40.0, 120.0, -10.0), (40.0, 120.0, 0.0), (1.0, 1e6, 3.0)]
CASES += [(40.0, (40.0 + 10.0) * (1 + gap), sign * 10.0)
          for gap in (1e-3, 1e-6, 1e-9, 1e-12) for sign in (1, -1)]
CASES += [(1e-6, 2e-6 * (1 + 1e-10), 1e-6), (1e6, 1.5e6 * (1 + 1e-11), 0.5e6)]


@pytest.mark.parametrize("l_ab, l_bc, e", CASES)
def test_time_ratio_to_full_precision_up_to_its_limit(l_ab, l_bc, e):
    want = _mp_ratio(l_ab, l_bc, e)
    got = _ours(l_ab, l_bc, e)
    assert abs(got - float(want)) <= 8e-16 * abs(float(want)), (got, want)


def test_the_asin_form_it_replaces_loses_digits_there():
    """The reason for the change: ASIN(e/(l_BC - l_AB)) near 1 loses digits (the asin of a ratio 1e-12 from 1 is good to about 6e-7 rad: half its digits, diluted by the 180 deg around it)."""
    import math
    l_ab, e = 40.0, 10.0
    l_bc = (l_ab + e) * (1 + 1e-12)
    between = math.degrees(math.asin(e / (l_bc - l_ab)) - math.asin(e / (l_bc + l_ab)))
    naive = (180 + between) / (180 - between)
    want = float(_mp_ratio(l_ab, l_bc, e))
    assert abs(naive - want) > 1e-12 * want
    assert abs(_ours(l_ab, l_bc, e) - want) <= 8e-16 * want


def test_no_time_ratio_beyond_the_limit():
    assert compile_numpy(TIME_RATIO)({}, {"l_AB": 40.0, "l_BC": 45.0, "e": 10.0}, 1).err[0]
