"""five_bar and parallel_4dof right at their limits (issue 21,
docs/stability.md, Limits by template).

Each limit is hit EXACTLY on a grid row (dyadic lengths: the float parameters are the
exact limit, and the 50-digit reference sees the same numbers) and to within 1e-12
(one length nudged by 1e-12 relative, either side), and again on rows of sweeps that
start at -537 and 713 deg (the same position a whole number of turns away, where SIN and
COS of the float angle are within rounding of it):

five_bar (C on its circle at phi = 90 or 270 deg):
  stretch_AB  |AC| = l_1 + l_2  (C = (0, 2), 1.25 + 0.75)
  fold_AB     |AC| = l_1 - l_2  (C = (0, 1.5), 2 - 0.5)
  stretch_ED  |EC| = l_4 + l_3  (C = E + (0, 2))
  in_line     B, C, D in line   (B = (0.75, 1), C = (1, 1), D = (1.25, 1): 3-4-5 triangles)
parallel_4dof (pose at t = 0: alpha = alpha_0, the platform unturned):
  leg_edge    leg 1 stretched in the plane of its hinge: d = P1 - O11 = (0.5, -0.5, 0.375),
              l_11 = 0.25, l_12 = 0.625, A^2 + B^2 = C^2 = 0.625^2 exactly

Checked: (a) every ok row against 50 digits (extremes_common.assert_sound; the parallel
reference is tests/mp_parallel_4dof.py), singular rates error values; (b) each workbook's
own audit, reference model included, both five-bar methods; (c) LibreOffice recalculating
all the workbooks in one run; (d) no Summary cell an error value while a row is ok;
(e) sweeps from anywhere in -720..720 and angle parameters of any size.
"""

from __future__ import annotations

import math

import openpyxl
import pytest

from extremes_common import assert_sound
from tests.engines.test_libreoffice_recalc import compare_with_libreoffice
from workbook_gen import audit
from workbook_gen.engines.libreoffice import recalculated_values_many
from workbook_gen.tabulate import evaluate
from mp_reference import scene_at

NEAR = 1e-12
FIVE_BAR = {   # name: (parameters, phi at the limit, the length nudged for "within 1e-12")
    "stretch_AB": (dict(l_1=1.25, l_2=0.75, l_3=1.0, l_4=2.0, l_5=1.6, x_0=0.0, y_0=1.75,
                        R_path=0.25), 90.0, "R_path"),
    "fold_AB": (dict(l_1=2.0, l_2=0.5, l_3=1.0, l_4=2.0, l_5=1.6, x_0=0.0, y_0=1.75,
                     R_path=0.25), 270.0, "R_path"),
    "stretch_ED": (dict(l_1=2.0, l_2=1.0, l_3=0.75, l_4=1.25, l_5=1.6, x_0=1.6, y_0=1.75,
                        R_path=0.25), 90.0, "R_path"),
    "in_line": (dict(l_1=1.25, l_2=0.25, l_3=0.25, l_4=1.25, l_5=2.0, x_0=1.0, y_0=0.875,
                     R_path=0.125), 90.0, "l_2"),
}
LEG_EDGE = dict(A_psi=0.0, A_vartheta=0.0, c_5=0.0, a_1=0.0, b_1=0.125, c_1=0.0, gamma_1=0.0,
                x_10=-0.5, y_10=0.625, z_10=0.125, l_11=0.25, l_12=0.625)
FLAG = {"stretch_AB": "limit", "fold_AB": "limit", "stretch_ED": "limit",
        "in_line": "singular"}
# LibreOffice stores 15 significant digits: Newton's last step (rounding noise once it has
# converged) differs by 1e-14 relative, and S = term / det_BCD 10 deg from B, C, D in line
# multiplies that by the condition |p| |q| / det_BCD (measured 4.4e-12 of the column).
LIBREOFFICE = {"fb_in_line_newton": 1e-11, "fb_in_line_far_713": 1e-11}
ERRORS = ("#DIV/0!", "#NUM!", "#N/A", "#VALUE!", "#REF!", "#NAME?", "#NULL!")


def _nudged(params: dict, key: str, rel: float) -> dict:
    return dict(params, **{key: params[key] * (1 + rel)})


