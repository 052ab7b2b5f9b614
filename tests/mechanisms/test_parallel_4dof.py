"""parallel_4dof template (docs/mechanisms.md, parallel_4dof; issue 11): every Table cell against
the independent reference (Newton per leg on |P_i - O_i2(theta)| = l_i2, centres of mass from link
frames, complex-step rates cross-checked by mpmath), LibreOffice recalculating the scenes in one
run, the balance (a still centre of mass over the sweep and over random poses, each of the 12
conditions necessary), out-of-reach poses, and modelling only what a scene asks."""

from __future__ import annotations

import math
import shutil

import numpy as np
import openpyxl
import pytest

from tests.engines.test_libreoffice_recalc import compare_with_libreoffice
from workbook_cells import as_float, column_error, table_columns
from workbook_gen import audit
from workbook_gen.tabulate import compute, derived_values, evaluate
from workbook_gen.engines.libreoffice import recalculated_values_many
from workbook_gen.expr.numeric import compile_numpy
from workbook_gen.pruning import select
from workbook_gen.reference import parallel_4dof as ref
from workbook_gen.reference import solve
from workbook_gen.scene import load_scene
from workbook_gen.xlerror import ExcelError

BARE = "templates/parallel_4dof.toml"
BALANCED = "templates/parallel_4dof_balanced.toml"
TOLERANCE = 1e-9      # of the column's magnitude
STILL = 1e-12         # spread of a balanced centre of mass, over l_5
LEGS = (1, 2, 3, 4)
OUT_OF_REACH = {"l_12": 0.27}   # leg 1 reaches P1 over part of the path only
COM = ("x_S", "y_S", "z_S")


def _compare(path, scene):
    """Every Table column against the reference; per leg, NaN exactly where it is."""
    cells = table_columns(path)
    inputs = as_float(cells.pop("t"))
    status = np.array(cells.pop("status"))
    reference = solve("parallel_4dof", derived_values(scene), inputs, scene.options)
    reached = np.all([np.isfinite(reference[f"theta_{i}1"]) for i in LEGS], axis=0)
    assert np.array_equal(status == "ok", reached)
    assert set(status) <= {"ok", "cannot assemble"}
    assert set(cells) <= set(reference)
    return max(column_error(name, as_float(values), reference[name])
               for name, values in cells.items()), status


@pytest.fixture(scope="module")
def books(generate, tmp_path_factory):
    """The scenes' workbooks (bare, balanced, a leg out of reach, the balanced one with
    masses and a length edited on its Parameters sheet, no cached values) and LibreOffice's
    values for all four, from one LibreOffice run."""
    paths = {"bare": generate(BARE), "balanced": generate(BALANCED),
             "reach": generate(BARE, overrides=OUT_OF_REACH)}
    folder = tmp_path_factory.mktemp("edited")
    edited = folder / "parallel_4dof_edited.xlsx"
    shutil.copy(paths["balanced"], edited)
    book = openpyxl.load_workbook(edited)
    sheet = book["Parameters"]
    for row in sheet.iter_rows(min_row=2):
        if row[0].value in EDITS:
            row[1].value = EDITS[row[0].value]
    book.save(edited)
    paths["edited"] = edited
    names = ["bare", "balanced", "reach", "edited"]
    moved = [folder / f"{name}.xlsx" for name in names]
    for name, target in zip(names, moved):
        if paths[name] != target:
            shutil.copy(paths[name], target)
    values = recalculated_values_many(moved)
    return paths, dict(zip(names, values))


EDITS = {"m_11": 1.7, "m_22": 0.6, "l_31": 0.33, "m_P": 3.1, "m_cP": 2.2, "xi_4": 0.25}


@pytest.mark.parametrize("scene_path, overrides, options, step", [
    (BARE, {}, {}, None),
    (BALANCED, {}, {}, None),
    (BARE, OUT_OF_REACH, {}, 5.0),
    (BALANCED, {"m_12": 2.0, "l_5c": -0.1, "A_psi": 25.0, "omega_t": 2.5}, {"branch": "+-+-"},
     7.5),
    (BARE, {"v_11": 0.02, "w_21": -0.03}, {"branch": "----"}, 15.0),
])
def test_every_table_cell_matches_the_reference(generate, tmp_path, scene_path, overrides,
                                                options, step):
    path_in = scene_path
    if options:
        text = open(scene_path, encoding="utf-8").read()
        text = text.replace('branch = "++++"', f'branch = "{options["branch"]}"')
        path_in = tmp_path / "scene.toml"
        path_in.write_text(text, encoding="utf-8")
    path = generate(str(path_in), overrides=overrides, step=step)
    scene = load_scene(path_in, overrides=overrides, step=step)
    worst, status = _compare(path, scene)
    assert worst <= TOLERANCE
    assert ("cannot assemble" in status) == bool(overrides.get("l_12"))


