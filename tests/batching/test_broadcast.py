"""batching/broadcast.py: a Plan evaluates many four-bar variants at once, flattened
variant after variant; each variant's columns against the 50-digit reference
(tests/mp_reference.py), the derived values by hand (Grashof's s + l - (p + q)), the
status where the reference cannot assemble, and, as the module promises, the same bits
as evaluating each variant's Table alone."""

from __future__ import annotations

import numpy as np
import pytest

import fourbar_figures as ref
import mp_reference
from workbook_gen.batching.broadcast import Plan
from workbook_gen.scene import load_scene
from workbook_gen.tabulate.table import CANNOT_ASSEMBLE, evaluate_table, status_texts

INPUTS = [float(x) for x in range(0, 360, 20)]
VARIANTS = [ref.NORTON, ref.NORTON | {"l_O1A": 30.0, "omega_2": -4.0},
            ref.NORTON | {"l_O1A": 60.0, "l_AB": 40.0, "l_O2B": 60.0}]


@pytest.fixture(scope="module")
def evaluated():
    scene = mp_reference.scene_at("four_bar", ref.NORTON, INPUTS)
    plan = Plan(scene)
    names = list(plan.parameters)
    values = {n: np.array([float(p.get(n, scene.parameters[n])) for p in VARIANTS])
              for n in names}
    params = plan.parameters_of(values, len(VARIANTS))
    columns, status = plan.evaluate(params, np.array(INPUTS), len(VARIANTS))
    return plan, params, columns, status_texts(status)


def test_derived_values_per_variant_by_hand(evaluated):
    _, params, _, _ = evaluated
    for v, p in enumerate(VARIANTS):
        links = sorted((p["l_O1O2"], p["l_O1A"], p["l_AB"], p["l_O2B"]))
        assert params["grashof_excess"][v] == links[0] + links[3] - links[1] - links[2]


def test_each_variants_columns_are_the_50_digit_four_bar(evaluated):
    _, _, columns, status = evaluated
    n = len(INPUTS)
    for v, p in enumerate(VARIANTS):
        exact, singular = mp_reference.solve("four_bar", p, INPUTS, {"branch": "open"})
        part = slice(v * n, (v + 1) * n)
        assert [s == CANNOT_ASSEMBLE for s in status[part]] == \
            [e is None for e in exact["theta_3"]]
        for name in ("omega_3", "alpha_4", "x_C", "vy_C", "ay_C"):
            got, err = columns[name].val[part], columns[name].err[part]
            scale = max(abs(float(e)) for e in exact[name] if e is not None)
            for i, e in enumerate(exact[name]):
                if e is None or singular[i]:
                    continue
                assert err[i] == 0 and abs(got[i] - float(e)) <= 1e-11 * scale, (v, name, i)
    assert (status == CANNOT_ASSEMBLE).any() and (status == "ok").any()


def test_the_same_bits_as_each_table_alone(evaluated):
    plan, _, columns, status = evaluated
    n = len(INPUTS)
    for v, p in enumerate(VARIANTS):
        table = evaluate_table(mp_reference.scene_at("four_bar", p, INPUTS))
        part = slice(v * n, (v + 1) * n)
        assert list(status[part]) == list(table.status)
        for q in plan.model.columns:
            a, b = columns[q.name], table.columns[q.name]
            assert np.array_equal(a.err[part], b.err), q.name
            ok = b.err == 0
            assert np.array_equal(a.val[part][ok], b.val[ok]), q.name


def test_parameter_only_subtrees_are_computed_per_variant():
    plan = Plan(load_scene("templates/four_bar.toml"))
    hoisted = [name for name, _ in plan._variant_steps]
    assert hoisted, "subtrees of parameters only are computed once per variant"
    assert all(name.startswith("\x00") for name in hoisted)
