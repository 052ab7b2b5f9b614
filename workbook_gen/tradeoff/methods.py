"""The method dimension: closed form against an iterative method, at the scene's step.

five_bar: ``method = "newton"`` with 1..8 iterations; the last iterates th1_k and th4_k
against the 50-digit closed form.  actuator_linkage: ``method = "bisection"`` at epsilon
1e-2..1e-10 with the fewest halvings that converge in every row (found with 60);
phi_2_iter against the 50-digit closed-form phi_2.  Other templates have a
closed form only: one "n/a" row.
"""

from __future__ import annotations

import numpy as np

from ..tabulate.extremes import ok_rows
from ..tabulate import evaluate
from ..mechanisms import get_template
from ..scene import Scene
from .common import Progress, Row, cost, floats, mp_diff, mp_floats, relative, worst
from .reference50 import Precise
from .variants import variant

NEWTON_ITERATIONS = tuple(range(1, 9))
EPSILONS = tuple(10.0 ** -k for k in range(2, 11))
MAX_HALVINGS = 60
#: template -> (iterated column, closed-form column) pairs; ``{k}`` the iteration count (the
#: last iterate: theta_1 itself is #NUM! where that iterate has not converged)
NEWTON = {"five_bar": (("th1_{k}", "theta_1"), ("th4_{k}", "theta_4"))}
HALVING = {"actuator_linkage": (("phi_2_iter", "phi_2"),)}


def method_progress_steps(scene: Scene) -> int:
    tid = scene.template.id
    return (1 + len(NEWTON_ITERATIONS) if tid in NEWTON
            else 1 + len(EPSILONS) if tid in HALVING else 0)


def _with(scene: Scene, names) -> tuple[str, ...]:
    return scene.outputs + tuple(n for n in names if n not in scene.outputs)


def _audit_note(spent) -> str:
    return "" if spent.audit_ok else "the audit flags it (1e-9 against the reference model)"


def _flagged(result) -> str:
    """How many assembled rows the workbook flags (not converged, singular): they set no
    Summary extreme (docs/workbook.md, Summary)."""
    flagged = int(np.sum(result.assembled & ~ok_rows(result.status)))
    return f"{flagged} rows flagged" if flagged else ""


def _closed(scene: Scene, pairs, progress: Progress):
    """The closed-form row and the 50-digit closed-form columns at the scene's rows."""
    template = get_template(scene.template.id).with_options({**scene.options, "method": "closed"})
    known = {q.name for q in template.quantities}
    outputs = tuple(n for n in scene.outputs if n in known)
    outputs += tuple(c for _, c in pairs if c not in outputs)
    closed = variant(scene, options={"method": "closed"}, outputs=outputs)
    result = evaluate(closed)
    names = [c for _, c in pairs]
    reference = Precise(closed).table(result.inputs, names)
    errors = {n: relative(mp_diff(floats(result, n), reference, n), mp_floats(reference, n))
              for n in names}
    spent = cost(closed)
    row = Row("method", "closed form", worst(errors), spent.seconds, spent.cells, spent.bytes,
              spent.rows, errors, note=_audit_note(spent), cpu_seconds=spent.cpu)
    progress("method: closed form")
    return row, reference


def _against(result, pairs, reference) -> tuple[dict[str, float], float, int]:
    """The iterates against the closed form in every row: what is measured is how the
    error falls with the iterations, so the rows the workbook flags "not converged" are
    measured too (and counted in the note by ``_flagged``)."""
    errors, abs_error, missing = {}, 0.0, 0
    for it, cl in pairs:
        y = floats(result, it, ok_only=False)
        ref = mp_floats(reference, cl)
        diff = mp_diff(y, reference, cl)
        missing += int(np.sum(np.isfinite(ref) & ~np.isfinite(y)))
        errors[it] = relative(diff, ref)
        if np.isfinite(diff).any():
            abs_error = max(abs_error, float(np.nanmax(np.abs(diff))))
    return errors, abs_error, missing


def _newton(scene: Scene, progress: Progress) -> list[Row]:
    templates = NEWTON[scene.template.id]
    first, reference = _closed(scene, templates, progress)
    rows = [first]
    for k in NEWTON_ITERATIONS:
        pairs = tuple((it.format(k=k), cl) for it, cl in templates)
        current = variant(scene, options={"method": "newton", "iterations": k},
                          outputs=_with(scene, [it for it, _ in pairs]))
        result = evaluate(current)
        errors, abs_error, missing = _against(result, pairs, reference)
        spent = cost(current)
        note = "; ".join(filter(None, [f"{missing} rows without a value" if missing else "",
                                       _flagged(result), _audit_note(spent)]))
        rows.append(Row("method", f"newton {k}", worst(errors), spent.seconds, spent.cells,
                        spent.bytes, spent.rows, errors, abs_error, note, spent.cpu))
        progress(f"method: newton {k}")
    return rows


def _halving(scene: Scene, progress: Progress) -> list[Row]:
    pairs = HALVING[scene.template.id]
    first, reference = _closed(scene, pairs, progress)
    rows = [first]
    outputs = _with(scene, [it for it, _ in pairs] + ["halvings_used"])
    for eps in EPSILONS:
        probe = variant(scene, options={"method": "bisection", "halvings": MAX_HALVINGS},
                        parameters={"epsilon": eps}, outputs=outputs)
        used = floats(evaluate(probe), "halvings_used", ok_only=False)
        halvings = int(np.nanmax(used)) if np.isfinite(used).any() else MAX_HALVINGS
        current = variant(scene, options={"method": "bisection", "halvings": halvings},
                          parameters={"epsilon": eps}, outputs=outputs)
        result = evaluate(current)
        errors, abs_error, missing = _against(result, pairs, reference)
        spent = cost(current)
        note = "; ".join(filter(None, [f"{halvings} halvings",
                                       f"{missing} rows not converged" if missing else "",
                                       _flagged(result), _audit_note(spent)]))
        rows.append(Row("method", f"epsilon {eps:.0e}", worst(errors), spent.seconds,
                        spent.cells, spent.bytes, spent.rows, errors, abs_error, note,
                        spent.cpu))
        progress(f"method: epsilon {eps:.0e}")
    return rows


def measure_methods(scene: Scene, progress: Progress) -> list[Row]:
    tid = scene.template.id
    if tid in NEWTON:
        return _newton(scene, progress)
    if tid in HALVING:
        return _halving(scene, progress)
    return [Row("method", "n/a", None, None, None, None,
                note=f"{tid} has a closed form only (no iterative method option)")]
