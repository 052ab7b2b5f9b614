"""tabulate computes everything a workbook shows, workbook/ places it (issue 23 item 3):
the one extremes rule against a plain loop (first ok row, ties, errors, many variants), and
the cached values of the Checks, Summary and Parameters cells, read back with openpyxl,
are ``evaluate(scene)``'s values in their places.  The values themselves are checked
independently elsewhere: the Summary against the Table and LibreOffice
(tests/workbook/test_summary.py), the residuals against the inline trees
(tests/tabulate/test_terms.py)."""

from __future__ import annotations

import math

import numpy as np
import openpyxl
import pytest
from hypothesis import given, settings, strategies as st

from workbook_gen.scene import load_scene
from workbook_gen.tabulate import evaluate
from workbook_gen.tabulate.extremes import ok_extremes
from workbook_gen.workbook import write_workbook

STATUSES = ("ok", "ok", "ok", "dead centre", "cannot assemble")


def _first_extremes(val, err, status, inputs):
    """(lo, lo_at, lo_row, hi, hi_at, hi_row, counted) of one variant, by a plain loop:
    the first ok row without an error that holds each extreme."""
    rows = [i for i in range(len(val)) if status[i] == "ok" and err[i] == 0]
    if not rows:
        return None
    lo = min(val[i] for i in rows)
    hi = max(val[i] for i in rows)
    i_lo = next(i for i in rows if val[i] == lo)
    i_hi = next(i for i in rows if val[i] == hi)
    return lo, inputs[i_lo], i_lo, hi, inputs[i_hi], i_hi, len(rows)


@settings(max_examples=150, deadline=None)
@given(st.integers(1, 4), st.integers(1, 9), st.data())
def test_ok_extremes_are_those_of_the_first_ok_rows_in_every_variant(variants, n, data):
    size = variants * n
    # few distinct values: ties are the rule, so "first row" is what is tested
    val = np.array(data.draw(st.lists(st.sampled_from([-2.5, -0.0, 0.0, 1.0, 3.25]),
                                      min_size=size, max_size=size)))
    err = np.array(data.draw(st.lists(st.sampled_from([0, 0, 0, 6]), min_size=size,
                                      max_size=size)), np.uint8)
    val = np.where(err != 0, np.nan, val)
    status = np.array(data.draw(st.lists(st.sampled_from(STATUSES), min_size=size,
                                         max_size=size)), dtype=object)
    inputs = np.arange(n) * 10.0 + 5.0
    found = ok_extremes(val, err, status, inputs, variants)
    for v in range(variants):
        block = slice(v * n, (v + 1) * n)
        expected = _first_extremes(val[block], err[block], status[block], inputs)
        if expected is None:
            assert found.counted[v] == 0
            assert all(math.isnan(x[v]) for x in (found.lo, found.lo_at, found.hi, found.hi_at))
            continue
        lo, lo_at, lo_row, hi, hi_at, hi_row, counted = expected
        assert (found.lo[v], found.lo_at[v], found.lo_row[v]) == (lo, lo_at, lo_row)
        assert (found.hi[v], found.hi_at[v], found.hi_row[v]) == (hi, hi_at, hi_row)
        assert found.counted[v] == counted


# (template, overrides): flagged rows among ok ones; a template with design conditions
SCENES = [("four_bar", {"l_O2B": 60.0}), ("sewing_machine", {"l_BC": 32.0}),
          ("sewing_machine_masses", {}), ("slider_crank", {"l_BC": 50.0})]


@pytest.fixture(scope="module", params=range(len(SCENES)))
def written(request, tmp_path_factory):
    name, overrides = SCENES[request.param]
    scene = load_scene(f"templates/{name}.toml", overrides=overrides)
    path = write_workbook(scene, tmp_path_factory.mktemp("tabulate"))
    return evaluate(scene), openpyxl.load_workbook(path, data_only=True)


def test_the_summary_caches_what_tabulate_computes(written):
    result, book = written
    sheet = book["Summary"]
    rows = {r[0]: r[1:] for r in sheet.iter_rows(values_only=True) if r[0]}
    values = result.summary
    for q in result.model.outputs():
        found = values.outputs[q.name]
        _unit, hi, at_hi, lo, at_lo = rows[q.name][:5]
        assert (hi, at_hi, lo, at_lo) == (found.hi, found.at_hi, found.lo, found.at_lo), q.name
    for span, value in zip(result.model.spans, values.spans):
        assert rows[f"{span.label} (from the table)"][1] == value
    for figure, value in zip(result.model.figures, values.figures):
        assert rows[figure.label][1] == value, figure.label
    assert rows["rows"][1] == values.rows == result.rows
    assert rows["rows in the extremes"][1] == values.rows_ok == np.sum(result.status == "ok")
    assert rows["rows flagged singular or not converged"][1] == values.rows_flagged
    assert rows["rows that cannot be assembled"][1] == values.rows_not_assembled


def test_the_checks_and_parameters_cache_what_tabulate_computes(written):
    result, book = written
    sheet = book["Checks"]
    checks = result.checks
    header = [c.value for c in sheet[7]]
    if result.model.checks:
        assert sheet["B2"].value == checks.overall
    for col, check in enumerate(result.model.checks, start=2):
        assert header[col - 1] == check.name
        assert sheet.cell(4, col).value == checks.maxima[check.name]
        assert sheet.cell(5, col).value == checks.verdicts[check.name]
        cells = [sheet.cell(8 + i, col).value for i in range(result.rows)]
        assert cells == checks.cells[check.name], check.name
    flags = len(result.model.checks) + 2
    assert [sheet.cell(8 + i, flags).value for i in range(result.rows)] == checks.cannot_assemble
    assert [sheet.cell(8 + i, flags + 1).value for i in range(result.rows)] == checks.flagged
    for term in checks.terms:
        col = header.index(term.name) + 1
        cells = [sheet.cell(8 + i, col).value for i in range(result.rows)]
        assert cells == checks.term_cells[term.name], term.name
    if result.model.conditions:
        below = [r for r in sheet.iter_rows(min_row=8 + result.rows, values_only=True)
                 if r[0] in {c.name for c in result.model.conditions}]
        assert [(r[1], r[3], r[4], r[5]) for r in below] == [
            (c.value, c.scale, c.relative, c.verdict) for c in result.conditions.items]
    params = {r[0]: r[1] for r in book["Parameters"].iter_rows(min_row=2, values_only=True)}
    for name, value in result.derived.items():
        assert params[name] == value, name
