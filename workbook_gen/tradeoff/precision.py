"""The precision dimension: float64 formulas against the 50-digit reference.

The float64 values are the workbook's cached values (numpy, as ``compute``
gives them).  Compared: every studied output over the whole table at the
scene's step, and at the rows of the finest step nearest each output's
maximum and minimum (three rows either side; section 9).  Errors are relative
to the output's magnitude.  Also timed: the same table at 30 and 50 digits.
"""

from __future__ import annotations

import time

import mpmath
import numpy as np

from ..tabulate import evaluate
from ..scene import Scene
from .common import Progress, Row, floats, mp_diff, mp_floats, relative, studied, worst
from .reference50 import Extremes, Precise
from .steps import StepRun

NEAR = 3  # rows either side of an extreme


def _digits_error(low: list[dict], high: list[dict], name: str) -> np.ndarray:
    out = np.full(len(low), np.nan)
    with mpmath.workdps(60):
        for i, (a, b) in enumerate(zip(low, high)):
            if isinstance(a[name], mpmath.mpf) and isinstance(b[name], mpmath.mpf):
                out[i] = float(a[name] - b[name])
    return out


def measure_precision(scene: Scene, precise: Precise, extremes: dict[str, Extremes],
                      finest: StepRun, progress: Progress) -> list[Row]:
    names = studied(scene)
    t, c = time.perf_counter(), time.process_time()
    result = evaluate(scene)
    t64, c64 = time.perf_counter() - t, time.process_time() - c
    t, c = time.perf_counter(), time.process_time()
    reference = precise.table(result.inputs, names)
    t50, c50 = time.perf_counter() - t, time.process_time() - c
    whole = {n: relative(mp_diff(floats(result, n), reference, n), mp_floats(reference, n))
             for n in names}
    n_values = result.rows * len(names)
    rows = [Row("precision", "float64, whole table", worst(whole), t64, n_values, None,
                result.rows, whole, note="numpy, as the cached values", cpu_seconds=c64)]

    near, compared = {}, 0
    fine = finest.result
    for name, true in extremes.items():
        found = fine.extremes[name]  # over the ok rows, as the Summary takes them
        if not found.counted[0]:
            continue
        y = floats(fine, name)
        picks = set()
        for i in (int(found.hi_row[0]), int(found.lo_row[0])):
            picks.update(range(max(0, i - NEAR), min(fine.rows, i + NEAR + 1)))
        idx = sorted(picks)
        values = precise.table(fine.inputs[idx], (name,))
        diff = mp_diff(y[idx], values, name)
        compared += len(idx)
        worst_diff = np.nanmax(np.abs(diff)) if np.isfinite(diff).any() else np.nan
        near[name] = float(worst_diff / true.magnitude) if true.magnitude > 0 else worst_diff
    rows.append(Row("precision", "float64, near the extremes", worst(near), None, compared,
                    None, fine.rows, near,
                    note=f"rows of the {finest.step:g} step within {NEAR} of each extreme"))

    low = Precise(scene, dps=30)
    t, c = time.perf_counter(), time.process_time()
    thirty = low.table(result.inputs, names)
    t30, c30 = time.perf_counter() - t, time.process_time() - c
    digits = {n: relative(_digits_error(thirty, reference, n), mp_floats(reference, n))
              for n in names}
    rows.append(Row("precision", "mpmath 30 digits, whole table", worst(digits), t30, n_values,
                    None, result.rows, digits, cpu_seconds=c30))
    rows.append(Row("precision", "mpmath 50 digits, whole table", None, t50, n_values, None,
                    result.rows, note="the reference", cpu_seconds=c50))
    progress("precision")
    return rows
