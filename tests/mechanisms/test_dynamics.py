"""Shaking force and balance (docs/mechanisms.md, Shaking force and balance): every dynamics cell
against an independent route.

The reference here shares nothing with the trees: the links' frames come from the joint
positions of the reference model (workbook_gen.reference, Newton on the closure equations),
the centres of mass are placed in those frames, and their accelerations are the second time
derivatives of the positions by an 8th-order central difference over the crank angle
(t = theta / omega). Sums, shaking force and moment follow from their definitions.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from tests.engines.test_libreoffice_recalc import compare_with_libreoffice
from workbook_cells import as_float, table_columns
from workbook_gen import audit
from workbook_gen.reference import solve
from workbook_gen.scene import load_scene, parse_scene
from workbook_gen.workbook import write_workbook

TOLERANCE = 1e-9          # of the column's magnitude (the differences reach about 5e-11)
STENCIL = (-1 / 560, 8 / 315, -1 / 5, 8 / 5, -205 / 72, 8 / 5, -1 / 5, 8 / 315, -1 / 560)
H_DEG = 0.5               # step of the difference in crank angle


def _unit(dx, dy):
    r = np.hypot(dx, dy)
    return dx / r, dy / r


def _frames(mechanism: str, p: dict, theta: np.ndarray) -> dict[str, tuple]:
    """{link: (origin x, origin y, e x, e y)} from the reference model's joint positions."""
    r = solve(mechanism, {k: v for k, v in p.items() if not k[:2] in ("m_", "u_", "v_")
                          and not k.startswith("r_cw")}, theta)
    t = np.radians(theta)
    zero = np.zeros_like(t)
    if mechanism == "slider_crank":
        phi = math.radians(p["phi_slide"])
        bx, by = p["l_AB"] * np.cos(t), p["l_AB"] * np.sin(t)
        cx = r["s_C"] * math.cos(phi) - p["e"] * math.sin(phi)
        cy = r["s_C"] * math.sin(phi) + p["e"] * math.cos(phi)
        return {"crank": (zero, zero, *_unit(bx, by)),
                "rod": (bx, by, *_unit(cx - bx, cy - by)),
                "slider": (cx, cy, zero + math.cos(phi), zero + math.sin(phi))}
    if mechanism == "sewing_machine":
        bx, by = p["l_AB"] * np.cos(t), p["l_AB"] * np.sin(t)
        cy = r["y_C"]
        return {"crank": (zero, zero, *_unit(bx, by)),
                "rod": (bx, by, *_unit(-bx, cy - by)),
                "needle_bar": (zero, cy, zero, zero + 1.0),
                "lever": (zero + p["x_F"], zero + p["y_F"],
                          *_unit(r["x_E"] - p["x_F"], r["y_E"] - p["y_F"]))}
    if mechanism == "four_bar":
        ax, ay = p["l_O1A"] * np.cos(t), p["l_O1A"] * np.sin(t)
        t3 = np.radians(r["theta_3"])
        bx, by = ax + p["l_AB"] * np.cos(t3), ay + p["l_AB"] * np.sin(t3)
        return {"crank": (zero, zero, *_unit(ax, ay)),
                "coupler": (ax, ay, *_unit(bx - ax, by - ay)),
                "rocker": (zero + p["l_O1O2"], zero, *_unit(bx - p["l_O1O2"], by))}
    raise AssertionError(mechanism)


def _points(mechanism, p, theta, points):
    """Positions of each (label, link, u, v) point at the crank angles ``theta``."""
    frames = _frames(mechanism, p, theta)
    out = {}
    for label, link, u, v in points:
        ox, oy, ex, ey = frames[link]
        out[label] = (ox + u * ex - v * ey, oy + u * ey + v * ex)
    return out


