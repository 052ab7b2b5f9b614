"""batching/job.py: one variant in, (workbook bytes, summary row) out.  The row's
extremes and figures against the four-bar worked out independently
(tests/fourbar_figures.py: 50-digit extremes, Grashof class and time ratio by hand),
the workbook read back with openpyxl (the varied parameter on the Parameters sheet, the
About sheet naming the batch's path), refusals with generate's reasons."""

from __future__ import annotations

import io
import math
from pathlib import Path

import openpyxl
import pytest

import fourbar_figures as ref
from workbook_gen.batching.job import (JobSpec, refused_reason, run_chunk, run_variant,
                                       unassembled_reason, variant_scene)
from workbook_gen.batching.variants import Variant
from workbook_gen.errors import SceneError
from workbook_gen.scene import load_scene

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR = ROOT / "templates" / "four_bar.toml"
SPEC = JobSpec(text=FOUR_BAR.read_text(), source="four_bar.toml",
               sets=(("l_O2B", 85.0),), step=30.0, folder="out/four_bar-batch",
               stem="four_bar", width=3)
INPUTS = [float(x) for x in range(0, 361, 30)]   # the sweep holds its stop


@pytest.fixture(scope="module")
def outcomes():
    return run_chunk(SPEC, [Variant(1, "l_O1A=35", (("l_O1A", 35.0),)),
                            Variant(2, "l_O1A=-1", (("l_O1A", -1.0),)),
                            Variant(3, "short", (("l_AB", 5.0), ("l_O2B", 5.0)))])


def test_names_and_overrides():
    v = Variant(7, "x", (("l_O1A", 35.0), ("l_O2B", 90.0)))
    assert SPEC.file_stem(v) == "four_bar-007" and SPEC.file_name(v) == "four_bar-007.xlsx"
    assert SPEC.overrides(v) == {"l_O2B": 90.0, "l_O1A": 35.0}   # the variant's last
    scene = variant_scene(SPEC, v)
    assert scene.name == "four_bar-007" and scene.parameters["l_O2B"] == 90.0
    assert scene.sweep.step == 30.0


def test_the_row_is_the_reference(outcomes):
    out = outcomes[0]
    params = ref.NORTON | {"l_O1A": 35.0, "l_O2B": 85.0}
    found, missing = ref.extremes(params, INPUTS)
    assert missing == 0 and out.index == 1
    for name, (lo, lo_at, hi, hi_at) in found.items():
        assert ref.close(out.row[f"{name}_min"], lo) and ref.close(out.row[f"{name}_max"], hi)
        assert (out.row[f"{name}_min_at"], out.row[f"{name}_max_at"]) == (lo_at, hi_at)
    assert out.row["grashof_class"] == ref.grashof_class(params) == "Grashof crank-rocker"
    assert math.isclose(out.row["time_ratio"], ref.time_ratio(params), rel_tol=1e-12)
    assert out.row["status"] == "ok" and out.row["rows_not_assembled"] == 0
    assert out.row["file"] == "four_bar-001.xlsx" and out.row["audit"] == ""


def test_the_workbook_read_back(outcomes):
    wb = openpyxl.load_workbook(io.BytesIO(outcomes[0].data))
    params = {row[0]: row[1] for row in wb["Parameters"].iter_rows(values_only=True)
              if row and isinstance(row[0], str)}
    assert params["l_O1A"] == 35.0 and params["l_O2B"] == 85.0
    about = " ".join(str(c) for row in wb["About"].iter_rows(values_only=True) for c in row
                     if c is not None)
    assert "four_bar-001.xlsx" in about
    table = wb["Table"]
    assert table.max_row == 1 + len(INPUTS)


def test_refusals_give_generates_reasons(outcomes):
    bad, short = outcomes[1], outcomes[2]
    assert bad.data is None and short.data is None
    with pytest.raises(SceneError) as caught:
        load_scene(FOUR_BAR, {"l_O2B": 85.0, "l_O1A": -1.0}, step=30.0)
    reason = str(caught.value).split(": ", 1)[1]
    assert bad.row == {"status": f"refused: {reason}", "file": ""}
    assert short.row["status"].startswith("refused: cannot be assembled anywhere in the "
                                          "sweep 0..360")
    assert refused_reason(SPEC, SceneError("four_bar.toml: a reason")) == "a reason"
    assert refused_reason(SPEC, SceneError("elsewhere: x")) == "elsewhere: x"
    scene = variant_scene(SPEC, Variant(3, "short", (("l_AB", 5.0), ("l_O2B", 5.0))))
    assert unassembled_reason(scene) == short.row["status"][len("refused: "):]


def test_audited_when_asked():
    spec = JobSpec(SPEC.text, SPEC.source, SPEC.sets, 60.0, SPEC.folder, SPEC.stem, 3,
                   audit=True)
    assert run_variant(spec, Variant(1, "a", ())).row["audit"] == "ok"
