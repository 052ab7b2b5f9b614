"""mechanisms/actuator_halving.py: the successive-halving columns of the actuator linkage,
evaluated column by column at 50 digits (expr/precise.py's mpmath printing of the trees)
and compared with tests/mp_reference.py's independent bisection (the paper's rule) and
its closed-form lever angle, over the template's stroke and variants of epsilon, the
number of halvings and the bracket."""

from __future__ import annotations

import tomllib
from pathlib import Path

import mpmath
import pytest

from workbook_gen.expr import Var
from workbook_gen.expr.precise import compile_mpmath
from workbook_gen.mechanisms.actuator_halving import (constraint, halving_quantities,
                                                      lever_point)
from workbook_gen.xlerror import ExcelError

import mp_reference as ref

ROOT = Path(__file__).resolve().parents[2]
PARAMS = tomllib.loads((ROOT / "templates/actuator_linkage.toml").read_text())["parameters"]
STROKES = [1.0 + 0.0687 * k for k in range(11)]


def run(n: int, params: dict, s: float):
    """The row's values: every halving column in order, then the two conditions."""
    columns, converged, on_branch = halving_quantities(n)
    values = {"s_BC": mpmath.mpf(s)}
    for q in columns:
        values[q.name] = compile_mpmath(q.expr)(values, params)
    values["converged"] = compile_mpmath(converged)(values, params)
    values["on_branch"] = compile_mpmath(on_branch)(values, params)
    return values


def f_mp(params, phi, s):
    xa, ya, xb, yb, l1, l1c = (mpmath.mpf(params[k]) for k in
                               ("x_A", "y_A", "x_B", "y_B", "l_A1", "l_A1C"))
    cx = xa + l1 * mpmath.cos(phi) + l1c * mpmath.sin(phi)
    cy = ya + l1 * mpmath.sin(phi) - l1c * mpmath.cos(phi)
    return (cx - xb) ** 2 + (cy - yb) ** 2 - mpmath.mpf(s) ** 2


def test_constraint_and_lever_point_by_the_geometry():
    with mpmath.workdps(50):
        for phi in (-1.5, 0.3, 1.57, 3.105, 4.64):
            for s in (1.0, 1.3435):
                values = {"s_BC": mpmath.mpf(s), "phi": mpmath.mpf(phi)}
                got = compile_mpmath(constraint(Var("phi")))(values, PARAMS)
                assert abs(got - f_mp(PARAMS, mpmath.mpf(phi), s)) < mpmath.mpf(10) ** -45
        # C = A + l_A1 (cos, sin) + l_A1C (sin, -cos): at phi = 0, (x_A + l_A1, y_A - l_A1C)
        cx, cy = lever_point(Var("phi"))
        zero = {"phi": mpmath.mpf(0)}
        assert compile_mpmath(cx)(zero, PARAMS) == mpmath.mpf(PARAMS["x_A"]) + PARAMS["l_A1"]
        assert compile_mpmath(cy)(zero, PARAMS) == \
            mpmath.mpf(PARAMS["y_A"]) - mpmath.mpf(PARAMS["l_A1C"])


@pytest.mark.parametrize("s", STROKES)
def test_the_template_rows_agree_with_the_reference_bisection(s):
    with mpmath.workdps(50):
        row = run(20, PARAMS, s)
        want = ref.actuator_bisection(PARAMS, s, 20)
        closed, _ = ref.actuator_linkage(PARAMS, s)
        assert want["phi_2_iter"] is not None
        assert row["phi_2_iter"] == want["phi_2_iter"]          # the same midpoint, exactly
        assert row["halvings_used"] == want["halvings_used"]
        assert row["converged"] and row["on_branch"]            # the lever's branch
        # |f| < epsilon there: within epsilon / |f'| of the closed-form root
        assert abs(row["phi_2_iter"] - closed["phi_2"]) < 1e-3


@pytest.mark.parametrize("epsilon, n, lo, hi", [
    (1e-9, 30, -1.5, 4.64),     # more halvings
    (1e-12, 10, -1.5, 4.64),    # too few: not converged, #NUM!
    (1e-4, 20, 0.0, 3.0),       # another bracket
    (1e-6, 25, -1.0, 2.0),
])
def test_variants_agree_with_the_reference(epsilon, n, lo, hi):
    params = PARAMS | {"epsilon": epsilon, "phi_lo": lo, "phi_hi": hi}
    with mpmath.workdps(50):
        for s in (1.0, 1.2748, 1.687):
            row = run(n, params, s)
            want = ref.actuator_bisection(params, s, n)
            assert row["halvings_used"] == want["halvings_used"], (s, n)
            if want["phi_2_iter"] is None:
                assert row["phi_2_iter"] is ExcelError.NUM and not row["converged"]
            else:
                assert row["phi_2_iter"] == want["phi_2_iter"] and row["converged"]


def test_a_row_stops_at_the_first_small_midpoint():
    """After |f_k| < epsilon the bracket is carried: mid and f repeat exactly."""
    with mpmath.workdps(50):
        row = run(20, PARAMS, 1.0)
        k = int(row["halvings_used"])
        assert k < 20
        for j in range(k + 1, 21):
            assert row[f"mid_{j}"] == row[f"mid_{k}"] and row[f"f_{j}"] == row[f"f_{k}"]
        assert all(abs(row[f"f_{j}"]) >= PARAMS["epsilon"] for j in range(1, k))


def test_the_columns_and_their_order():
    columns, _, _ = halving_quantities(3)
    assert [q.name for q in columns] == [
        "f_lo", "lo_1", "hi_1", "mid_1", "f_1", "lo_2", "hi_2", "mid_2", "f_2",
        "lo_3", "hi_3", "mid_3", "f_3", "halvings_used", "phi_2_iter"]
    assert [q.name for q in columns if q.output] == ["halvings_used", "phi_2_iter"]
