"""four_bar template (docs/mechanisms.md, four_bar): every Table cell against the independent
reference (Newton on the loop closure, rates from the differentiated closure), both branches,
Norton's published angles, toggles, Grashof class, toggle angles and time ratio, the audit and
LibreOffice."""

from __future__ import annotations

import math

import numpy as np
import openpyxl
import pytest

from workbook_gen.reference import solve
from workbook_gen.scene import load_scene
from workbook_cells import as_float, column_error, table_columns

TOLERANCE = 1e-9  # of the column's magnitude
SCENE = "templates/four_bar.toml"
ALWAYS_DEFINED = {"theta_2r", "x_A", "y_A", "d_AO2", "phi_AO2", "f_B", "p2_d2", "d2_q2"}  # numbers even where B is not


@pytest.fixture(scope="module")
def scenes(tmp_path_factory):
    """scene(branch) -> path of four_bar.toml with that branch option."""
    folder = tmp_path_factory.mktemp("scenes")
    text = open(SCENE, encoding="utf-8").read()

    def scene(branch: str = "open") -> str:
        path = folder / f"four_bar_{branch}.toml"
        path.write_text(text.replace('branch = "open"', f'branch = "{branch}"'),
                        encoding="utf-8")
        return str(path)
    return scene


def _compare(path, scene_path, overrides, step, toggle_ok=False):
    scene = load_scene(scene_path, overrides=overrides, step=step)
    cells = table_columns(path)
    inputs = as_float(cells.pop("theta_2"))
    status = np.array(cells.pop("status"))
    reference = solve("four_bar", scene.parameters, inputs, scene.options)
    assembled = status != "cannot assemble"
    assert np.array_equal(assembled, np.isfinite(reference["theta_3"]))
    worst = 0.0
    for name, values in cells.items():
        error = column_error(name, as_float(values), reference[name], assembled, ALWAYS_DEFINED)
        assert error <= TOLERANCE, f"{name}: {error:.3g} of its magnitude"
        worst = max(worst, error)
    if not toggle_ok:
        assert "toggle" not in status
    return status, cells


CASES = [
    ("open", {}, None),
    ("crossed", {}, None),
    ("open", {}, 1.0),
    ("crossed", {"l_AC": 150.0, "delta_C": -75.0, "omega_2": -3.0}, 2.5),
    # double crank (ground shortest, crank longer than the ground: phi follows the crank)
    ("open", {"l_O1O2": 30.0, "l_O1A": 60.0, "l_AB": 70.0, "l_O2B": 80.0}, 5.0),
    ("crossed", {"l_O1O2": 30.0, "l_O1A": 60.0, "l_AB": 70.0, "l_O2B": 80.0}, 5.0),
    # double rocker: rows that cannot be assembled
    ("open", {"l_O1O2": 100.0, "l_O1A": 80.0, "l_AB": 30.0, "l_O2B": 90.0}, 5.0),
    ("crossed", {"l_O1O2": 100.0, "l_O1A": 150.0, "l_AB": 60.0, "l_O2B": 120.0}, 5.0),
]


@pytest.mark.parametrize("branch, overrides, step", CASES)
def test_every_table_cell_matches_the_reference(generate, scenes, branch, overrides, step):
    path = generate(scenes(branch), overrides=overrides, step=step)
    _compare(path, scenes(branch), overrides, step)


@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_toggle_rows_say_so_and_hold_div0_rates(generate, scenes, branch):
    """Change-point linkage 100/40/140/80: at theta_2 = 0 and 360 the coupler folds
    over the rocker (d = l_AB - l_O2B exactly): positions exact, rates singular."""
    overrides = {"l_AB": 140.0}
    path = generate(scenes(branch), overrides=overrides)
    status, cells = _compare(path, scenes(branch), overrides, None, toggle_ok=True)
    toggles = np.flatnonzero(status == "toggle")
    assert toggles.tolist() == [0, len(status) - 1]
    for i in toggles:
        assert cells["omega_3"][i] == "#DIV/0!" and cells["alpha_4"][i] == "#DIV/0!"
        assert cells["mu"][i] == pytest.approx(0.0, abs=1e-12)
    assert set(status[1:-1]) == {"ok"}


def _row(scene_path, theta: float) -> dict[str, float]:
    from workbook_gen.tabulate import compute
    table = compute(load_scene(scene_path))
    row = table[table.iloc[:, 0] == theta].iloc[0]
    return {str(k).split(" ")[0]: v for k, v in row.items()}


@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_norton_example_and_branch_side(scenes, branch):
    """Norton's example: 100/40/120/80 at theta_2 = 40 deg, open: theta_3 = 20.30,
    theta_4 = 57.32 deg with B left of A->O2; crossed: B mirrored in the line A->O2."""
    row = _row(scenes(branch), 40.0)
    a = np.array([row["x_A"], row["y_A"]])
    b = np.array([row["x_B"], row["y_B"]])
    o2 = np.array([100.0, 0.0])
    side = (o2 - a)[0] * (b - a)[1] - (o2 - a)[1] * (b - a)[0]
    if branch == "open":
        assert round(row["theta_3"], 2) == 20.30 and round(row["theta_4"], 2) == 57.32
        assert side > 0
    else:
        assert side < 0
        e = (o2 - a) / np.linalg.norm(o2 - a)
        # the open B by the published angles, mirrored in the line A->O2
        b_open = 120.0 * np.array([math.cos(math.radians(20.2979)),
                                   math.sin(math.radians(20.2979))])
        mirrored = 2 * np.dot(b_open, e) * e - b_open
        assert np.allclose(b - a, mirrored, atol=1e-2)
        assert np.hypot(*(b - o2)) == pytest.approx(80.0, rel=1e-12)


