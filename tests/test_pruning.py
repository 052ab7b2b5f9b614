"""workbook_gen/pruning.py: a scene asking for some outputs gets exactly the columns those
need: closed (every kept tree refers only to the input, parameters and kept columns),
minimal (each kept column is needed by a requested one or the status), and computing
the same numbers, to the bit, as the whole template does (random subsets of every
template's outputs, each scene written as a TOML file with its [outputs] replaced)."""

from __future__ import annotations

import random
import re

import numpy as np
import pytest

from workbook_gen import compute, load_scene
from workbook_gen.expr import variables
from workbook_gen.pruning import needed, select

TEMPLATES = ["slider_crank", "sewing_machine", "four_bar", "walking_beam", "actuator_linkage",
             "five_bar"]


def with_outputs(tmp_path, template: str, names: list[str]):
    text = open(f"templates/{template}.toml", encoding="utf-8").read()
    text = re.sub(r"\[outputs\]\nquantities = \[[^\]]*\]",
                  "[outputs]\nquantities = [" + ", ".join(f'"{n}"' for n in names) + "]",
                  text)
    path = tmp_path / f"{template}.toml"
    path.write_text(text, encoding="utf-8")
    return load_scene(path)


@pytest.mark.parametrize("template", TEMPLATES)
def test_pruned_models_are_closed_minimal_and_compute_the_same(template, tmp_path):
    full = load_scene(f"templates/{template}.toml")
    whole = compute(full)
    outputs = list(full.template.outputs)
    rng = random.Random(template)
    for _ in range(4):
        names = rng.sample(outputs, rng.randint(1, min(4, len(outputs))))
        model = select(full.template, tuple(names))
        kept = {q.name for q in model.columns}
        known = kept | {full.template.input.name} | set(full.parameters)
        for q in model.columns:
            assert variables(q.expr) <= known, (q.name, variables(q.expr) - known)
        assert kept == needed(full.template, set(names) | variables(model.status))
        part = compute(with_outputs(tmp_path, template, names))
        assert {c.split(" [")[0] for c in part.columns} >= set(names)
        for column in part.columns:   # every kept column, the status, the outputs
            a, b = part[column].to_numpy(), whole[column].to_numpy()
            if a.dtype.kind == "f":
                assert np.array_equal(a, b, equal_nan=True), column
            else:
                assert (a == b).all(), column
