"""Sewing machine and four-bar exactly at their limits, and 1e-12 from them (issue 21,
the table in docs/stability.md, Limits by template).

Each scene puts a limit exactly on a Table row (a 10 deg row, or a row of a sweep that
starts at -537 or 713 deg), or within rounding of it, or 1e-12 (relative) from it:
- sewing machine: rod = crank (dead centres at 0 and 180 deg), rod shorter than the crank
  (reach limits where l_AB |cos| = l_BC: at 60 deg for l_BC = l_AB / 2), the lever's pivot
  F on the path of the block E (E on F: no lever angle);
- four-bar: change points (Grashof boundary), coupler and rocker in line at an assembly
  limit (extended at 90 deg for 80/60/70/30, folded at 60 deg for 80/30/100/30, 120 deg
  for 50/30/40/30), the crank as long as the ground (A on O2 at 0 deg: a kite that
  folds, or no assembly).
For each: (a) no ok row holds a value the 50-digit reference (tests/mp_reference.py)
does not give, and the rows at the limit are flagged with their rates error values;
(b) the workbook passes its own audit, reference model included; (c) LibreOffice
recalculates every file (one run for all) to the cached values; (d) no Summary cell is an
error value while a row is ok; (e) sweeps from anywhere in -720..720 and angle parameters
of any size pass the audit.
"""

from __future__ import annotations

import math
from pathlib import Path

import mpmath
import numpy as np
import openpyxl
import pytest

from extremes_common import assert_sound
from openpyxl.utils import get_column_letter

from tests.engines.test_libreoffice_recalc import TOLERANCE, _magnitudes, _tied_extreme
from workbook_gen import audit, load_scene, write_workbook
from workbook_gen.engines.libreoffice import read_formula_values, recalculated_values_many
from workbook_gen.tabulate import evaluate
from workbook_gen.xlerror import ExcelError

ROOT = Path(__file__).resolve().parents[2] / "templates"
SEWING_RATES = ("v_C", "a_C", "v_FE", "a_FE", "omega_5", "alpha_5")
LEVER_RATES = ("v_FE", "a_FE", "omega_5", "alpha_5", "vx_G", "ay_G")  # the needle's are sound
LEVER = ("theta_5", "x_G", "y_G", "omega_5", "alpha_5", "v_FE")
FOUR_BAR_RATES = ("omega_3", "omega_4", "alpha_3", "alpha_4", "vx_C", "ay_C")


def _fb(g, a, b, c):
    return dict(l_O1O2=g, l_O1A=a, l_AB=b, l_O2B=c)


def _limit_at_63() -> float:
    """The rocker that puts coupler and rocker of 80/60/70/c in line at 63 deg, to
    rounding (50 digits, rounded once)."""
    with mpmath.workdps(50):
        return float(mpmath.sqrt(80 ** 2 + 60 ** 2 - 9600 * mpmath.cos(mpmath.radians(63))) - 70)


def _block_at(theta_deg: float) -> tuple[float, float]:
    """The sewing machine's block E (default lengths, beta_E = 0) at ``theta_deg``, at 50
    digits, rounded: a lever pivot on E's path there."""
    with mpmath.workdps(50):
        t = mpmath.radians(theta_deg)
        x_b, y_b = 32 * mpmath.cos(t), 32 * mpmath.sin(t)
        h, k = mpmath.sqrt(100 ** 2 - x_b ** 2), mpmath.mpf(28) / 100
        return float(x_b * (1 - k)), float(y_b - k * h)


