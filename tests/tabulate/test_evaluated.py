"""tabulate/evaluated.py: ``evaluate`` gives the Table's columns (against the 50-digit
four-bar of tests/mp_reference.py) and, computed once on first read, everything else the
workbook shows: the extremes over the ok rows (against a plain numpy max/min over the
50-digit column), the Summary's row counts (counted by hand from the status), the
residuals and the derived values."""

from __future__ import annotations


import numpy as np
import pytest

import mp_reference
from workbook_gen.errors import CannotAssembleError
from workbook_gen.tabulate import evaluate
from workbook_gen.tabulate.evaluated import Evaluated

# crank 90, coupler 20, rocker 60, ground 100: part of the turn cannot assemble
PARAMS = {"l_O1O2": 100.0, "l_O1A": 90.0, "l_AB": 20.0, "l_O2B": 60.0, "l_AC": 60.0,
          "delta_C": 30.0, "omega_2": 10.0}
INPUTS = [float(x) for x in range(0, 360, 10)]


@pytest.fixture(scope="module")
def result() -> Evaluated:
    return evaluate(mp_reference.scene_at("four_bar", PARAMS, INPUTS))


@pytest.fixture(scope="module")
def reference():
    return mp_reference.solve("four_bar", PARAMS, INPUTS, {})[0]


def test_evaluate_gives_the_columns(result, reference):
    assert isinstance(result, Evaluated)
    for i, exact in enumerate(reference["theta_4"]):
        if exact is None:
            assert result.status[i] == "cannot assemble"
        else:
            assert result.status[i] == "ok"
            got = float(result.columns["theta_4"].val[i])
            assert abs((got - float(exact) + 180) % 360 - 180) < 1e-10


def test_the_rest_is_computed_once_on_first_read(result):
    for name in ("derived", "checks", "conditions", "extremes", "summary"):
        assert name not in vars(evaluate(result.scene))       # not computed up front
        assert getattr(result, name) is getattr(result, name)  # kept


def test_extremes_are_the_reference_columns_over_the_ok_rows(result, reference):
    for name in ("x_C", "y_C", "omega_4", "alpha_3"):
        rows = [i for i, v in enumerate(reference[name]) if v is not None]
        exact = np.array([float(reference[name][i]) for i in rows])
        found = result.extremes[name]
        scale = np.abs(exact).max()
        assert found.counted[0] == len(rows)
        assert abs(found.hi[0] - exact.max()) <= 1e-10 * scale
        assert abs(found.lo[0] - exact.min()) <= 1e-10 * scale
        assert found.hi_at[0] == INPUTS[rows[int(exact.argmax())]]
        assert found.lo_at[0] == INPUTS[rows[int(exact.argmin())]]


def test_summary_counts_the_rows(result, reference):
    missing = sum(v is None for v in reference["theta_3"])
    summary = result.summary
    assert summary.rows == len(INPUTS)
    assert summary.rows_not_assembled == missing > 0
    assert summary.rows_ok + summary.rows_flagged + missing == len(INPUTS)



def test_checks_and_derived(result):
    assert result.checks.overall == "PASS"
    assert result.checks.cannot_assemble == [int(s == "cannot assemble") for s in result.status]
    # Grashof by hand: s + l - (p + q) = 20 + 100 - (90 + 60) = -30
    assert result.derived["grashof_excess"] == -30.0
    assert result.conditions.items == ()


def test_nothing_assembles_is_refused():
    params = PARAMS | {"l_AB": 5.0, "l_O2B": 5.0}
    with pytest.raises(CannotAssembleError):
        evaluate(mp_reference.scene_at("four_bar", params, [90.0, 180.0]))