def _summary(path) -> dict[str, object]:
    sheet = openpyxl.load_workbook(path, data_only=True)["Summary"]
    return {r[0]: r[2] for r in sheet.iter_rows(values_only=True) if r[0]}


@pytest.mark.parametrize("lengths, expected", [
    ((100.0, 40.0, 120.0, 80.0), "Grashof crank-rocker"),
    ((30.0, 60.0, 70.0, 80.0), "Grashof double-crank"),
    ((100.0, 80.0, 30.0, 90.0), "Grashof double-rocker"),
    ((100.0, 90.0, 80.0, 30.0), "Grashof crank-rocker"),      # rocker shortest
    ((100.0, 40.0, 140.0, 80.0), "change point"),
    ((100.0, 70.0, 60.0, 90.0), "change point"),             # 60 + 100 = 70 + 90
    ((100.0, 70.0, 50.0, 40.0), "non-Grashof triple-rocker"),
    ((0.1, 0.2, 0.3, 0.2), "change point"),                    # 0.1 + 0.3 vs 0.2 + 0.2
])
def test_grashof_class(generate, lengths, expected):
    names = ("l_O1O2", "l_O1A", "l_AB", "l_O2B")
    overrides = dict(zip(names, lengths)) | {"l_AC": 0.1}
    summary = _summary(generate(SCENE, overrides=overrides, step=30.0))
    assert summary["Grashof class"] == expected


def _omega_4_zeros(params, branch):
    """Crank angles where the rocker stops, by bisection on the reference's omega_4."""
    def w4(theta):
        return solve("four_bar", params, np.atleast_1d(theta), {"branch": branch})["omega_4"]
    grid = np.arange(0.0, 360.0, 0.5)
    values = w4(grid)
    zeros = []
    for i in np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:])):
        lo, hi = grid[i], grid[i + 1]
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            if np.sign(w4(mid)[0]) == np.sign(values[i]):
                lo = mid
            else:
                hi = mid
        zeros.append(0.5 * (lo + hi))
    return zeros


@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_toggle_angles_and_time_ratio_match_where_the_rocker_stops(generate, scenes, branch):
    path = generate(scenes(branch))
    summary = _summary(path)
    params = load_scene(SCENE).parameters
    zeros = _omega_4_zeros(params, branch)
    assert len(zeros) == 2
    extended = summary["toggle, crank and coupler extended"] % 360.0
    folded = summary["toggle, crank and coupler folded"] % 360.0
    assert sorted([extended, folded]) == pytest.approx(sorted(zeros), abs=1e-9)
    # crank and coupler in line there (the reference's angles)
    ref = solve("four_bar", params, np.array([extended, folded]), {"branch": branch})
    assert math.sin(math.radians(ref["theta_3"][0] - extended)) == pytest.approx(0, abs=1e-9)
    assert math.cos(math.radians(ref["theta_3"][0] - extended)) > 0
    assert math.cos(math.radians(ref["theta_3"][1] - folded)) < 0
    stroke = (zeros[1] - zeros[0]) % 360.0
    ratio = max(stroke, 360 - stroke) / min(stroke, 360 - stroke)
    assert summary["time ratio"] == pytest.approx(ratio, rel=1e-9)


def test_angles_continuous_for_a_double_crank(generate, scenes):
    """Coupler and rocker of a double-crank turn fully: no jump of 360 between rows."""
    overrides = {"l_O1O2": 30.0, "l_O1A": 60.0, "l_AB": 70.0, "l_O2B": 80.0}
    cells = table_columns(generate(scenes("open"), overrides=overrides, step=5.0))
    for name in ("theta_3", "theta_4"):
        steps = np.abs(np.diff(as_float(cells[name])))
        assert steps.max() < 30.0, name
        assert as_float(cells[name])[-1] - as_float(cells[name])[0] == pytest.approx(360.0)


@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_audit_is_clean(generate, scenes, branch):
    from workbook_gen import audit
    report = audit(generate(scenes(branch)))
    assert report.ok and not report.mismatches


@pytest.mark.parametrize("branch, overrides", [
    ("open", {}),
    ("crossed", {"l_O1O2": 30.0, "l_O1A": 60.0, "l_AB": 70.0, "l_O2B": 80.0}),
    ("open", {"l_O1O2": 100.0, "l_O1A": 80.0, "l_AB": 30.0, "l_O2B": 90.0}),  # #NUM! rows
    ("crossed", {"l_AB": 140.0}),                                             # toggles
])
def test_libreoffice_agrees_with_every_cached_value(libreoffice, generate, scenes, branch,
                                                    overrides):
    from tests.engines.test_libreoffice_recalc import compare_with_libreoffice
    cells, worst = compare_with_libreoffice(generate(scenes(branch), overrides=overrides))
    assert cells > 100 and math.isfinite(worst)
