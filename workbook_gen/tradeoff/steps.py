"""The step and derivative dimensions: one generated and audited workbook per step.

Step: the extremes of each output read off the table (its largest and smallest
cached value over the ok rows, ``tabulate.extremes``, as the Summary shows them)
against the true extremes of the 50-digit formula, relative to the output's magnitude.
Derivative: finite differences of the tabulated positions against the analytic
velocity and acceleration columns (``rates``), the analytic columns themselves
against the 50-digit reference, and the cost of a workbook that holds the positions
only (plus the difference columns it would need).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..tabulate import Evaluated, evaluate
from ..scene import Scene
from .common import Cost, Progress, Row, cost, floats, mp_diff, mp_floats, relative, studied, worst
from .rates import chains_for, differences, position_factor, time_factor
from .reference50 import Extremes, Precise, true_extremes
from .variants import variant

DEG_STEPS = (10.0, 5.0, 2.0, 1.0, 0.5, 0.1)
STEP_RATIOS = (1.0, 0.5, 0.2, 0.1, 0.05, 0.01)  # of the template's step, for other inputs


def step_settings(scene: Scene) -> tuple[float, ...]:
    spec = scene.template.input
    if spec.unit == "deg":
        return DEG_STEPS
    return tuple(float(f"{spec.step * r:.12g}") for r in STEP_RATIOS)


def step_label(scene: Scene, step: float) -> str:
    return f"{step:g} {scene.template.input.unit}"


@dataclass
class StepRun:
    step: float
    result: Evaluated
    cost: Cost


def find_extremes(scene: Scene, precise: Precise) -> dict[str, Extremes]:
    """True extremes of every studied output, from the finest step's grid."""
    fine = evaluate(variant(scene, step=min(step_settings(scene))))
    found = {}
    for name in studied(scene):
        extremes = true_extremes(precise, name, fine.inputs, floats(fine, name))
        if extremes is not None:
            found[name] = extremes
    return found


def measure_steps(scene: Scene, extremes: dict[str, Extremes],
                  progress: Progress) -> tuple[list[Row], list[StepRun]]:
    rows, runs = [], []
    for step in step_settings(scene):
        current = variant(scene, step=step)
        result = evaluate(current)
        spent = cost(current)
        errors = {}
        for name, true in extremes.items():
            found = result.extremes[name]  # over the ok rows, as the Summary takes them
            if not found.counted[0]:
                continue
            err = max(abs(found.hi[0] - true.maximum), abs(found.lo[0] - true.minimum))
            errors[name] = err / true.magnitude if true.magnitude > 0 else err
        note = "" if spent.audit_ok else "the audit flags it (1e-9 against the reference model)"
        rows.append(Row("step", step_label(scene, step), worst(errors), spent.seconds,
                        spent.cells, spent.bytes, spent.rows, errors, note=note,
                        cpu_seconds=spent.cpu))
        runs.append(StepRun(step, result, spent))
        progress(f"step {step_label(scene, step)}")
    return rows, runs


def derivative_progress_steps(scene: Scene) -> int:
    return len(step_settings(scene)) if chains_for(scene.template, scene.outputs)[1] else 0


def measure_derivatives(scene: Scene, precise: Precise, runs: list[StepRun],
                        progress: Progress) -> list[Row]:
    template = scene.template
    _, chains = chains_for(template, scene.outputs)
    if not chains:
        return [Row("derivative", "n/a", None, None, None, None,
                    note=f"{template.id}: no position -> velocity -> acceleration columns "
                         "among the scene's outputs")]
    rates = [n for c in chains for n in (c.velocity, c.acceleration)]
    base = evaluate(scene)
    reference = precise.table(base.inputs, rates)
    analytic = {n: relative(mp_diff(floats(base, n), reference, n), mp_floats(reference, n))
                for n in rates}
    factor = time_factor(template, scene.parameters)
    rows = []
    for run in runs:
        label = step_label(scene, run.step)
        rows.append(Row("derivative", f"analytic, {label}", worst(analytic), run.cost.seconds,
                        run.cost.cells, run.cost.bytes, run.cost.rows, dict(analytic),
                        note="analytic columns against 50 digits at the scene's rows",
                        cpu_seconds=run.cost.cpu))
        positions = variant(scene, step=run.step, outputs=tuple(c.position for c in chains))
        spent = cost(positions)
        extra = 2 * len(chains) * run.result.rows  # a difference column per rate
        for scheme in ("central", "forward"):
            errors = {}
            for chain in chains:
                y = floats(run.result, chain.position) * position_factor(template, chain.position)
                d1, d2 = differences(y, run.step, scheme)
                v, a = floats(run.result, chain.velocity), floats(run.result, chain.acceleration)
                errors[chain.velocity] = relative(d1 * factor - v, v)
                errors[chain.acceleration] = relative(d2 * factor ** 2 - a, a)
            rows.append(Row("derivative", f"{scheme}, {label}", worst(errors), spent.seconds,
                            spent.cells + extra, spent.bytes, spent.rows, errors,
                            note="positions-only workbook plus the difference columns",
                            cpu_seconds=spent.cpu))
        progress(f"derivatives {label}")
    return rows
