"""Sweeps that start anywhere in -720..720 deg, and angle parameters of any size, pass the
workbook's own audit, reference model included (issue 21 item 4): the reference model and
the workbook may choose different turns of one angle, and an angle is compared modulo a
whole turn.  A wrong angle (half a turn off) still fails."""

from __future__ import annotations

import numpy as np
import pytest

from workbook_gen import audit, load_scene, write_workbook
from workbook_gen.auditor.mechanics import TURN, _apart

ROOT = __import__("pathlib").Path(__file__).resolve().parents[2]

CASES = [
    ("sewing_machine", {}, -540.0, 0.0),
    ("four_bar", {}, -720.0, None),
    ("slider_crank", {}, -720.0, None),
    ("slider_crank", {"phi_slide": 720.0}, None, None),
    ("slider_crank", {"phi_slide": -1080.0}, 360.0, 720.0),
]


@pytest.mark.parametrize("template,overrides,start,stop", CASES)
def test_far_angles_pass_the_reference_model(template, overrides, start, stop, tmp_path):
    kwargs = {k: v for k, v in (("start", start), ("stop", stop)) if v is not None}
    scene = load_scene(ROOT / "templates" / f"{template}.toml", overrides=overrides, **kwargs)
    report = audit(write_workbook(scene, tmp_path))
    failing = [q.name for q in report.mechanics.quantities if not q.ok]
    assert failing == [] and report.ok, (failing, report.mechanics.quantities[:3])


def test_angles_apart_modulo_a_turn_but_not_other_quantities():
    ours = np.array([359.0, -540.0, 10.0, 190.0])
    ref = np.array([-1.0, 180.0, 10.0, 10.0])
    assert np.allclose(np.abs(_apart(ours, ref, TURN["deg"])), [0.0, 0.0, 0.0, 180.0])
    assert np.allclose(_apart(ours, ref, None), ours - ref)
    assert abs(_apart(np.array([2 * np.pi]), np.array([0.0]), TURN["rad"])[0]) < 1e-15