# (id, template, overrides, sweep (start, stop, step) or None, {input: status expected});
# a length 1e-12 (relative) from a limit is written with 15 digits, as typed: LibreOffice
# reads a 17-digit number such as 60 (1 + 1e-12) = 60.000000000060005 an ulp off, which 1e-12
# from a limit moves h 1e-4 (relative) and is no disagreement of the formulas
# "flag": any status but ok and cannot assemble, with the rates error values
SCENES = [
    ("sew-rod-crank", "sewing_machine", {"l_BC": 32.0}, None,
     {0.0: "flag", 180.0: "flag", 360.0: "flag", 10.0: "ok"}),
    ("sew-rod-crank-537", "sewing_machine", {"l_BC": 32.0}, (-537.0, -177.0, 3.0),
     {-360.0: "flag", -180.0: "flag", -357.0: "ok"}),
    ("sew-rod-crank-plus12", "sewing_machine", {"l_BC": 32.000000000032}, None,
     {0.0: "flag", 180.0: "flag", 10.0: "ok"}),
    ("sew-reach60", "sewing_machine", {"l_BC": 16.0}, None,
     {60.0: "flag", 120.0: "flag", 240.0: "flag", 300.0: "flag", 90.0: "ok",
      50.0: "cannot assemble"}),
    ("sew-reach60-537", "sewing_machine", {"l_BC": 16.0}, (-537.0, -177.0, 3.0),
     {-420.0: "flag", -300.0: "flag", -423.0: "ok", -417.0: "cannot assemble"}),
    ("sew-reach60-plus12", "sewing_machine", {"l_BC": 16.000000000016}, None,
     {60.0: "flag", 120.0: "flag"}),
    ("sew-reach60-minus12", "sewing_machine", {"l_BC": 15.999999999984}, None,
     {60.0: "cannot assemble", 70.0: "ok"}),
    ("sew-reach63-537", "sewing_machine", {"l_BC": 32.0 * math.cos(math.radians(63.0))},
     (-537.0, -177.0, 10.0), {-477.0: "flag", -297.0: "flag", -287.0: "ok", -487.0: "cannot assemble"}),
    ("sew-pivot90", "sewing_machine", {"x_F": 0.0, "y_F": 4.0}, None,
     {90.0: "flag", 80.0: "ok"}),
    ("sew-pivot90-plus12", "sewing_machine", {"x_F": 0.0, "y_F": 4.000000000004}, None,
     {90.0: "flag", 100.0: "ok"}),
    ("sew-pivot713", "sewing_machine", dict(zip(("x_F", "y_F"), _block_at(713.0))),
     (713.0, 1073.0, 10.0), {713.0: "flag", 1073.0: "flag", 723.0: "ok"}),
    ("fb-parallelogram", "four_bar", _fb(100.0, 40.0, 100.0, 40.0), None,
     {0.0: "flag", 180.0: "flag", 360.0: "flag", 90.0: "ok"}),
    ("fb-parallelogram-plus12", "four_bar", _fb(100.0, 40.0, 100.0000000001, 40.0), None,
     {0.0: "cannot assemble", 180.0: "flag", 90.0: "ok"}),
    ("fb-changepoint-537", "four_bar", _fb(100.0, 50.0, 110.0, 60.0), (-537.0, -177.0, 3.0),
     {-360.0: "flag", -363.0: "ok"}),
    ("fb-changepoint-plus12", "four_bar", _fb(100.0, 50.0, 110.0, 60.00000000006), None,
     {0.0: "flag", 10.0: "ok"}),
    ("fb-changepoint-minus12", "four_bar", _fb(100.0, 50.0, 110.0, 59.99999999994), None,
     {0.0: "cannot assemble", 10.0: "ok"}),
    ("fb-extended90", "four_bar", _fb(80.0, 60.0, 70.0, 30.0), None,
     {90.0: "flag", 270.0: "flag", 80.0: "ok", 100.0: "cannot assemble"}),
    ("fb-extended90-plus12", "four_bar", _fb(80.0, 60.0, 70.0, 30.00000000003), None,
     {90.0: "flag", 270.0: "flag"}),
    ("fb-extended90-minus12", "four_bar", _fb(80.0, 60.0, 70.0, 29.99999999997), None,
     {90.0: "cannot assemble", 80.0: "ok"}),
    ("fb-folded60-537", "four_bar", _fb(80.0, 30.0, 100.0, 30.0), (-537.0, -177.0, 3.0),
     {-300.0: "flag", -420.0: "flag", -297.0: "ok", -303.0: "cannot assemble"}),
    ("fb-folded60-plus12", "four_bar", _fb(80.0, 30.0, 100.0, 30.00000000003), None,
     {60.0: "flag", 70.0: "ok"}),
    ("fb-extended120-crossed", "four_bar", {**_fb(50.0, 30.0, 40.0, 30.0), "branch": "crossed"},
     None, {120.0: "flag", 240.0: "flag", 110.0: "ok", 130.0: "cannot assemble"}),
    ("fb-extended63-537", "four_bar", _fb(80.0, 60.0, 70.0, _limit_at_63()),
     (-537.0, -177.0, 10.0), {-297.0: "flag", -287.0: "cannot assemble", -307.0: "ok"}),
    ("fb-kite", "four_bar", _fb(100.0, 100.0, 40.0, 40.0), None,
     {0.0: "flag", 360.0: "flag", 10.0: "ok"}),
    ("fb-crank-ground", "four_bar", _fb(100.0, 100.0, 60.0, 40.0), None,
     {0.0: "cannot assemble", 60.0: "flag", 20.0: "ok"}),
]
# the same limits under the templates with masses (shaking force): audit and LibreOffice
MASSES = [
    ("sewm-reach60", "sewing_machine_masses", {"l_BC": 16.0}, None),
    ("sewm-pivot90", "sewing_machine_masses", {"x_F": 0.0, "y_F": 4.0}, None),
    # unbalanced: with the counterweights the shaking force is 0 to rounding, which
    # LibreOffice makes 0 (at the template's own scene too)
    ("fbb-extended90", "four_bar_balanced", {**_fb(80.0, 60.0, 70.0, 30.0), "balance": False},
     None),
    ("fbb-changepoint", "four_bar_balanced", {**_fb(100.0, 50.0, 110.0, 60.0), "balance": False},
     (-537.0, 183.0, 10.0)),
]
# (e) far angles: sweeps from anywhere in -720..720, angle parameters of any size
FAR = [
    ("far-sew-720", "sewing_machine", {}, (-720.0, -360.0, 10.0)),
    ("far-sew-beta", "sewing_machine", {"beta_E": 725.0}, (-537.0, 183.0, 10.0)),
    ("far-sew-beta-big", "sewing_machine", {"beta_E": -1e4, "x_F": 60.0, "y_F": 0.0},
     (713.0, 1073.0, 10.0)),
    ("far-fb-delta", "four_bar", {"delta_C": 725.0}, (-720.0, 720.0, 10.0)),
    ("far-fb-delta-big", "four_bar", {"delta_C": -1e4, "branch": "crossed"}, (713.0, 1073.0, 10.0)),
    ("far-fb-537", "four_bar", _fb(100.0, 50.0, 110.0, 60.0), (-537.0, 183.0, 7.0)),
]