@pytest.mark.parametrize("name", ["bare", "balanced", "reach"])
def test_libreoffice_agrees_with_every_cached_value(libreoffice, books, name):
    paths, values = books
    cells, worst = compare_with_libreoffice(paths[name], values[name])
    assert cells > 4000 and math.isfinite(worst)


def _spread(columns: dict, names=COM) -> float:
    return max(float(np.ptp(as_float(columns[n]))) for n in names)


def test_edited_parameters_keep_the_balance_in_libreoffice(libreoffice, books):
    """Masses and a length changed on the Parameters sheet: LibreOffice recomputes the
    counterweights' positions, and the centre of mass still stands still (elsewhere)."""
    paths, values = books
    header = [c.value for c in openpyxl.load_workbook(paths["balanced"], read_only=True)
              ["Table"][1]]
    table = values["edited"]["Table"]
    columns = {}
    for col, text in enumerate(header):
        name = str(text).split(" ")[0]
        letter = openpyxl.utils.get_column_letter(col + 1)
        cells = [table.get(f"{letter}{r}") for r in range(2, 39)]
        if all(isinstance(v, float) for v in cells):
            columns[name] = cells
    assert _spread(columns) <= STILL * 0.5
    before = table_columns(paths["balanced"])
    assert abs(columns["x_S"][0] - before["x_S"][0]) > 1e-4   # the edit did move it
    params = {k: v for k, v in load_scene(BALANCED).parameters.items()} | EDITS
    derived = values["edited"]["Parameters"]
    sheet = openpyxl.load_workbook(paths["balanced"], read_only=True)["Parameters"]
    names = {f"B{r}": row[0] for r, row in enumerate(sheet.iter_rows(values_only=True), 1)}
    params |= {names[ref_]: v for ref_, v in derived.items()}
    reference = solve("parallel_4dof", params, np.arange(0.0, 361.0, 10.0), {"balance": True})
    for n in COM:
        assert np.allclose(columns[n], reference[n], rtol=0, atol=1e-12)


def test_libreoffice_gives_num_where_a_leg_is_out_of_reach(libreoffice, books):
    paths, values = books
    cached = table_columns(paths["reach"])
    table = values["reach"]["Table"]
    header = list(cached)
    col = openpyxl.utils.get_column_letter(header.index("theta_11") + 1)
    status_col = openpyxl.utils.get_column_letter(header.index("status") + 1)
    rows = [r for r, s in enumerate(cached["status"], start=2) if s == "cannot assemble"]
    assert 5 < len(rows) < 30
    for r in rows:
        assert table[f"{col}{r}"] == ExcelError.NUM
        assert table[f"{status_col}{r}"] == "cannot assemble"


def test_balanced_centre_of_mass_stands_still_over_the_sweep(generate):
    cells = table_columns(generate(BALANCED, step=4.0))
    assert _spread(cells) <= STILL * 0.5
    # masses and lengths changed: the derived counterweights follow
    rng = np.random.default_rng(7)
    for _ in range(3):
        overrides = {f"m_{i}{k}": float(rng.uniform(0.5, 2.0)) for i in LEGS for k in (1, 2)}
        overrides |= {"m_P": float(rng.uniform(1, 4)), "m_5": float(rng.uniform(0.5, 3)),
                      "l_5c": float(rng.uniform(-0.2, 0.3)), "m_c5": float(rng.uniform(4, 12)),
                      "v_21": float(rng.uniform(-0.02, 0.02)), "xi_3": float(rng.uniform(0.1, 0.4))}
        table = compute(load_scene(BALANCED, overrides=overrides))
        spread = max(float(np.ptp(table[f"{n} [m]"])) for n in COM)
        assert spread <= STILL * 0.5, overrides


def _random_poses(n: int, seed: int):
    rng = np.random.default_rng(seed)
    return (np.radians(rng.uniform(60, 120, n)), np.radians(rng.uniform(-25, 25, n)),
            np.radians(rng.uniform(-20, 20, n)), np.radians(rng.uniform(-20, 20, n)))