def reference_dynamics(mechanism, p, theta, points, omega, metres=1e-3):
    """Every dynamics column by the independent route; points: (label, link, m, u, v)."""
    geometry = [(label, link, u, v) for label, link, m, u, v in points]
    at = _points(mechanism, p, theta, geometry)
    h = math.radians(H_DEG)
    acc = {label: [0.0, 0.0] for label, *_ in points}
    for k, c in zip(range(-4, 5), STENCIL):
        shifted = _points(mechanism, p, theta + k * H_DEG, geometry)
        for label in acc:
            acc[label][0] = acc[label][0] + c * shifted[label][0]
            acc[label][1] = acc[label][1] + c * shifted[label][1]
    out, total = {}, sum(m for _, _, m, _, _ in points)
    sums = dict.fromkeys(("x", "y", "ax", "ay", "mom"), 0.0)
    for label, link, m, u, v in points:
        x, y = at[label]
        ax, ay = (omega / h) ** 2 * acc[label][0], (omega / h) ** 2 * acc[label][1]
        out.update({f"x_S_{label}": x, f"y_S_{label}": y, f"ax_S_{label}": ax,
                    f"ay_S_{label}": ay})
        for key, value in (("x", x), ("y", y), ("ax", ax), ("ay", ay), ("mom", x * ay - y * ax)):
            sums[key] = sums[key] + m * value
    out.update({"x_S": sums["x"] / total, "y_S": sums["y"] / total,
                "ax_S": sums["ax"] / total, "ay_S": sums["ay"] / total,
                "F_x": -sums["ax"] * metres, "F_y": -sums["ay"] * metres,
                "M_S": -sums["mom"] * metres ** 2})
    out["F_abs"] = np.hypot(out["F_x"], out["F_y"])
    return out


def _scene_points(scene) -> list[tuple]:
    p = scene.parameters
    return [(name, name, p[f"m_{name}"], p[f"u_{name}"], p[f"v_{name}"]) for name in scene.masses]


def _write(tmp_path: Path, text: str, name: str = "scene"):
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    scene = load_scene(path)
    return scene, write_workbook(scene, tmp_path / "out", force=True)


def _partner(name: str) -> str:
    """x and y components share a scale (a slider's y acceleration is 0 on a level slide)."""
    for a, b in (("x_", "y_"), ("ax_", "ay_"), ("F_x", "F_y")):
        if name.startswith(a):
            return b + name[len(a):]
        if name.startswith(b):
            return a + name[len(b):]
    return name


def _compare(cells: dict, reference: dict, tolerance: float = TOLERANCE) -> int:
    checked = 0
    for name, ref in reference.items():
        ours = as_float(cells[name])
        both = np.isfinite(ref)
        assert np.array_equal(np.isfinite(ours), both), name
        scale = max(np.nanmax(np.abs(ref)), np.nanmax(np.abs(reference[_partner(name)])))
        error = np.max(np.abs(ours[both] - ref[both])) / scale
        assert error <= tolerance, f"{name}: {error:.3g} of its magnitude {scale:.6g}"
        checked += int(both.sum())
    return checked


CASES = [
    ("templates/slider_crank_masses.toml", {}, None),
    ("templates/slider_crank_masses.toml", {"e": -25.0, "phi_slide": 30.0, "l_BC": 70.0,
                                            "v_rod": 6.0, "u_slider": 12.0, "v_slider": -3.0,
                                            "v_crank": -4.0}, 2.0),
    ("templates/sewing_machine_masses.toml", {}, None),
    ("templates/sewing_machine_masses.toml", {"beta_E": 15.0, "x_F": 60.0, "y_F": 0.0,
                                              "m_needle_bar": 0.5}, 5.0),
]


@pytest.mark.parametrize("scene_path, overrides, step", CASES)
def test_every_dynamics_cell_matches_the_independent_route(generate, scene_path, overrides,
                                                           step):
    path = generate(scene_path, overrides=overrides, step=step)
    scene = load_scene(scene_path, overrides=overrides, step=step)
    cells = table_columns(path)
    theta = as_float(cells["theta_1"])
    ref = reference_dynamics(scene.mechanism, dict(scene.parameters), theta,
                             _scene_points(scene), scene.parameters["omega_1"])
    assert set(ref) <= set(cells)
    assert _compare(cells, ref) >= len(theta) * len(ref)


@pytest.mark.parametrize("scene_path", ["templates/slider_crank_masses.toml",
                                        "templates/sewing_machine_masses.toml"])