def _scene(name, template, overrides, sweep):
    kwargs = dict(zip(("start", "stop", "step"), sweep)) if sweep else {}
    return load_scene(ROOT / f"{template}.toml", overrides=overrides, name=name, **kwargs)


@pytest.fixture(scope="module")
def books(tmp_path_factory):
    """{id: path} of every scene's workbook, written once."""
    out = tmp_path_factory.mktemp("limits")
    return {name: write_workbook(_scene(name, template, overrides, sweep), out)
            for name, template, overrides, sweep, *_ in SCENES + MASSES + FAR}


@pytest.fixture(scope="module")
def libreoffice_values(books, libreoffice):
    """LibreOffice's values of every workbook, from one run."""
    names = list(books)
    return dict(zip(names, recalculated_values_many([books[n] for n in names])))


@pytest.mark.parametrize("name, template, overrides, sweep, expected", SCENES,
                         ids=[s[0] for s in SCENES])
def test_rows_at_and_near_the_limit_are_exact_or_flagged(name, template, overrides, sweep,
                                                         expected):
    scene = _scene(name, template, overrides, sweep)
    ev = evaluate(scene)
    inputs = [float(x) for x in ev.inputs]
    worst, status = assert_sound(template, scene.parameters, inputs, scene.options)
    rates = (FOUR_BAR_RATES if template == "four_bar" else
             LEVER_RATES if name.startswith("sew-pivot") else SEWING_RATES)
    for x, want in expected.items():
        i = inputs.index(x)
        got = status[i]
        if want != "flag":
            assert got == want, (x, got)
            continue
        assert got not in ("ok", "cannot assemble"), (x, got)
        # a singular rate is an error value, never a huge finite number
        for rate in rates:
            assert ev.columns[rate].err[i] != 0, (x, rate, ev.columns[rate].val[i])
    if name.startswith("sew-pivot"):  # E on F: the lever's angle itself is undefined
        i = inputs.index(min(x for x, w in expected.items() if w == "flag"))
        if ev.columns["s_FE"].val[i] == 0:
            assert all(ev.columns[q].err[i] != 0 for q in LEVER)


# (template, parameters, the limit's crank angle): rows a hair from it, 1e-12 .. 3 deg
NEAR = [
    ("sewing_machine", {"l_BC": 32.0}, 0.0),                 # rod = crank
    ("sewing_machine", {"l_BC": 16.0}, 60.0),                # reach limit
    ("sewing_machine", {"x_F": 0.0, "y_F": 4.0}, 90.0),      # E through the lever pivot
    ("four_bar", _fb(100.0, 50.0, 110.0, 60.0), 0.0),        # change point
    ("four_bar", _fb(80.0, 60.0, 70.0, 30.0), 90.0),         # extended in line
    ("four_bar", _fb(80.0, 30.0, 100.0, 30.0), 60.0),        # folded in line
]


