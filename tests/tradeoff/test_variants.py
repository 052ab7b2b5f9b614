"""variants: the minimal TOML writer reads back with tomllib (the standard library's
TOML 1.0 reader) to the same data, and a variant is the scene re-parsed with only the
named keys replaced (the command line's --set re-applied, the variant's options winning)."""

from __future__ import annotations

import math
import tomllib

import pytest

from workbook_gen.scene import load_scene
from workbook_gen.tradeoff.variants import dumps, variant

FIVE_BAR = "templates/five_bar.toml"


def test_dumps_reads_back_with_tomllib():
    data = {"name": 'say "hi" \\ there', "count": 3, "flag": False, "ratio": 0.1,
            "tiny": 1e-300, "big": 1.5e300, "neg": -0.0,
            "outputs": {"quantities": ["y_C", "v_C"]},
            "masses": {"crank": {"m": 1.0, "u": 2.5, "v": -0.5}}}
    text = dumps(data)
    back = tomllib.loads(text)
    assert back == data
    assert math.copysign(1, back["neg"]) == -1
    assert text.index("name =") < text.index("[outputs]")  # top-level keys first
    assert "masses = " not in text and "[masses]" in text


@pytest.mark.parametrize("bad, error", [(float("nan"), ValueError), (float("inf"), ValueError),
                                        (None, TypeError), ((1, 2), TypeError)])
def test_dumps_refuses_what_toml_cannot_hold(bad, error):
    with pytest.raises(error):
        dumps({"x": bad})


def test_variant_replaces_only_the_named_keys():
    scene = load_scene(FIVE_BAR)
    other = variant(scene, step=2.5, options={"method": "newton", "iterations": 3},
                    parameters={"R_path": 0.25}, outputs=("theta_1", "th1_3"))
    assert (other.sweep.start, other.sweep.stop, other.sweep.step) == (0.0, 360.0, 2.5)
    assert other.sweep.rows == 145  # 360 / 2.5 + 1
    assert other.options["method"] == "newton" and other.options["iterations"] == 3
    assert other.parameters["R_path"] == 0.25
    assert {k: v for k, v in other.parameters.items() if k != "R_path"} == {
        k: v for k, v in scene.parameters.items() if k != "R_path"}
    assert other.outputs == ("theta_1", "th1_3")
    assert other.name == scene.name and other.template.id == "five_bar"
    same = variant(scene)
    assert same.outputs == scene.outputs and same.sweep == scene.sweep
    assert same.parameters == scene.parameters


def test_command_line_settings_are_kept_but_the_variants_options_win():
    scene = load_scene(FIVE_BAR, {"l_2": 1.05, "iterations": 5}, start=10.0, stop=100.0,
                       name="renamed")
    other = variant(scene, options={"method": "newton", "iterations": 7})
    assert other.parameters["l_2"] == 1.05
    assert other.options["iterations"] == 7
    assert (other.sweep.start, other.sweep.stop) == (10.0, 100.0) and other.name == "renamed"
    kept = variant(scene, options={"method": "newton"})
    assert kept.options["iterations"] == 5
