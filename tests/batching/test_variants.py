"""batching/variants.py: the variants of ``--vary`` specs are the full factorial of
their levels in the order given, the last varying fastest (itertools.product), grids
inclusive of their stop (numpy), random samples numpy's ``default_rng(seed)`` drawn spec
by spec; ``ColumnVariants`` indexes, slices and iterates as the tuple it stands for;
design files give one variant per row (written here by csv and openpyxl)."""

from __future__ import annotations

import csv
import itertools

import numpy as np
import pytest

from workbook_gen.batching.variants import ColumnVariants, from_design, from_specs
from workbook_gen.errors import SceneError
from workbook_gen.mechanisms import get_template

PARAMS = ["l_AB", "l_BC", "e", "omega_1"]


def test_a_grid_factorial_as_itertools_product():
    design = from_specs(["l_AB=30:40:2.5", "l_BC=100,110", "e=-1:1:1"], PARAMS)
    grids = [np.arange(30, 40 + 1e-9, 2.5).tolist(), [100.0, 110.0], [-1.0, 0.0, 1.0]]
    want = list(itertools.product(*grids))
    got = [tuple(v for _, v in variant.values) for variant in design.variants]
    assert got == want and design.kind == "grid" and len(design) == 5 * 2 * 3
    assert [v.index for v in design.variants] == list(range(1, len(want) + 1))
    assert [n for n, _ in design.variants[0].values] == ["l_AB", "l_BC", "e"]


def test_a_grids_stop_is_kept_within_1e_9():
    design = from_specs(["l_AB=0.1:0.3:0.1"], PARAMS)   # 0.1 + 2*0.1 != 0.3 in floats
    assert len(design) == 3
    assert [v.values[0][1] for v in design.variants] == pytest.approx([0.1, 0.2, 0.3])


def test_random_samples_are_numpys_draws():
    design = from_specs(["l_AB=normal:32:0.5", "e=uniform:-2:2"], PARAMS, samples=50, seed=7)
    rng = np.random.default_rng(7)
    a, b = rng.normal(32, 0.5, 50), rng.uniform(-2, 2, 50)
    got = np.array([[v for _, v in variant.values] for variant in design.variants])
    assert design.kind == "random" and np.array_equal(got, np.stack([a, b], axis=1))


def test_column_variants_behave_as_their_tuple():
    columns = [np.arange(10, dtype=float), np.arange(10, dtype=float) * 2]
    cv = ColumnVariants(("a", "b"), columns)
    whole = tuple(cv)
    assert len(cv) == 10 and whole[3] == cv[3] == cv[-7]
    assert tuple(cv[2:5]) == whole[2:5] and cv[2:5][0].index == 3
    assert cv[::3] == whole[::3]
    with pytest.raises(IndexError):
        cv[10]


def test_options_vary_like_parameters():
    options = get_template("four_bar").options
    design = from_specs(["branch=open,crossed", "l_AB=100,110"],
                        ["l_AB", "l_BC"], options=options)
    assert [tuple(v for _, v in x.values) for x in design.variants] == \
        list(itertools.product(["open", "crossed"], [100.0, 110.0]))
    assert design.options == ("branch",)


@pytest.mark.parametrize("specs, kwargs, words", [
    (["nope=1,2"], {}, "nope"),
    (["l_AB=1:0:1"], {}, "l_AB"),
    (["l_AB=normal:1:1"], {}, "--samples"),
    (["l_AB=normal:1:1", "e=1,2"], {"samples": 3}, "cannot"),
    (["l_AB=1,2"], {"seed": 3}, "--seed"),
])
def test_bad_specs_are_one_scene_error(specs, kwargs, words):
    with pytest.raises(SceneError, match=words):
        from_specs(specs, PARAMS, **kwargs)


def test_a_design_file_one_variant_per_row(tmp_path):
    path = tmp_path / "design.csv"
    with open(path, "w", newline="") as f:
        csv.writer(f).writerows([["variant", "l_AB", "e"], ["short", "30", ""],
                                 ["long", "40.5", "2"]])
    design = from_design(path, PARAMS)
    assert design.kind == "design" and len(design) == 2
    assert [v.label for v in design.variants] == ["short", "long"]
    assert dict(design.variants[1].values) == {"l_AB": 40.5, "e": 2.0}
    assert "e" not in dict(design.variants[0].values)   # an empty cell keeps the scene's
