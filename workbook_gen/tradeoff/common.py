"""What every tradeoff dimension shares: a measured row, the cost of a workbook,
the columns a study compares, and a progress callback."""

from __future__ import annotations

import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import mpmath
import numpy as np

from ..tabulate.extremes import ok_rows
from ..tabulate import Evaluated
from ..scene import Scene

#: progress(label): called once per finished step of work (``progress_steps`` in all).
Progress = Callable[[str], None]

#: Columns left out of the extremes and precision studies: their table values are
#: an iteration's stopping point, not a smooth function of the input (measured
#: under "method").  Columns without a unit (flags, counts) are left out as well.
ITERATED = {"actuator_linkage": ("phi_2_iter",)}


def quiet(label: str) -> None:
    """A progress callback that shows nothing."""


@dataclass
class Row:
    """One measured setting of one dimension."""

    dimension: str            # "step" | "method" | "derivative" | "precision"
    setting: str              # "10 deg", "newton 3", "central, 1 deg", "float64, whole table"
    max_error: float | None   # worst relative error (to the output's magnitude); None: n/a
    seconds: float | None     # generate + audit (precision: the evaluation itself)
    cells: int | None         # formula cells of the workbook (precision: values compared)
    bytes: int | None         # size of the workbook
    rows: int | None = None   # Table rows
    errors: dict[str, float] = field(default_factory=dict)  # per quantity
    abs_error: float | None = None
    note: str = ""
    cpu_seconds: float | None = None  # process time of the same work (this process)

    def to_json(self) -> dict:
        def num(x):
            return None if x is None or not np.isfinite(x) else float(x)
        return {"dimension": self.dimension, "setting": self.setting,
                "max_error": num(self.max_error), "seconds": num(self.seconds),
                "cells": self.cells, "bytes": self.bytes, "rows": self.rows,
                "errors": {k: num(v) for k, v in self.errors.items()},
                "abs_error": num(self.abs_error), "note": self.note,
                "cpu_seconds": num(self.cpu_seconds)}


@dataclass(frozen=True)
class Cost:
    generate: float
    audit: float
    cells: int
    bytes: int
    rows: int
    audit_ok: bool
    cpu: float  # process time of generate + audit (what a loaded machine does not inflate)

    @property
    def seconds(self) -> float:
        return self.generate + self.audit


def cost(scene: Scene) -> Cost:
    """Generate the scene's workbook into a temporary folder and audit it, timed (wall and
    process time)."""
    from ..auditor import audit
    from ..workbook import write_workbook
    with tempfile.TemporaryDirectory(prefix="workbook-gen-tradeoff-") as tmp:
        cpu, t0 = time.process_time(), time.perf_counter()
        path = write_workbook(scene, tmp, force=True)
        t1 = time.perf_counter()
        report = audit(path)
        t2 = time.perf_counter()
        return Cost(t1 - t0, t2 - t1, report.formula_cells, Path(path).stat().st_size,
                    scene.sweep.rows, report.ok, time.process_time() - cpu)


def floats(result: Evaluated, name: str, ok_only: bool = True) -> np.ndarray:
    """A column as float64, NaN where it holds an Excel error and, with ``ok_only``, in the
    rows whose status is not ok: the tradeoff measures what the workbook vouches for, by
    the Summary's rule (a flagged row, a toggle, a dead centre, a row not converged never
    sets an extreme nor an error; ``extremes.ok_rows``)."""
    column = result.columns[name]
    bad = column.err != 0
    if ok_only:
        bad = bad | ~ok_rows(result.status)
    return np.where(bad, np.nan, column.val.astype(float))


def studied(scene: Scene) -> tuple[str, ...]:
    """The requested outputs whose extremes and precision are measured."""
    skip = set(ITERATED.get(scene.template.id, ()))
    return tuple(n for n in scene.outputs
                 if n not in skip and scene.template.quantity(n).unit)


def mp_floats(values: list[dict], name: str) -> np.ndarray:
    """A column of 50-digit rows as float64 (NaN where an error)."""
    return np.array([float(v[name]) if isinstance(v[name], mpmath.mpf) else np.nan
                     for v in values])


def mp_diff(table: np.ndarray, values: list[dict], name: str) -> np.ndarray:
    """table - reference, row by row, taken in high precision before rounding to float64
    (NaN where either is undefined)."""
    out = np.full(len(table), np.nan)
    with mpmath.workdps(60):
        for i, (a, row) in enumerate(zip(table, values)):
            b = row[name]
            if np.isfinite(a) and isinstance(b, mpmath.mpf):
                out[i] = float(mpmath.mpf(float(a)) - b)
    return out


def relative(diff: np.ndarray, reference: np.ndarray) -> float:
    """max |diff| / max |reference| over the rows where both are defined (NaN if none)."""
    ok = np.isfinite(diff) & np.isfinite(reference)
    if not ok.any():
        return float("nan")
    scale = np.max(np.abs(reference[ok]))
    worst = np.max(np.abs(diff[ok]))
    return float(worst / scale) if scale > 0 else float(worst)


def worst(errors: dict[str, float]) -> float | None:
    values = [v for v in errors.values() if np.isfinite(v)]
    return max(values) if values else None