def test_masses_workbook_audits_clean_and_libreoffice_agrees(libreoffice, generate,
                                                             scene_path):
    path = generate(scene_path)
    report = audit(path)
    assert report.ok, report.mismatches[:3]
    cells, worst = compare_with_libreoffice(path)
    assert cells > 500 and math.isfinite(worst)


def test_a_single_crank_mass_shakes_with_m_r_omega_squared(tmp_path):
    """Closed form: a point mass m at radius r on a crank turning at omega: |F| = m r omega^2,
    directed outwards along the crank's centre of mass, and no moment about the pivot."""
    m, u, v, omega = 0.37, 21.0, -6.5, 13.0
    scene, path = _write(tmp_path, f"""
        name = "crank_only"
        mechanism = "slider_crank"
        [parameters]
        omega_1 = {omega}
        [sweep]
        step = 7.5
        [masses]
        crank = {{ m = {m}, u = {u}, v = {v} }}
    """)
    cells = table_columns(path)
    r = math.hypot(u, v)
    expected = m * r * 1e-3 * omega ** 2
    f_abs = as_float(cells["F_abs"])
    assert np.max(np.abs(f_abs - expected)) <= 1e-13 * expected
    t = np.radians(as_float(cells["theta_1"])) + math.atan2(v, u)
    assert np.max(np.abs(as_float(cells["F_x"]) - expected * np.cos(t))) <= 1e-13 * expected
    assert np.max(np.abs(as_float(cells["F_y"]) - expected * np.sin(t))) <= 1e-13 * expected
    assert np.max(np.abs(as_float(cells["M_S"]))) <= 1e-15 * expected * r * 1e-3


def test_rows_that_cannot_assemble_have_no_shaking_force(generate):
    path = generate("templates/sewing_machine_masses.toml", overrides={"l_BC": 20.0})
    cells = table_columns(path)
    bad = [i for i, s in enumerate(cells["status"]) if s == "cannot assemble"]
    assert bad
    for i in bad:
        assert cells["F_x"][i] == "#NUM!" and cells["M_S"][i] == "#NUM!"


def test_mass_parameters_are_named_cells_a_user_can_edit(generate):
    import openpyxl
    book = openpyxl.load_workbook(generate("templates/slider_crank_masses.toml"))
    names = set(book.defined_names)
    assert {"m_crank", "u_rod", "v_slider"} <= names
    table = book["Table"]
    headers = [c.value for c in table[1]]
    formula = table.cell(2, headers.index("F_x [N]") + 1).value
    assert "m_rod" in formula and "m_slider" in formula


def test_negative_mass_is_refused(tmp_path):
    from workbook_gen.errors import SceneError
    text = Path("templates/slider_crank_masses.toml").read_text()
    with pytest.raises(SceneError, match="m_rod"):
        parse_scene(text, "x.toml", overrides={"m_rod": -1.0})


# --- four-bar: full shaking-force balance (Berkof-Lowen) ---------------------------------

BALANCED = "templates/four_bar_balanced.toml"


def _four_bar(tmp_path: Path, balance: bool, extra: str = "", name: str = "fb"):
    text = Path(BALANCED).read_text().replace("balance = true", f"balance = {str(balance).lower()}")
    text = text.replace('name = "four_bar_balanced"', f'name = "{name}"') + extra
    return _write(tmp_path, text, name)


def _parameters(path) -> dict[str, object]:
    """Name -> cached value of the Parameters sheet (the counterweights are derived rows)."""
    import openpyxl
    sheet = openpyxl.load_workbook(path, data_only=True)["Parameters"]
    return {r[0]: r[1] for r in sheet.iter_rows(min_row=2, values_only=True) if r[0]}


def _counterweight_points(scene, path) -> list[tuple]:
    values = _parameters(path)
    out = []
    for link in ("crank", "rocker"):
        m = values[f"m_cw_{link}"]
        phi = math.radians(values[f"phi_cw_{link}"])
        r = scene.parameters[f"r_cw_{link}"]
        out.append((f"cw_{link}", link, m, r * math.cos(phi), r * math.sin(phi)))
    return out


