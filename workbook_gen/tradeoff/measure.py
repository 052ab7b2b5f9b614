"""Speed against accuracy on one scene (docs/tradeoff.md, The command): every dimension, in order.

    result = measure(load_scene("templates/sewing_machine.toml"))
    result.rows       # Row per measured setting: dimension, setting, max_error, seconds ...

Dimensions: step (extremes read off the table against the true extremes),
method (closed form against Newton or halving), derivative (analytic rates
against finite differences of the positions), precision (float64 against 50
digits).  The reference throughout is the scene's own trees at 50 digits
(``reference50``); a dimension a template cannot have is one "n/a" row.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

from ..scene import Scene
from .common import Progress, Row, quiet
from .methods import measure_methods, method_progress_steps
from .precision import measure_precision
from .reference50 import Extremes, Precise
from .steps import (derivative_progress_steps, find_extremes, measure_derivatives, measure_steps,
                    step_settings)

DIMENSIONS = ("step", "method", "derivative", "precision")


@dataclass
class Tradeoff:
    scene: Scene
    rows: list[Row]
    extremes: dict[str, Extremes]
    seconds: float
    cpu_seconds: float | None = None  # process time of the whole measurement

    def to_json(self) -> dict:
        return {
            "scene": self.scene.source, "name": self.scene.name,
            "mechanism": self.scene.template.id,
            "input": {"name": self.scene.template.input.name,
                      "unit": self.scene.template.input.unit},
            "reference": "the scene's formulas evaluated with mpmath at 50 digits",
            "rows": [r.to_json() for r in self.rows],
            "extremes": {n: {"max": e.maximum, "at_max": e.at_max, "min": e.minimum,
                             "at_min": e.at_min} for n, e in self.extremes.items()},
            "seconds": self.seconds,
            "cpu_seconds": self.cpu_seconds,
        }


def progress_steps(scene: Scene) -> int:
    """How many progress calls ``measure`` makes."""
    return (2 + len(step_settings(scene)) + derivative_progress_steps(scene)
            + method_progress_steps(scene))


def measure(scene: Scene, progress: Progress = quiet) -> Tradeoff:
    started, cpu = time.perf_counter(), time.process_time()
    precise = Precise(scene)
    extremes = find_extremes(scene, precise)
    progress("true extremes (50 digits)")
    step_rows, runs = measure_steps(scene, extremes, progress)
    method_rows = measure_methods(scene, progress)
    derivative_rows = measure_derivatives(scene, precise, runs, progress)
    precision_rows = measure_precision(scene, precise, extremes, runs[-1], progress)
    rows = step_rows + method_rows + derivative_rows + precision_rows
    return Tradeoff(scene, rows, extremes, time.perf_counter() - started,
                    time.process_time() - cpu)
