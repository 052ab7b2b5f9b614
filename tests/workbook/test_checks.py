"""workbook/checks.py: the Checks sheet of a four-bar that cannot assemble over part of
its turn, recalculated by LibreOffice (one run for two files): the residuals are the loop
closure recomputed with numpy from the 50-digit angles (tests/mp_reference.py), "n/a"
where the row is not ok, the flags where the reference has no solution; a copy whose
theta_3 is off by 0.01 deg in one row FAILs with the numpy residual of that row; the
cached values are LibreOffice's; the sheet's fixed cells and widths by hand."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import openpyxl
import pytest

import mp_reference
from workbook_gen.engines.libreoffice import recalculated_values_many
from workbook_gen.scene import load_scene
from workbook_gen.workbook.checks import FLAG_HEADERS, TOLERANCE_NAME, sheet_widths
from workbook_gen.workbook.layout import CHECK_FIRST_ROW, CHECKS, TABLE

OVERRIDES = {"l_O1A": 60.0, "l_AB": 40.0, "l_O2B": 60.0}   # ground 100: |theta_2| <= 72.5 deg
STEP = 15.0
INPUTS = [float(x) for x in range(0, 361, 15)]
BAD = 3                                                   # the corrupted row (45 deg)
SHIFT = 0.01


@pytest.fixture(scope="module")
def reference():
    params = load_scene("templates/four_bar.toml", OVERRIDES, step=STEP).parameters
    return params, mp_reference.solve("four_bar", params, INPUTS, {"branch": "open"})[0]


@pytest.fixture(scope="module")
def books(generate, libreoffice, reference, tmp_path_factory):
    path = generate("templates/four_bar.toml", overrides=OVERRIDES, step=STEP)
    # the copy: Table's theta_3 in row BAD replaced by the 50-digit angle + SHIFT
    _, ref = reference
    wb = openpyxl.load_workbook(path)
    table = wb[TABLE]
    col = [c.value for c in table[1]].index("theta_3 [deg]") + 1
    assert ref["theta_3"][BAD] is not None
    table.cell(BAD + 2, col).value = float(ref["theta_3"][BAD]) + SHIFT
    corrupted = tmp_path_factory.mktemp("corrupted") / "corrupted.xlsx"
    wb.save(corrupted)
    good, bad = recalculated_values_many([path, corrupted])
    return SimpleNamespace(
        sheet=openpyxl.load_workbook(path)[CHECKS],
        cached=openpyxl.load_workbook(path, data_only=True)[CHECKS],
        good=good[CHECKS], bad=bad[CHECKS])


def _closure(params, t2, t3, t4) -> float:
    """|O1A + AB - O1O2 - O2B| / l_O1O2 with numpy."""
    a, b, c, g = (params[k] for k in ("l_O1A", "l_AB", "l_O2B", "l_O1O2"))
    r = np.radians
    dx = a * np.cos(r(t2)) + b * np.cos(r(t3)) - g - c * np.cos(r(t4))
    dy = a * np.sin(r(t2)) + b * np.sin(r(t3)) - c * np.sin(r(t4))
    return float(np.hypot(dx, dy) / g)


def test_the_fixed_cells(books):
    s = books.sheet
    assert (s["A1"].value, s["B1"].value) == ("tolerance", 1e-9)
    assert s.parent.defined_names[TOLERANCE_NAME].attr_text == f"{CHECKS}!$B$1"
    assert s["B2"].value == '=IF(MAX(B4:G4)<=check_tol,"PASS","FAIL")'
    last = CHECK_FIRST_ROW + len(INPUTS) - 1
    assert s["B4"].value == f"=MAX(MAX(B{CHECK_FIRST_ROW}:B{last}),-MIN(B{CHECK_FIRST_ROW}:B{last}))"
    assert s["C5"].value == '=IF(C4<=check_tol,"PASS","FAIL")'
    heads = [c.value for c in s[CHECK_FIRST_ROW - 1]]
    assert heads[:9] == ["theta_2 [deg]", "loop_position", "loop_velocity",
                         "loop_acceleration", "coupler_point_position",
                         "coupler_point_velocity", "coupler_point_acceleration",
                         *FLAG_HEADERS]
    assert all(h.startswith("term ") for h in heads[9:]) and len(heads) > 9
    assert [c.value for c in s[6]][1:4] == ["position", "velocity", "acceleration"]


def test_libreoffice_residuals_are_the_numpy_closure(books, reference):
    params, ref = reference
    compared = 0
    for i, x in enumerate(INPUTS):
        row = CHECK_FIRST_ROW + i
        got = books.good[f"B{row}"]
        if ref["theta_3"][i] is None:
            assert got == "n/a" and books.good[f"H{row}"] == 1, x
            continue
        assert books.good[f"H{row}"] == 0
        if books.good[f"I{row}"] == 1:                 # flagged: a toggle
            assert got == "n/a"
            continue
        want = _closure(params, x, float(ref["theta_3"][i]), float(ref["theta_4"][i]))
        assert abs(got - want) <= 1e-13, x
        compared += 1
    assert compared >= 8
    assert any(ref["theta_3"][i] is None for i in range(len(INPUTS)))
    assert books.good["B2"] == "PASS" and books.good["B5"] == "PASS"


def test_a_wrong_angle_fails(books, reference):
    params, ref = reference
    row = CHECK_FIRST_ROW + BAD
    want = _closure(params, INPUTS[BAD], float(ref["theta_3"][BAD]) + SHIFT,
                    float(ref["theta_4"][BAD]))
    assert want > 1e-6
    assert math.isclose(books.bad[f"B{row}"], want, rel_tol=1e-9)
    assert math.isclose(books.bad["B4"], want, rel_tol=1e-9)
    assert books.bad["B5"] == "FAIL" and books.bad["B2"] == "FAIL"


def test_the_cached_values_are_libreoffices(books):
    for row in range(2, CHECK_FIRST_ROW + len(INPUTS)):
        for col in "BCDEFGHIJK":
            theirs = books.good.get(f"{col}{row}")
            if theirs is None and f"{col}{row}" not in books.good:
                continue
            ours = books.cached[f"{col}{row}"].value
            if isinstance(theirs, float):
                assert abs(ours - theirs) <= 1e-12 * max(1.0, abs(theirs)), (col, row)
            else:
                assert ours == theirs, (col, row)


def test_sheet_widths_by_hand():
    def check(name, description):
        return SimpleNamespace(name=name, description=description)
    short = check("loop", "a b")
    long_name = check("x" * 30, "short")
    wordy = check("c", " ".join(["word"] * 40))   # 40 words of 4: 199 characters
    widths = sheet_widths([short, long_name, wordy], ["t " * 3])
    assert widths[0] == 14                       # at least 14
    assert widths[1] == 32                       # its name and 2
    # 199 characters in 4 lines of whole words: 10 words a line at 49+, over the
    # 24 most: capped at 24
    assert widths[2] == 24
    assert widths[3] == 14
    # a term's text of 30 words of 5 letters (179 characters) fits 4 lines at 45
    # characters (7 words of 6 = 41 too narrow: 8 words need 47): widened up to 48
    text = " ".join(["abcde"] * 30)
    (w,) = sheet_widths([], [text])
    lines_at = lambda width: -(-30 // ((width + 1) // 6))
    assert lines_at(w) <= 4 and lines_at(w - 1) > 4