def _far(limit: float, full: bool = True) -> list[float]:
    """The limit's angle and its neighbours, on the 10-deg grid and on the rows of sweeps
    from -537 (step 3) and 713 (step 97) that are the same position (``full``: also 1e-6
    deg either side)."""
    same = [a for a in (limit - 720, limit - 360, limit + 360, limit + 720)
            if (a + 537) % 3 == 0 or (a - 713) % 97 == 0]
    near = [limit - 1e-6, limit + 1e-6] if full else []
    return sorted({limit, limit - 10, limit + 10, *near, *same})


# ------------------------------------------------------------------ (a) 50 digits
@pytest.mark.parametrize("name", FIVE_BAR)
@pytest.mark.parametrize("rel", [0.0, NEAR, -NEAR])
def test_five_bar_ok_rows_are_the_50_digit_values(name, rel):
    params, limit, key = FIVE_BAR[name]
    params = _nudged(params, key, rel)
    inputs = _far(limit, full=rel == 0.0)
    assert -270.0 in inputs or 810.0 in inputs or -90.0 in inputs
    _, status = assert_sound("five_bar", params, inputs)
    at = [s for x, s in zip(inputs, status) if x % 360 == limit % 360]
    if rel == 0.0:    # exactly at the limit: flagged, never ok
        assert set(at) == {FLAG[name]}, at
    assert "ok" not in at or rel != 0.0
    _singular_rates_are_errors("five_bar", params, inputs, "S_")


@pytest.mark.parametrize("name", ["stretch_AB", "in_line"])
def test_five_bar_newton_ok_rows_are_the_50_digit_values(name):
    params, limit, _ = FIVE_BAR[name]
    inputs = _far(limit) + [limit + 45.0, limit - 90.0, limit + 180.0]
    _, status = assert_sound("five_bar", params, inputs, {"method": "newton"})
    assert FLAG[name] in set(status) and "ok" in set(status)
    # 10 deg from the limit the elbow is 2.7 deg from straight: 8 steps do not converge
    assert "not converged" in set(status) or name == "in_line"


@pytest.mark.parametrize("rel", [0.0, NEAR, -NEAR, 1e-9, 1e-6])
@pytest.mark.parametrize("balance", [False, True])
def test_parallel_ok_rows_are_the_50_digit_values(rel, balance):
    params = _nudged(LEG_EDGE, "l_12", rel)
    inputs = [-360.0, -1e-6, 0.0, 1e-6, 10.0, 90.0, 360.0, 720.0]
    _, status = assert_sound("parallel_4dof", params, inputs, {"balance": balance})
    if rel == 0.0:
        assert status[2] == "singular" and status[-1] == "singular"
    if rel == -NEAR:   # the leg 1e-12 too short: out of reach at t = 0
        assert status[2] == "cannot assemble"
    _singular_rates_are_errors("parallel_4dof", params, inputs, "omega_", {"balance": balance})


def _singular_rates_are_errors(mechanism, params, inputs, prefix, options=None):
    """In a row flagged singular the singular rates are error values, never numbers."""
    ev = evaluate(scene_at(mechanism, params, inputs, options))
    rows = [i for i, s in enumerate(ev.status) if s == "singular"]
    for name in ev.columns:
        if not name.startswith(prefix):
            continue
        column = ev.columns[name]
        numbers = [i for i in rows if column.err[i] == 0 and abs(column.val[i]) > 0]
        if mechanism == "parallel_4dof":   # only the leg at its edge is singular
            leg = name[len(prefix)]
            numbers = [i for i in numbers if ev.columns[f"K_{leg}"].val[i]
                       <= (1e-3 * (params.get(f"l_{leg}1", 0.3) + params.get(f"l_{leg}2", 0.5))) ** 2]
        assert not numbers, (name, [float(ev.inputs[i]) for i in numbers])