def test_balanced_centre_of_mass_stands_still_over_random_poses():
    """The counterweights the workbook derives, placed in the reference's link frames:
    the total centre of mass is the same at 1,000 random reachable poses."""
    scene = load_scene(BALANCED)
    params = derived_values(scene)
    out, thetas = ref.positions(params, _random_poses(1100, 3), {"balance": True})
    reached = np.all([np.isfinite(thetas[i]) for i in LEGS], axis=0)
    assert reached.sum() >= 1000
    spread = max(float(np.ptp(out[n][reached][:1000])) for n in COM)
    assert spread <= STILL * params["l_5"]


def test_bare_centre_of_mass_moves(books):
    cells = table_columns(books[0]["bare"])
    assert _spread(cells) > 1e-2 * load_scene(BARE).parameters["l_5"]
    out, thetas = ref.positions(derived_values(load_scene(BARE)), _random_poses(200, 5), {})
    assert max(float(np.nanmax(out[n]) - np.nanmin(out[n])) for n in COM) > 1e-2


def _balanced_bare_parameters() -> dict[str, float]:
    """The bare design's parameters moved so that every condition holds (no counterweights):
    u_i1, v_i1 on each link i1, the platform's centre of mass and leg 5's."""
    p = dict(load_scene(BARE).parameters)
    mu = {i: p[f"m_{i}2"] * p[f"xi_{i}"] / p[f"l_{i}2"] for i in LEGS}
    for i in LEGS:
        p[f"u_{i}1"] = -p[f"m_{i}2"] * p[f"l_{i}1"] * (1 - p[f"xi_{i}"] / p[f"l_{i}2"]) / p[f"m_{i}1"]
        p[f"v_{i}1"] = 0.0
    for joint, com in zip("abc", "uvw"):
        origin = p[f"{joint}_5"]
        p[f"{com}_P"] = origin - sum(mu[i] * (p[f"{joint}_{i}"] - origin) for i in LEGS) / p["m_P"]
    p["l_5c"] = -p["l_5"] * (p["m_P"] + sum(mu.values())) / p["m_5"]
    return p


BREAKS = [(f"leg{i}_xi", f"u_{i}1") for i in LEGS] + [(f"leg{i}_eta", f"v_{i}1") for i in LEGS] \
    + [("platform_x", "u_P"), ("platform_y", "v_P"), ("platform_z", "w_P"), ("leg5", "l_5c")]


def _condition_verdicts(params: dict[str, float]) -> dict[str, bool]:
    scene = load_scene(BARE, overrides=params)
    model = select(scene.template, scene.outputs)
    out = {}
    for c in model.conditions:
        value = compile_numpy(c.expr)({}, dict(scene.parameters), 1).val[0]
        scale = compile_numpy(c.scale)({}, dict(scene.parameters), 1).val[0]
        out[c.name] = abs(value) <= 1e-9 * scale
    return out


def test_the_conditions_suffice_and_each_is_necessary():
    """With parameters that satisfy all 12 conditions the reference's centre of mass stands
    still; breaking any one alone (one parameter moved by 1 cm) makes it move, and the
    workbook's conditions say which one fails."""
    p = _balanced_bare_parameters()
    t = np.arange(0.0, 360.0, 5.0)
    still = solve("parallel_4dof", p, t, {})
    assert max(float(np.ptp(still[n])) for n in COM) <= STILL * p["l_5"]
    assert all(_condition_verdicts(p).values())
    assert len(BREAKS) == 12
    for condition, name in BREAKS:
        broken = dict(p) | {name: p[name] + 0.01}
        moved = solve("parallel_4dof", broken, t, {})
        assert max(float(np.ptp(moved[n])) for n in COM) > 1e-5, condition
        verdicts = _condition_verdicts(broken)
        assert [k for k, ok in verdicts.items() if not ok] == [condition]


def test_out_of_reach_rows_hold_num_and_a_status(generate):
    path = generate(BARE, overrides=OUT_OF_REACH)
    cells = table_columns(path)
    out = np.array(cells["status"]) == "cannot assemble"
    assert 5 < out.sum() < 30
    for name in ("theta_11", "omega_11", "x_O12", "x_S11", "x_S12", "x_S", "z_S"):
        assert {cells[name][i] for i in np.flatnonzero(out)} == {"#NUM!"}, name
    for name in ("theta_21", "theta_41", "x_P1", "C_1"):
        assert all(isinstance(cells[name][i], float) for i in np.flatnonzero(out)), name
    summary = {r[0]: r[2] for r in openpyxl.load_workbook(path, data_only=True)["Summary"]
               .iter_rows(values_only=True) if r[0]}
    assert summary["rows that cannot be assembled"] == out.sum()


