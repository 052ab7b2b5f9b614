"""For workbooks made by workbook-gen: every Table column against the independent
reference model, the closure checks, and the paper's error table.

The mechanism, parameters and inputs are read off the workbook itself (About,
Parameters, Table column A), so a workbook whose parameters were edited and
recalculated in Excel is checked against the model with its new parameters.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field

import numpy as np

from .. import reference
from ..cellref import a1, row_col
from ..reference.newton import NOISE
from .noise import INPUT, ColumnNoise, column_trees, numbers_or_nan

REFERENCE_TOLERANCE = 1e-9  # of the column's magnitude, or of its rounding noise (noise.py)
# An angle's magnitude is at least a radian: a rod 1e20 long at 4e-17 deg to the slide is
# at 0 deg to within the reference's closure, and 4e-17 deg is not a relative error of 1.
ANGLE_FLOOR = {"deg": 180.0 / np.pi, "rad": 1.0}
# An angle and the same angle a whole number of turns away are one position: the workbook
# and the model may choose different turns (a sweep from -540 deg, phi_slide = 720).
TURN = {"deg": 360.0, "rad": 2.0 * np.pi}
# Rows the workbook flags as singular: their rates are undefined or half their digits are
# the model's (Newton at a double root), so they are counted, not compared.  A row that is
# "not converged" or on the "other branch" is compared: the model shows how far off it is.
SINGULAR = frozenset({"dead centre", "toggle", "limit", "singular"})  # five_bar, parallel_4dof: limit, singular
# Rounding noise m (noise.py) allows an error of NOISE_ULPS * eps * m: as a magnitude to
# measure the error against, that is m * NOISE_ULPS * eps / REFERENCE_TOLERANCE.
NOISE_ULPS = 1024
NOISE_TO_SCALE = NOISE_ULPS * np.finfo(float).eps / REFERENCE_TOLERANCE
PAPER_QUANTITY = "alpha_5"  # the sewing-machine paper checked the lever's angular acceleration
_HEADER = re.compile(r"^(\w+)(?: \[(.*)\])?$")
CRANK_PIN = {"theta_1r", "psi", "theta_2r", "x_B", "y_B", "u_B", "n_B"}  # defined whether or not the rod reaches


@dataclass
class QuantityCheck:
    name: str
    rows: int
    max_error: float          # relative to the column's magnitude
    worst_row_input: float | None
    wrong_rows: list[str] = field(default_factory=list)  # cells valued where nothing assembles, ...
    flagged_rows: int = 0     # rows flagged singular (toggle, dead centre): not compared
    # the Table rows (as numbered in the sheet) over the tolerance or in ``wrong_rows``
    bad_rows: list[int] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return self.max_error <= REFERENCE_TOLERANCE and not self.wrong_rows


@dataclass
class MechanicsReport:
    mechanism: str
    generator: str
    quantities: list[QuantityCheck]
    residuals: dict[str, float]        # check name -> max |r| (recomputed)
    tolerance: float | None
    paper_table: list[tuple[float, float, float, float]]  # input, ours, reference, error %
    # rows whose status flags a singular or unconverged row (toggle, dead centre, ...)
    flagged: dict[str, int] = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        residuals_ok = self.tolerance is None or all(
            isinstance(r, float) and r <= self.tolerance for r in self.residuals.values())
        return residuals_ok and all(q.ok for q in self.quantities)


def _column(column_of, sheet: str, col: int, rows: range):
    return column_of(sheet, col, rows.start, rows.stop - 1)


def _row(sheet, row: int) -> list:
    """``sheet.row(row)``, without indexing every row of the sheet."""
    return sheet.row_cells(row)


def _sheet(book, name: str):
    return book.sheet(name) if name in book.sheet_names else None


def _about(book) -> dict[str, object]:
    about = _sheet(book, "About")
    if about is None:
        return {}
    out = {}
    for cell in about.column(1):
        value = about.cell(cell.row, 2)
        if isinstance(cell.value, str) and value is not None:
            out[cell.value] = value.value
    return out


def _ours(book) -> tuple[str, str, dict] | None:
    """(mechanism, generator, About) of a workbook made by workbook-gen for a mechanism
    we model, with its Table and Parameters sheets; else None."""
    about = _about(book)
    mechanism, generator = about.get("mechanism"), str(about.get("generator", ""))
    if not generator.startswith("workbook-gen") or mechanism not in reference.MECHANISMS:
        return None
    if _sheet(book, "Table") is None or _sheet(book, "Parameters") is None:
        return None
    return mechanism, generator, about


def noise_trees(book, runs=(), has_formula=None) -> dict | None:
    """The formula trees of the Table's columns, read from their text alone (no value):
    ``check_mechanics``'s ``trees``, computed ahead.

    ``runs``: the evaluator's runs (a column's rows equal in R1C1 form, one tree each): a
    column that is one run over the data rows has that run's tree, a column without a
    run or formula (``has_formula(key)``) is an input; other columns are read from their
    text (column_tree)."""
    if _ours(book) is None:
        return None
    table = _sheet(book, "Table")
    rows = range(2, table.max_row + 1)
    of_column: dict[int, list] = {}
    for run in runs:
        if run.sheet == table.name:
            of_column.setdefault(run.col, []).append(run)
    out = {}
    for col in range(1, table.max_col + 1):
        mine = of_column.get(col, [])
        if len(mine) == 1 and (mine[0].first, mine[0].last) == (rows.start, rows.stop - 1):
            out[col] = mine[0].node
        elif has_formula and not mine and not has_formula((table.name, rows.start, col)):
            out[col] = INPUT
        else:
            out.update(column_trees(table, rows, [col]))
    return out


def check_mechanics(book, value_of, column_of, trees: dict | None = None
                    ) -> MechanicsReport | None:
    """``value_of(sheet, row, col)`` gives one recomputed value, ``column_of(sheet, col,
    first, last)`` a column of them; ``trees``: ``noise_trees(book)`` if already known.
    None unless the workbook was made by workbook-gen for a mechanism we model."""
    ours = _ours(book)
    if ours is None:
        return None
    mechanism, generator, about = ours
    table, params_sheet = _sheet(book, "Table"), _sheet(book, "Parameters")
    params, known = {}, reference.known_parameters(mechanism)
    for cell in params_sheet.column(1)[1:]:
        value = value_of("Parameters", cell.row, 2)
        if cell.value in known and isinstance(value, (int, float)):
            params[cell.value] = float(value)
    rows = range(2, table.max_row + 1)
    inputs = np.array(_column(column_of, "Table", 1, rows), dtype=float)
    try:
        options = json.loads(str(about.get("options") or "{}"))
    except json.JSONDecodeError:
        options = {}
    solved = reference.solve(mechanism, params, inputs, options)
    flagged: dict[str, int] = {}
    singular = np.zeros(len(rows), dtype=bool)
    for cell in _row(table, 1)[1:]:
        if cell.value == "status":
            for i, text in enumerate(_column(column_of, "Table", cell.col, rows)):
                if isinstance(text, str) and text not in ("ok", "cannot assemble"):
                    flagged[text] = flagged.get(text, 0) + 1
                    singular[i] = text in SINGULAR
    noise = ColumnNoise(table, rows, lambda col: _column(column_of, "Table", col, rows),
                        lambda name: _name_value(book, value_of, name), trees)
    quantities = []
    for cell in _row(table, 1)[1:]:
        match = _HEADER.match(str(cell.value))
        name = match.group(1) if match else None
        if name not in solved:
            continue
        ours_noise, ref_noise = noise.of(cell.col), solved.get(name + NOISE)
        if ref_noise is not None:  # the model's own cancellation (sewing h_BC = y_B - y_C)
            ref_noise = np.where(np.isfinite(ref_noise), ref_noise, 0.0)
            ours_noise = ref_noise if ours_noise is None else np.maximum(ours_noise, ref_noise)
        quantities.append(_check_column(name, _column(column_of, "Table", cell.col, rows),
                                        solved[name], inputs, cell.col, singular,
                                        ours_noise, match.group(2)))
    residuals, tolerance = _residuals(book, value_of)
    return MechanicsReport(mechanism, generator, quantities, residuals, tolerance,
                           _paper_table(table, column_of, solved, inputs, rows), flagged)


def _name_value(book, value_of, name: str) -> float | None:
    """The number a defined name holds (a Parameters cell), or None."""
    text = book.resolve_name(name)
    if not text:
        return None
    sheet, _, ref = text.lstrip("=").rpartition("!")
    try:
        row, col = row_col(ref)
        value = value_of(sheet.strip("'"), row, col)
    except (ValueError, KeyError, AttributeError):
        return None
    return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) \
        else None


def _check_column(name, values, ref, inputs, col, singular, noise, unit) -> QuantityCheck:
    """Worst error of a column against the model, over the larger of the column's
    magnitude and each row's rounding noise; rows flagged singular are counted, not
    compared (the model's Newton loses half its digits at a dead centre)."""
    ours = numbers_or_nan(values)
    wrong, bad = [], []
    for i in np.flatnonzero(np.isfinite(ours) != np.isfinite(ref)):
        if singular[i]:  # a flagged row may hold an error value, or the model none
            continue
        if name in CRANK_PIN and np.isfinite(ours[i]):
            continue
        bad.append(int(i) + 2)  # the Table's data start at its row 2
        what = "a value where the model has none" if np.isfinite(ours[i]) else (
            f"{values[i]} where the model has {ref[i]:.12g}")
        wrong.append(f"{a1(i + 2, col)}: {what}")
    finite = np.isfinite(ours) & np.isfinite(ref)
    both = finite & ~singular
    skipped = int((finite & singular).sum())
    if not both.any():
        return QuantityCheck(name, 0, 0.0, None, wrong, skipped, bad)
    scale = max(float(np.max(np.abs(ref[both]))), ANGLE_FLOOR.get(unit or "", 0.0), 1e-300)
    if noise is not None:
        scale = np.maximum(scale, NOISE_TO_SCALE * np.where(np.isfinite(noise), noise, 0.0))
    errors = np.where(both, np.abs(_apart(ours, ref, TURN.get(unit or ""))) / scale, 0.0)
    worst = int(np.argmax(errors))
    bad = sorted(set(bad).union((np.flatnonzero(errors > REFERENCE_TOLERANCE) + 2).tolist()))
    return QuantityCheck(name, int(both.sum()), float(errors[worst]), float(inputs[worst]),
                         wrong, skipped, bad)


def _apart(ours, ref, turn: float | None):
    """ours - ref, or for an angle (a ``turn`` given) its distance modulo a whole turn,
    in [-turn/2, turn/2)."""
    diff = ours - ref
    if turn is None:
        return diff
    return np.remainder(diff + turn / 2, turn) - turn / 2


def _residuals(book, value_of) -> tuple[dict[str, float], float | None]:
    checks = _sheet(book, "Checks")
    if checks is None:
        return {}, None
    tolerance = value_of("Checks", 1, 2)
    out = {}
    for cell in _row(checks, 7)[1:]:
        if cell.value in ("cannot assemble", "flagged"):
            break  # the residuals end here: the flags, then the terms they share
        value = value_of("Checks", 4, cell.col)
        out[str(cell.value)] = float(value) if isinstance(value, (int, float)) else value
    return out, float(tolerance) if isinstance(tolerance, (int, float)) else None


def _paper_table(table, column_of, solved, inputs, rows):
    """The lever's angular acceleration against the model in percent, per 10 deg."""
    if PAPER_QUANTITY not in solved:
        return []
    col = next((c.col for c in _row(table, 1) if str(c.value).startswith(PAPER_QUANTITY + " ")),
               None)
    if col is None:
        return []
    ours = numbers_or_nan(_column(column_of, "Table", col, rows))
    out = []
    for i, angle in enumerate(inputs):
        if abs(angle / 10.0 - round(angle / 10.0)) > 1e-9 or not np.isfinite(solved[PAPER_QUANTITY][i]):
            continue
        ref = float(solved[PAPER_QUANTITY][i])
        error = 100.0 * abs(ours[i] - ref) / abs(ref) if ref else float(ours[i] != ref) * 100.0
        out.append((float(angle), float(ours[i]), ref, error))
    return out