# ------------------------------------------------------------------ (b)-(e) workbooks
def _book_scenes():
    """(file stem, mechanism, parameters, options, (start, stop, step))."""
    out = []
    for name, (params, limit, key) in FIVE_BAR.items():
        out.append((f"fb_{name}", "five_bar", params, {}, (0.0, 360.0, 10.0)))
        if name != "stretch_ED":    # the mirror of stretch_AB
            out.append((f"fb_{name}_newton", "five_bar", params, {"method": "newton"},
                        (0.0, 360.0, 10.0)))
        if name in ("stretch_AB", "in_line"):
            out.append((f"fb_{name}_near", "five_bar", _nudged(params, key, -NEAR), {},
                        (0.0, 360.0, 10.0)))
    out += [
        ("fb_stretch_far_537", "five_bar", FIVE_BAR["stretch_AB"][0], {}, (-537.0, 183.0, 3.0)),
        ("fb_in_line_far_713", "five_bar", FIVE_BAR["in_line"][0], {"method": "newton"},
         (713.0, 1101.0, 97.0)),
        ("fb_default_far_720", "five_bar", {}, {}, (-720.0, -360.0, 10.0)),
        ("fb_default_far_newton", "five_bar", {}, {"method": "newton"}, (-181.0, 179.0, 10.0)),
        ("pl_leg_edge", "parallel_4dof", LEG_EDGE, {}, (0.0, 360.0, 10.0)),
        ("pl_leg_edge_near", "parallel_4dof", _nudged(LEG_EDGE, "l_12", NEAR), {},
         (0.0, 360.0, 10.0)),
        ("pl_leg_edge_balanced", "parallel_4dof", LEG_EDGE, {"balance": True},
         (0.0, 360.0, 10.0)),
        ("pl_leg_edge_far_537", "parallel_4dof", LEG_EDGE, {}, (-537.0, 183.0, 3.0)),
        ("pl_far_angles", "parallel_4dof",   # angle parameters whole turns away
         dict(alpha_0=90.0 + 1080.0, gamma_2=85.0 - 720.0, gamma_4=285.0 + 360.0), {},
         (713.0, 1073.0, 10.0)),
    ]
    return out


SCENES = _book_scenes()


def _write(folder, stem, mechanism, params, options, sweep):
    from workbook_gen.scene import parse_scene
    from workbook_gen.workbook import write_workbook

    lines = [f'name = "{stem}"', f'mechanism = "{mechanism}"', "[parameters]"]
    lines += [f"{k} = {float(v)!r}" for k, v in params.items()]
    lines += ["[sweep]", f"start = {sweep[0]!r}", f"stop = {sweep[1]!r}", f"step = {sweep[2]!r}"]
    if options:
        lines.append("[options]")
        lines += [f"{k} = " + (f'"{v}"' if isinstance(v, str) else str(v).lower())
                  for k, v in options.items()]
    return write_workbook(parse_scene("\n".join(lines), f"{stem}.toml"), folder)


@pytest.fixture(scope="module")
def books(tmp_path_factory, libreoffice):
    """Every workbook of SCENES, and LibreOffice's values for all of them (one run)."""
    folder = tmp_path_factory.mktemp("limits")
    paths = [_write(folder, *scene) for scene in SCENES]
    return dict(zip((s[0] for s in SCENES), zip(paths, recalculated_values_many(paths))))


@pytest.mark.parametrize("stem", [s[0] for s in SCENES])
def test_workbook_at_a_limit_passes_its_audit_libreoffice_and_summary(books, stem):
    path, theirs = books[stem]
    report = audit(path)
    failing = [(q.name, q.max_error, q.worst_row_input, q.wrong_rows[:2])
               for q in report.mechanics.quantities if not q.ok]
    assert report.ok and not failing, (failing, report.mechanics.residuals)
    cells, worst = compare_with_libreoffice(path, theirs, LIBREOFFICE.get(stem, 1e-12))
    assert cells > 500 and math.isfinite(worst)
    book = openpyxl.load_workbook(path, data_only=True, read_only=True)
    table = list(book["Table"].iter_rows(values_only=True))
    status = [r[table[0].index("status")] for r in table[1:]]
    assert "ok" in status
    if "_near" not in stem and "default" not in stem and "far_angles" not in stem:
        assert set(status) & {"limit", "singular"}, set(status)   # the limit is on a row
    bad = [(r[0], v) for r in book["Summary"].iter_rows(values_only=True)
           for v in r if isinstance(v, str) and v in ERRORS]
    assert not bad, bad
