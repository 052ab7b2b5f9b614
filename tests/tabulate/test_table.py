"""tabulate/table.py: the Table's columns against the 50-digit four-bar
(tests/mp_reference.py) and Norton's published values, the status texts, the cached
values' Excel error texts, the headers, the derived values (Grashof's sums by hand) and
``compute``'s DataFrame."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mpmath import mp

import mp_reference
from workbook_gen import xlmath as xm
from workbook_gen.errors import CannotAssembleError
from workbook_gen.scene import load_scene
from workbook_gen.tabulate.table import (CANNOT_ASSEMBLE, STATUS, Table, cached_values,
                                         compute, derived_cells, derived_values,
                                         evaluate_table, headers, status_texts)

NORTON = {"l_O1O2": 100.0, "l_O1A": 40.0, "l_AB": 120.0, "l_O2B": 80.0, "l_AC": 60.0,
          "delta_C": 30.0, "omega_2": 10.0}
# crank 90, coupler 20, rocker 60, ground 100: assembles only over part of the turn
NON_GRASHOF = NORTON | {"l_O1A": 90.0, "l_AB": 20.0, "l_O2B": 60.0}
INPUTS = [0.0, 40.0, 77.5, 130.0, 180.0, 250.0, 333.0]


@pytest.fixture(scope="module")
def norton() -> Table:
    return evaluate_table(mp_reference.scene_at("four_bar", NORTON, INPUTS,
                                                {"branch": "open"}))


def test_columns_match_the_50_digit_four_bar(norton):
    ref, singular = mp_reference.solve("four_bar", NORTON, INPUTS, {"branch": "open"})
    assert not any(singular)
    for name in ("theta_3", "theta_4", "omega_3", "omega_4", "alpha_3", "alpha_4",
                 "x_C", "y_C", "vx_C", "vy_C", "ax_C", "ay_C"):
        ours = norton.columns[name]
        assert not ours.err.any()
        scale = max(abs(float(v)) for v in ref[name])
        for got, exact in zip(ours.val, ref[name]):
            diff = float(got) - float(exact)
            if name.startswith("theta"):
                diff = (diff + 180.0) % 360.0 - 180.0
            assert abs(diff) <= 1e-12 * scale, (name, got, exact)
    assert list(norton.status) == ["ok"] * len(INPUTS)
    assert norton.rows == len(INPUTS) and norton.assembled.all()


def test_nortons_published_angles(norton):
    """Norton, Design of Machinery, example 4-1: theta_2 = 40 deg gives
    theta_3 = 20.30 deg, theta_4 = 57.32 deg on the open branch."""
    i = INPUTS.index(40.0)
    assert round(float(norton.columns["theta_3"].val[i]), 2) == 20.30
    assert round(float(norton.columns["theta_4"].val[i]), 2) == 57.32


def test_rows_that_cannot_assemble_are_marked_where_the_reference_has_none():
    inputs = [float(x) for x in range(0, 360, 15)]
    table = evaluate_table(mp_reference.scene_at("four_bar", NON_GRASHOF, inputs))
    ref, _ = mp_reference.solve("four_bar", NON_GRASHOF, inputs, {})
    expected = [ref["theta_3"][i] is None for i in range(len(inputs))]
    assert any(expected) and not all(expected)
    assert [s == CANNOT_ASSEMBLE for s in table.status] == expected
    assert list(table.assembled) == [not e for e in expected]
    # where it cannot assemble the columns hold an error, never a number marked ok
    assert all(table.columns["theta_3"].err[i] != 0 for i, e in enumerate(expected) if e)


def test_a_sweep_where_nothing_assembles_is_refused():
    params = NORTON | {"l_AB": 5.0, "l_O2B": 5.0}   # 5 + 5 + 40 < 100: never closes
    with pytest.raises(CannotAssembleError, match="cannot be assembled anywhere"):
        evaluate_table(mp_reference.scene_at("four_bar", params, [0.0, 90.0, 180.0]))


def test_status_texts_turn_errors_into_cannot_assemble():
    status = xm.XArray(np.array(["ok", "dead centre", "ok"], dtype=object),
                       np.array([0, 0, xm.DIV0], np.uint8))
    assert list(status_texts(status)) == ["ok", "dead centre", CANNOT_ASSEMBLE]


def test_cached_values_are_numbers_booleans_and_excels_error_texts():
    """Error texts as Excel shows them: support.microsoft.com "#DIV/0! error",
    "#NUM! error", "#VALUE! error"."""
    column = xm.XArray(np.array([1.5, 2.0, 0.0, -3.0]),
                       np.array([0, xm.DIV0, xm.NUM, xm.VALUE], np.uint8))
    assert cached_values(column) == [1.5, "#DIV/0!", "#NUM!", "#VALUE!"]
    flags = xm.XArray(np.array([1.0, 0.0]), np.zeros(2, np.uint8), boolean=True)
    got = cached_values(flags)
    assert got == [True, False] and all(type(v) is bool for v in got)


def test_headers_name_and_unit_input_first_status_last(norton):
    heads = headers(norton.model)
    assert heads[0] == "theta_2 [deg]" and heads[-1] == STATUS
    assert "theta_3 [deg]" in heads and "x_C [mm]" in heads and "omega_3 [rad/s]" in heads


def test_derived_values_are_grashofs_sums_by_hand():
    """Grashof: s + l - (p + q) = 40 + 120 - (100 + 80) = -20 (a crank-rocker)."""
    scene = load_scene("templates/four_bar.toml")
    params = derived_values(scene)
    assert params["grashof_excess"] == -20.0
    assert {k: params[k] for k in NORTON} == NORTON
    # the folded toggle: law of cosines, crank and coupler folded (120 - 40) between
    # ground 100 and rocker 80, angle at O2 in radians
    fold = math.acos((100**2 + 80**2 - (120 - 40)**2) / (2 * 100 * 80))
    assert math.isclose(params["toggle_fold"], fold, rel_tol=1e-14)
    cells = derived_cells(evaluate_table(scene))
    assert cells["grashof_excess"] == -20.0


def test_compute_is_the_table_as_a_dataframe_with_nan_for_errors():
    inputs = [float(x) for x in range(0, 360, 15)]
    scene = mp_reference.scene_at("four_bar", NON_GRASHOF, inputs)
    frame = compute(scene)
    table = evaluate_table(scene)
    assert list(frame.columns) == headers(table.model)
    ref, _ = mp_reference.solve("four_bar", NON_GRASHOF, inputs, {})
    for i, exact in enumerate(ref["theta_4"]):
        got = frame["theta_4 [deg]"].iloc[i]
        if exact is None:
            assert math.isnan(got) and frame[STATUS].iloc[i] == CANNOT_ASSEMBLE
        else:
            with mp.workdps(50):
                assert abs(((got - float(exact)) + 180) % 360 - 180) < 1e-10
