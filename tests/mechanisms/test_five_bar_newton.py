"""five_bar_newton: the Newton chain's trees at 50 digits against the five-bar's
closed form from tests/mp_reference.py (mpmath, independent of the trees)."""

from __future__ import annotations

import mpmath
import pytest

from tests import mp_reference
from workbook_gen.expr import Var
from workbook_gen.expr.precise import compile_mpmath
from workbook_gen.mechanisms import get_template
from workbook_gen.mechanisms.five_bar_newton import (CONVERGED_DEG, newton_quantities,
                                                     newton_status)
from workbook_gen.xlerror import ExcelError

PARAMS = get_template("five_bar").defaults


def _inputs(phi_deg, params=PARAMS):
    """x_C .. h_D at 50 digits by hand: C on its circle, the pivots' directions and the
    dyads' half chords (Heron), #NUM! out of reach as the workbook has it."""
    p = {k: mpmath.mpf(v) for k, v in params.items()}
    v = mpmath.radians(phi_deg)
    cx, cy = p["x_0"] + p["R_path"] * mpmath.cos(v), p["y_0"] + p["R_path"] * mpmath.sin(v)

    def chord(a, b, d):
        q = (a + b + d) * (a + b - d) * (d + a - b) * (d - a + b)
        return mpmath.sqrt(q) / (2 * d) if q >= 0 else ExcelError.NUM
    d_ac, d_ec = mpmath.hypot(cx, cy), mpmath.hypot(cx - p["l_5"], cy)
    return p, {"x_C": cx, "y_C": cy, "d_AC": d_ac, "d_EC": d_ec,
               "psi_AC": mpmath.degrees(mpmath.atan2(cy, cx)),
               "psi_EC": mpmath.degrees(mpmath.atan2(cy, cx - p["l_5"])),
               "h_B": chord(p["l_1"], p["l_2"], d_ac), "h_D": chord(p["l_4"], p["l_3"], d_ec)}


def _run(steps, phi_deg, params=PARAMS):
    p, values = _inputs(phi_deg, params)
    with mpmath.workdps(50):
        for q in newton_quantities(steps):
            values[q.name] = compile_mpmath(q.expr)(values, p)
    return values


def _mod360(x):
    return (x + 180) % 360 - 180


@pytest.mark.parametrize("phi", [0, 75, 180, 290])
def test_eight_steps_reach_the_closed_form_elbows_out(phi):
    values = _run(8, phi)
    ref, _ = mp_reference.five_bar(PARAMS, phi)
    for name in ("theta_1", "theta_4"):
        assert isinstance(values[name], mpmath.mpf), name
        assert abs(_mod360(values[name] - ref[name])) < 1e-12, (name, values[name], ref[name])


def test_the_error_falls_quadratically_and_an_unconverged_angle_is_num():
    ref, _ = mp_reference.five_bar(PARAMS, 40)
    values = _run(8, 40)
    errs = [abs(_mod360(values[f"th1_{k}"] - ref["theta_1"])) for k in range(9)]
    # monotone from the start, quadratic at the end (e_{k+1} ~ C e_k^2)
    assert all(b < a for a, b in zip(errs, errs[1:5]))
    k = next(i for i, e in enumerate(errs) if e < 1e-3)
    assert errs[k + 1] < 10 * errs[k] ** 2 * 57.3
    one = _run(1, 40)
    # one step moves the angle by far more than CONVERGED_DEG: #NUM!, never the iterate
    assert abs(one["th1_1"] - one["th1_0"]) > CONVERGED_DEG
    assert one["theta_1"] is ExcelError.NUM and one["theta_4"] is ExcelError.NUM


def test_the_start_is_the_crank_perpendicular_to_the_pivot_line():
    values = _run(1, 0)
    assert values["th1_0"] == pytest.approx(float(values["psi_AC"]) + 90, abs=1e-12)
    assert values["th4_0"] == pytest.approx(float(values["psi_EC"]) - 90, abs=1e-12)


def test_out_of_reach_carries_the_half_chords_error():
    far = dict(PARAMS, R_path=3.0)  # C 3 m from the path's centre: beyond l_1 + l_2
    values = _run(3, 90, far)
    assert values["h_B"] is ExcelError.NUM
    assert values["th1_0"] is ExcelError.NUM and values["theta_1"] is ExcelError.NUM


def test_status_flags_a_row_where_either_angle_is_an_error():
    seen = []
    status = newton_status(3, lambda cond: seen.append(cond) or cond)
    (cond,) = seen
    f = compile_mpmath(status)
    assert f({"theta_1": mpmath.mpf(1), "theta_4": mpmath.mpf(2)}, {}) in (False, 0)
    assert f({"theta_1": ExcelError.NUM, "theta_4": mpmath.mpf(2)}, {}) in (True, 1)
    assert f({"theta_1": mpmath.mpf(1), "theta_4": ExcelError.NUM}, {}) in (True, 1)
    assert {v.name for v in _vars(cond)} == {"theta_1", "theta_4"}


def _vars(node):
    from workbook_gen.expr.tree import children
    out, stack = [], [node]
    while stack:
        n = stack.pop()
        if isinstance(n, Var):
            out.append(n)
        stack.extend(children(n))
    return out


def test_names_and_order_of_the_chain():
    names = [q.name for q in newton_quantities(2)]
    assert names == ["th1_0", "th4_0", "th1_1", "th4_1", "th1_2", "th4_2", "theta_1", "theta_4"]
    assert [q.output for q in newton_quantities(2)][-2:] == [True, True]