@pytest.mark.parametrize("template, params, limit", NEAR)
def test_rows_a_hair_from_the_limit_are_sound_or_flagged(template, params, limit):
    """Between rounding and a few degrees from the limit each row is within TOL of 50
    digits (of the column's magnitude over the turn) or flagged; the bands that flag
    them are as wide as the digits lost require (docs/stability.md)."""
    spans = (1e-12, 1e-9, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 0.1, 0.5, 1.0, 1.5, 3.0)
    inputs = sorted({10.0 * k for k in range(37)}
                    | {limit + s * k for s in spans for k in (-1, 1)})
    worst, status = assert_sound(template, params, inputs)
    assert status[inputs.index(limit)] not in ("ok", "cannot assemble")


@pytest.mark.parametrize("name", [s[0] for s in SCENES + MASSES + FAR])
def test_own_audit_passes_with_the_reference_model(books, name):
    report = audit(books[name])
    failing = [(q.name, q.max_error, q.worst_row_input, q.wrong_rows[:2])
               for q in report.mechanics.quantities if not q.ok]
    assert not failing and not report.mismatches and report.ok, (
        failing, [m for m in report.mismatches][:2])


@pytest.mark.parametrize("name", [s[0] for s in SCENES + MASSES + FAR])
def test_no_summary_error_while_a_row_is_ok(books, name):
    book = openpyxl.load_workbook(books[name], data_only=True)
    statuses = [c.value for c in next(col for col in book["Table"].iter_cols()
                                      if col[0].value == "status")[1:]]
    assert "ok" in statuses
    errors = [(row[0], v) for row in book["Summary"].iter_rows(values_only=True)
              for v in row[1:] if isinstance(v, str) and v.startswith("#")]
    assert not errors, errors


def _unit(header: object) -> str:
    text = str(header)
    return text[text.find("[") + 1:-1] if text.endswith("]") else ""


def _agree_with_libreoffice(path: Path, theirs: dict) -> int:
    """tests/engines/test_libreoffice_recalc.py's comparison (every formula cell within 1e-12 of
    its column's magnitude, errors and text equal, tied Summary extremes accepted) with
    three allowances that only rows at a limit need: in a Table row that is not ok both
    engines may show different errors (a formula meeting #NUM! and #DIV/0! shows the one
    its engine evaluates first); a Table column that is 0 to rounding (a balanced shaking
    force) is measured against the magnitude of its unit's columns; a Checks residual may
    differ by 1e-10 (a tenth of check_tol: LibreOffice makes a difference within 2^-48 of
    its operands 0, and the terms of a residual next to a limit are large)."""
    ours = read_formula_values(path)
    table = list(openpyxl.load_workbook(path, data_only=True)["Table"].iter_rows(values_only=True))
    header, rows = table[0], table[1:]
    status = {r + 2: row[header.index("status")] for r, row in enumerate(rows)}
    units = {get_column_letter(c + 1): _unit(h) for c, h in enumerate(header)}
    cells = 0
    for sheet, values in ours.items():
        scale = _magnitudes(sheet, values)
        of_unit: dict[str, float] = {}
        if sheet == "Table":
            for col, m in list(scale.items()):
                of_unit[units[col]] = max(of_unit.get(units[col], 0.0), m)
        for ref, value in values.items():
            other, cells = theirs[sheet][ref], cells + 1
            col, row = ref.rstrip("0123456789"), int(ref.lstrip("ABCDEFGHIJKLMNOPQRSTUVWXYZ"))
            if (sheet == "Summary" and ref[0] in "DF" and value != other
                    and _tied_extreme(path, ref, value, other)):
                continue
            if (isinstance(value, ExcelError) and isinstance(other, ExcelError)
                    and sheet == "Table" and status.get(row) != "ok"):
                continue
            if not isinstance(value, float) or isinstance(value, bool):
                assert other == value, f"{sheet}!{ref}: ours {value!r}, LibreOffice {other!r}"
                continue
            assert isinstance(other, float), f"{sheet}!{ref}: ours {value!r}, LibreOffice {other!r}"
            size = scale[col]
            if sheet == "Table" and size <= 1e-9 * of_unit[units[col]]:
                size = of_unit[units[col]]
            allowed = TOLERANCE * max(size, 1e-300)
            if sheet == "Checks":
                allowed = max(allowed, 1e-10)
            assert abs(value - other) <= allowed, (
                f"{sheet}!{ref}: ours {value!r}, LibreOffice {other!r}")
    return cells


@pytest.mark.parametrize("name", [s[0] for s in SCENES + MASSES + FAR])
def test_libreoffice_recalculates_the_same_values(books, libreoffice_values, name):
    assert _agree_with_libreoffice(books[name], libreoffice_values[name]) > 100