def test_theta_11_alone_models_leg_1_only(tmp_path, generate):
    text = open(BARE, encoding="utf-8").read() + '\n[outputs]\nquantities = ["theta_11"]\n'
    scene_path = tmp_path / "leg1.toml"
    scene_path.write_text(text, encoding="utf-8")
    scene = load_scene(scene_path)
    model = select(scene.template, scene.outputs)
    names = set(model.names)
    expected = {"t", "alpha", "psi", "vartheta", "phi", "x_P5", "z_P5", "x_P1", "y_P1", "z_P1",
                "A_1", "B_1", "C_1", "K_1", "theta_11"} | {f"Q_{r}{c}" for r in "123" for c in "123"}
    assert names == expected
    assert [c.name for c in model.checks] == ["leg1_closure"]
    assert not model.conditions and not model.charts
    path = generate(str(scene_path))
    report = audit(path)
    assert report.ok and report.cells_checked == report.formula_cells


def test_reference_rates_agree_with_mpmath():
    """The reference's complex-step rates against a 50-digit central difference."""
    p = dict(ref.DEFAULTS)
    t = np.radians(np.array([0.0, 37.0, 211.0]))
    g = ref._Geometry(p, np)
    _, thetas = ref.positions(p, g.pose(t), {})
    fast, slow = ref._rates(p, t, thetas), ref.rates_mpmath(p, t, thetas)
    assert np.max(np.abs(fast - slow) / np.maximum(np.max(np.abs(slow), axis=0), 1e-300)) < 1e-13


@pytest.mark.parametrize("name, scene_path", [("bare", BARE), ("balanced", BALANCED)])
def test_audit_checks_every_column_against_the_reference(books, name, scene_path):
    report = audit(books[0][name])
    assert report.ok and not report.mismatches
    columns = len(select(load_scene(scene_path).template, load_scene(scene_path).outputs).columns)
    assert len(report.reference) == columns


def test_a_leg_at_the_edge_of_its_reach_is_flagged_not_ok():
    """l_12 chosen (from the reference's A and B) so that P1 is at the edge of leg 1's reach
    at t = 0: that row is 'singular' (its rate's denominator vanishes), or 'cannot assemble'
    a hair beyond, never 'ok'; a little inside the edge it is 'ok' again."""
    p = load_scene(BARE).parameters
    r = solve("parallel_4dof", {}, np.array([0.0]), {})
    d2 = sum((r[f"{a}_P1"][0] - p[f"{a}_10"]) ** 2 for a in "xyz")
    edge = math.sqrt(d2 + p["l_11"] ** 2 - 2 * p["l_11"] * math.hypot(r["A_1"][0], r["B_1"][0]))
    for nudge, expected in ((1e-15, "singular"), (-1e-15, "cannot assemble"), (0.0, None),
                            (1e-5, "ok")):
        table = compute(load_scene(BARE, overrides={"l_12": edge + nudge}))
        status = table["status"].iloc[0]
        assert status != "ok" if expected is None else status == expected, nudge
        if status == "singular":
            assert math.isfinite(table["theta_11 [deg]"].iloc[0])


@pytest.mark.parametrize("seed", range(6))
def test_random_designs_match_the_reference(tmp_path, seed):
    """Random designs (every length, platform coordinate, centre of mass and mass moved by up
    to 15 %, random branches, balanced or not): every column of compute() against the
    reference, rows out of reach included."""
    rng = np.random.default_rng(seed)
    balance = bool(seed % 2)
    scene_path = BALANCED if balance else BARE
    base = load_scene(scene_path).parameters
    overrides = {k: float(v * rng.uniform(0.85, 1.15)) for k, v in base.items()
                 if not k.startswith(("gamma_", "alpha_0", "A_", "omega_t"))}
    overrides |= {f"gamma_{i}": float(base[f"gamma_{i}"] + rng.uniform(-20, 20)) for i in LEGS}
    branch = "".join(rng.choice(["+", "-"], 4))
    text = open(scene_path, encoding="utf-8").read().replace('branch = "++++"',
                                                            f'branch = "{branch}"')
    path = tmp_path / "scene.toml"
    path.write_text(text, encoding="utf-8")
    scene = load_scene(path, overrides=overrides, step=7.5)
    result = evaluate(scene)
    reference = solve("parallel_4dof", result.params, result.inputs, scene.options)
    reached = np.all([np.isfinite(reference[f"theta_{i}1"]) for i in LEGS], axis=0)
    assert np.array_equal(result.status != "cannot assemble", reached)
    for name, column in result.columns.items():
        if name == "t":
            continue
        ours = np.where(column.err != 0, np.nan, column.val.astype(float))
        assert column_error(name, ours, reference[name]) <= TOLERANCE, (name, branch)
