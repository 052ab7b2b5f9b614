"""batching/summary_only.py: ``--summary-only``'s rows without workbooks, for a block of
four-bar variants: the extremes and figures against the four-bar worked out
independently (tests/fourbar_figures.py: 50-digit extremes, Grashof class and time
ratio by hand), refusals with load_scene's reasons, a varied option (the crossed branch
against the 50-digit crossed four-bar), the block size, and the CSV text parsed back."""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import pytest

import fourbar_figures as ref
import mp_reference
from workbook_gen.batching.job import JobSpec
from workbook_gen.batching.summary_only import (BLOCK_ELEMENTS, SummaryJob, block_size,
                                                summary_block, summary_rows)
from workbook_gen.batching.variants import Variant
from workbook_gen.batching.rows import value_columns
from workbook_gen.errors import SceneError
from workbook_gen.pruning import select
from workbook_gen.scene import load_scene

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR = ROOT / "templates" / "four_bar.toml"
SPEC = JobSpec(text=FOUR_BAR.read_text(), source="four_bar.toml", step=15.0,
               stem="four_bar")
INPUTS = [float(x) for x in range(0, 361, 15)]
LENGTHS = [25.0, 40.0, -3.0, 75.0]      # the third refused, the fourth non-Grashof
VARIANTS = [Variant(i + 1, f"l_O1A={x:g}", (("l_O1A", x),)) for i, x in enumerate(LENGTHS)]


@pytest.fixture(scope="module")
def block():
    return summary_block(SPEC, VARIANTS)


def test_each_variant_against_the_reference(block):
    for v, length in enumerate(LENGTHS):
        if length <= 0:
            continue
        params = ref.NORTON | {"l_O1A": length}
        found, missing = ref.extremes(params, INPUTS)
        for name, (lo, lo_at, hi, hi_at) in found.items():
            assert ref.close(block[f"{name}_min"][v], lo), (v, name)
            assert ref.close(block[f"{name}_max"][v], hi), (v, name)
            assert (block[f"{name}_min_at"][v], block[f"{name}_max_at"][v]) == (lo_at, hi_at)
        assert block["rows_not_assembled"][v] == missing
        assert block["status"][v] == ("partial" if missing else "ok")
        assert block["grashof_class"][v] == ref.grashof_class(params)
    assert math.isclose(block["time_ratio"][1], ref.time_ratio(ref.NORTON), rel_tol=1e-12)
    assert block["status"][3] == "partial"     # 75 + 120 > 100 + 80
    assert block["file"] == [""] * 4 and block["audit"] == [""] * 4


def test_a_refused_variant_has_generates_reason_and_no_numbers(block):
    with pytest.raises(SceneError) as caught:
        load_scene(FOUR_BAR, {"l_O1A": -3.0}, step=15.0)
    assert block["status"][2] == "refused: " + str(caught.value).split(": ", 1)[1]
    assert math.isnan(block["y_C_max"][2]) and block["rows_not_assembled"][2] is None


def test_nothing_assembles_is_refused():
    out = summary_block(SPEC, [Variant(1, "a", (("l_AB", 5.0),)),
                               Variant(2, "b", (("l_AB", 5.0), ("l_O2B", 5.0)))])
    assert out["status"][0] == "partial"
    assert out["status"][1].startswith("refused: cannot be assembled anywhere in the sweep")
    assert math.isnan(out["x_C_min"][1])


def test_a_varied_option_uses_that_branch():
    scene = load_scene(FOUR_BAR, step=15.0)
    values = tuple(value_columns(select(scene.template, scene.outputs)))
    job = SummaryJob(SPEC, ("branch",), values=values, options=("branch",),
                     text_options=frozenset({"branch"}), defaults=(("branch", "open"),))
    data, text = summary_rows(job, [Variant(1, "open", (("branch", "open"),)),
                                    Variant(2, "crossed", (("branch", "crossed"),))])
    exact, _ = mp_reference.solve("four_bar", ref.NORTON, INPUTS, {"branch": "crossed"})
    ys = [float(y) for y in exact["y_C"]]
    assert ref.close(data["y_C_max"][1], max(ys)) and ref.close(data["y_C_min"][1], min(ys))
    found, _ = ref.extremes(ref.NORTON, INPUTS)
    assert ref.close(data["y_C_max"][0], found["y_C"][2])
    assert data["branch"] == ["open", "crossed"]
    rows = list(csv.reader(io.StringIO(text.csv)))
    assert [r[0] for r in rows] == ["open", "crossed"] and rows[1][3] == "crossed"


def test_csv_text_of_a_consecutive_block(block):
    job = SummaryJob(SPEC, ("l_O1A",))
    data, text = summary_rows(job, VARIANTS[:2])
    rows = list(csv.reader(io.StringIO(text.csv)))
    assert len(rows) == 2 and rows[0][0] == "l_O1A=25" and float(rows[0][3]) == 25.0
    assert rows[0][2] == "ok"
    assert summary_rows(job, [VARIANTS[0], VARIANTS[3]])[1] is None   # not consecutive


def test_block_size():
    assert block_size(SPEC) == BLOCK_ELEMENTS // len(INPUTS) == 65536 // 25