@pytest.mark.parametrize("overrides", [{}, {"l_O1A": 30.0, "l_AB": 110.0, "v_coupler": -12.0,
                                            "u_rocker": 55.0, "v_crank": 5.0,
                                            "r_cw_crank": 25.0, "omega_2": 7.0}])
def test_balanced_four_bar_shaking_force_vanishes(tmp_path, overrides):
    _, plain = _four_bar(tmp_path, False, name="plain")
    scene, balanced = _four_bar(tmp_path, True, name="balanced")
    if overrides:
        scene = load_scene(tmp_path / "balanced.toml", overrides=overrides)
        balanced = write_workbook(scene, tmp_path / "over", force=True)
        plain = write_workbook(load_scene(tmp_path / "plain.toml", overrides={
            k: v for k, v in overrides.items() if not k.startswith("r_cw")}), tmp_path / "over",
            force=True)
    ours, theirs = table_columns(balanced), table_columns(plain)
    unbalanced = max(np.max(np.abs(as_float(theirs[f]))) for f in ("F_x", "F_y"))
    assert unbalanced > 0.1  # newtons: the links alone do shake the frame
    for f in ("F_x", "F_y", "F_abs"):
        assert np.max(np.abs(as_float(ours[f]))) < 1e-9 * unbalanced, f
    for s in ("x_S", "y_S"):  # the total centre of mass stands still
        values = as_float(ours[s])
        assert np.ptp(values) < 1e-12 * scene.parameters["l_O1O2"], s
    # The counterweights (read off the Summary) placed in the independent model, and the
    # whole balanced mechanism's columns against it; F, a_S against the unbalanced scale.
    theta = as_float(ours["theta_2"])
    points = _scene_points(scene) + _counterweight_points(scene, balanced)
    ref = reference_dynamics("four_bar", dict(scene.parameters), theta, points,
                             scene.parameters["omega_2"])
    small = {"F_x", "F_y", "F_abs", "ax_S", "ay_S"}
    _compare(ours, {k: v for k, v in ref.items() if k not in small})
    for name in small:
        scale = unbalanced if name.startswith("F") else np.max(np.abs(ref["ax_S_coupler"]))
        assert np.max(np.abs(as_float(ours[name]) - ref[name])) <= 1e-9 * scale, name


def test_unbalanced_four_bar_matches_the_independent_route(tmp_path):
    scene, path = _four_bar(tmp_path, False)
    cells = table_columns(path)
    ref = reference_dynamics("four_bar", dict(scene.parameters), as_float(cells["theta_2"]),
                             _scene_points(scene), scene.parameters["omega_2"])
    assert _compare(cells, ref) >= 37 * len(ref)


def test_balanced_four_bar_audits_clean_and_balances_in_libreoffice(libreoffice, tmp_path):
    from workbook_gen.engines.libreoffice import recalculated_values
    _, plain = _four_bar(tmp_path, False, name="plain")
    _, path = _four_bar(tmp_path, True, name="balanced")
    assert audit(path).ok and audit(plain).ok
    compare_with_libreoffice(plain)
    import openpyxl
    from openpyxl.utils import get_column_letter
    headers = [c.value for c in next(openpyxl.load_workbook(path, read_only=True)["Table"].rows)]
    f_x = get_column_letter(headers.index("F_x [N]") + 1)
    table = recalculated_values(path)["Table"]
    values = [table[f"{f_x}{row}"] for row in range(2, 39)]
    unbalanced = np.max(np.abs(as_float(table_columns(plain)["F_x"])))
    assert max(abs(v) for v in values) < 1e-9 * unbalanced


def test_counterweights_are_on_the_parameters_sheet_as_live_formulas(tmp_path):
    import openpyxl
    _, path = _four_bar(tmp_path, True)
    book = openpyxl.load_workbook(path)
    names = set(book.defined_names)
    assert {"r_cw_crank", "r_cw_rocker", "m_coupler", "m_cw_crank", "phi_cw_rocker"} <= names
    formulas = {r[0]: r[1] for r in book["Parameters"].iter_rows(min_row=2, values_only=True)}
    assert str(formulas["m_cw_crank"]).startswith("=")
    values = _parameters(path)
    assert values["m_cw_crank"] > 0
    assert values["m_cw_rocker"] > 0
