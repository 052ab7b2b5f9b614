"""workbook/conditions.py: the design conditions below the Checks' residuals, written for
the bare 4-DOF parallel mechanism (its balancing conditions, docs/mechanisms.md:
m_i1 u_i1 + m_i2 l_i1 (l_i2 - xi_i)/l_i2 = 0 and m_i1 v_i1 = 0 per leg), recalculated by
LibreOffice and compared with those sums worked out by hand from the parameters; the
cached values are LibreOffice's; a template without conditions writes none."""

from __future__ import annotations

import math

import openpyxl
import pytest

from workbook_gen.engines.libreoffice import recalculated_values
from workbook_gen.scene import load_scene
from workbook_gen.workbook.conditions import SKIP
from workbook_gen.workbook.layout import CHECK_FIRST_ROW, CHECKS

STEP = 60.0                       # 0, 60, ..., 360: 7 rows
ROWS = 7
# leg 1 balanced along xi by hand: u_11 = -m_12 l_11 (l_12 - xi_1) / (m_11 l_12)
U_11 = -1.2 * 0.3 * (0.46 - 0.2) / (1.0 * 0.46)
SCENE = ("templates/parallel_4dof.toml", {"u_11": U_11})


@pytest.fixture(scope="module")
def book(generate, libreoffice):
    path = generate(SCENE[0], overrides=SCENE[1], step=STEP)
    sheet = openpyxl.load_workbook(path)[CHECKS]
    cached = openpyxl.load_workbook(path, data_only=True)[CHECKS]
    return sheet, cached, recalculated_values(path)[CHECKS]


def _by_hand() -> dict[str, tuple[float, float]]:
    """{condition: (residual, scale)} of the eight leg conditions, from the parameters."""
    p = load_scene(SCENE[0], SCENE[1], step=STEP).parameters
    out = {}
    for i in range(1, 5):
        terms = [p[f"m_{i}1"] * p[f"u_{i}1"],
                 p[f"m_{i}2"] * p[f"l_{i}1"] * (p[f"l_{i}2"] - p[f"xi_{i}"]) / p[f"l_{i}2"]]
        out[f"leg{i}_xi"] = (sum(terms), sum(abs(t) for t in terms))
        eta = p[f"m_{i}1"] * p[f"v_{i}1"]
        out[f"leg{i}_eta"] = (eta, abs(eta))
    return out


def _first_row() -> int:
    """1-based row of the "design conditions" label: SKIP rows below the last residual."""
    return CHECK_FIRST_ROW + ROWS - 1 + SKIP


def test_the_block_sits_below_the_residuals(book):
    sheet, _, _ = book
    top = _first_row()
    assert SKIP == 2 and top == 16
    assert sheet.cell(top - 1, 1).value is None                 # the blank row
    assert sheet.cell(top, 1).value == "design conditions"
    assert sheet.cell(top + 1, 1).value == "all conditions"
    assert [sheet.cell(top + 2, c).value for c in range(1, 8)] == [
        "condition", "residual", "unit", "scale", "|residual|/scale", "result", "description"]
    names = [sheet.cell(top + 3 + k, 1).value for k in range(12)]
    assert names[:8] == [f"leg{i}_{a}" for i in range(1, 5) for a in ("xi", "eta")]
    assert sheet.cell(top + 3, 3).value == "kg*m"
    assert sheet.cell(top + 3 + 12, 1).value is None             # 12 conditions, no more
    r = top + 3
    assert sheet.cell(r, 5).value == f"=IF(D{r}=0,0,ABS(B{r})/D{r})"
    assert sheet.cell(r, 6).value == f'=IF(E{r}<=check_tol,"PASS","FAIL")'


def test_libreoffice_gives_the_hand_sums(book):
    sheet, _, recalculated = book
    top = _first_row()
    expected = _by_hand()
    for k in range(12):
        r = top + 3 + k
        name = sheet.cell(r, 1).value
        value, scale = (recalculated[f"{col}{r}"] for col in "BD")
        relative, result = recalculated[f"E{r}"], recalculated[f"F{r}"]
        if name in expected:
            want, want_scale = expected[name]
            assert math.isclose(value, want, rel_tol=1e-12, abs_tol=1e-15), name
            assert math.isclose(scale, want_scale, rel_tol=1e-12), name
        want_relative = 0.0 if scale == 0 else abs(value) / scale
        assert math.isclose(relative, want_relative, rel_tol=1e-12, abs_tol=1e-15), name
        assert result == ("PASS" if relative <= 1e-9 else "FAIL"), name
    # leg 1 balanced along xi (by U_11), m_i1 v_i1 = 0: those pass; leg 2 does not
    verdicts = {sheet.cell(top + 3 + k, 1).value: recalculated[f"F{top + 3 + k}"]
                for k in range(12)}
    assert verdicts["leg1_xi"] == verdicts["leg1_eta"] == "PASS"
    assert verdicts["leg2_xi"] == "FAIL"
    assert recalculated[f"B{top + 1}"] == "FAIL"


def test_the_cached_values_are_libreoffices(book):
    _, cached, recalculated = book
    top = _first_row()
    assert cached.cell(top + 1, 2).value == recalculated[f"B{top + 1}"]
    for r in range(top + 3, top + 15):
        for col in "BDEF":
            ours, theirs = cached[f"{col}{r}"].value, recalculated[f"{col}{r}"]
            if isinstance(theirs, float):
                assert math.isclose(ours, theirs, rel_tol=1e-12, abs_tol=1e-15), (col, r)
            else:
                assert ours == theirs, (col, r)


def test_no_conditions_no_block(generate):
    path = generate("templates/four_bar.toml", step=STEP)
    sheet = openpyxl.load_workbook(path, read_only=True)[CHECKS]
    labels = [row[0] for row in sheet.iter_rows(values_only=True)]
    assert "design conditions" not in labels
    assert len(labels) == CHECK_FIRST_ROW + ROWS - 1
