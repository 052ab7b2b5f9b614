"""tradeoff.methods: the method dimension's errors recomputed independently: the
five-bar's Newton iterates by a plain mpmath Newton-Raphson on the closure (written here
from the equations, not the trees) against mp_reference's closed form; the actuator's
halvings by mp_reference.actuator_bisection at 50 digits.  Workbooks are not written
(the cost is stubbed: what is measured here is the error)."""

from __future__ import annotations

import mpmath
import pytest

from tests import mp_reference
from workbook_gen.scene import load_scene
from workbook_gen.tradeoff import methods
from workbook_gen.tradeoff.common import Cost

QUIET = lambda label: None  # noqa: E731
FREE = Cost(0.0, 0.0, 0, 0, 0, True, 0.0)


def _newton_hand(p, phi_deg, k):
    """k Newton steps on |C - B(t)|^2 = l_2^2 and |C - D(t)|^2 = l_3^2, from the cranks
    perpendicular to pivot->C (deg): f(t) = |C - P - a u(t)|^2 - b^2, f'(t) = 2a (C-P) x u."""
    p = {n: mpmath.mpf(v) for n, v in p.items()}
    v = mpmath.radians(phi_deg)
    cx, cy = p["x_0"] + p["R_path"] * mpmath.cos(v), p["y_0"] + p["R_path"] * mpmath.sin(v)
    out = []
    for px, a, b, turn in ((0, p["l_1"], p["l_2"], 90), (p["l_5"], p["l_4"], p["l_3"], -90)):
        dx, dy = cx - px, cy
        t = mpmath.atan2(dy, dx) + mpmath.radians(turn)
        for _ in range(k):
            f = (dx - a * mpmath.cos(t)) ** 2 + (dy - a * mpmath.sin(t)) ** 2 - b ** 2
            df = 2 * a * (dx * mpmath.sin(t) - dy * mpmath.cos(t))
            t -= f / df
        out.append(mpmath.degrees(t))
    return out


def _wrap(d):
    return (d + 180) % 360 - 180


@pytest.fixture(scope="module")
def five_bar_rows():
    mp = pytest.MonkeyPatch()
    mp.setattr(methods, "NEWTON_ITERATIONS", (1, 3, 8))
    mp.setattr(methods, "cost", lambda scene: FREE)
    try:
        scene = load_scene("templates/five_bar.toml")
        return scene, methods.measure_methods(scene, QUIET)
    finally:
        mp.undo()


def test_newton_errors_against_a_hand_newton_and_the_closed_form(five_bar_rows):
    scene, rows = five_bar_rows
    assert [r.setting for r in rows] == ["closed form", "newton 1", "newton 3", "newton 8"]
    assert rows[0].max_error < 1e-14  # float64 closed form against 50 digits
    xs = [scene.sweep.start + i * scene.sweep.step for i in range(scene.sweep.rows)]
    with mpmath.workdps(50):
        ref = [mp_reference.five_bar(scene.parameters, x)[0] for x in xs]
        for row, k in zip(rows[1:], (1, 3, 8)):
            hand = [_newton_hand(scene.parameters, x, k) for x in xs]
            for j, (it, closed) in enumerate((("th1_{k}", "theta_1"), ("th4_{k}", "theta_4"))):
                diff = [float(_wrap(h[j] - r[closed])) for h, r in zip(hand, ref)]
                scale = max(abs(float(r[closed])) for r in ref)
                expected = max(abs(d) for d in diff) / scale
                got = row.errors[it.format(k=k)]
                if k < 8:
                    assert got == pytest.approx(expected, rel=1e-6, abs=0), (k, it)
                else:
                    assert got < 1e-14 and expected < 1e-14
            if k < 8:
                assert row.abs_error == pytest.approx(
                    max(abs(float(_wrap(h[j] - r[c]))) for h, r in zip(hand, ref)
                        for j, c in enumerate(("theta_1", "theta_4"))), rel=1e-6, abs=0)
    assert rows[1].note == f"{scene.sweep.rows} rows flagged"  # one step converges nowhere
    assert rows[3].note == ""


@pytest.fixture(scope="module")
def actuator_rows():
    mp = pytest.MonkeyPatch()
    mp.setattr(methods, "EPSILONS", (1e-2, 1e-6))
    mp.setattr(methods, "cost", lambda scene: FREE)
    try:
        scene = load_scene("templates/actuator_linkage.toml")
        return scene, methods.measure_methods(scene, QUIET)
    finally:
        mp.undo()


def test_halving_uses_the_fewest_halvings_that_converge_everywhere(actuator_rows):
    scene, rows = actuator_rows
    assert [r.setting for r in rows] == ["closed form", "epsilon 1e-02", "epsilon 1e-06"]
    xs = scene.sweep.values()
    for row, eps in zip(rows[1:], (1e-2, 1e-6)):
        p = dict(scene.parameters, epsilon=eps)
        with mpmath.workdps(50):
            runs = [mp_reference.actuator_bisection(p, x, methods.MAX_HALVINGS) for x in xs]
            halvings = int(max(r["halvings_used"] for r in runs))
            closed = [mp_reference.actuator_linkage(p, x)[0]["phi_2"] for x in xs]
        assert row.note.startswith(f"{halvings} halvings")
        diff = [abs(float(r["phi_2_iter"] - c)) for r, c in zip(runs, closed)]
        expected = max(diff) / max(abs(float(c)) for c in closed)
        assert row.errors["phi_2_iter"] == pytest.approx(expected, rel=1e-6, abs=0)
    assert rows[2].max_error < rows[1].max_error


def test_closed_form_only_templates_and_progress_counts():
    sewing = load_scene("templates/sewing_machine.toml")
    (row,) = methods.measure_methods(sewing, QUIET)
    assert row.setting == "n/a" and row.max_error is None and "closed form only" in row.note
    assert methods.method_progress_steps(sewing) == 0
    assert methods.method_progress_steps(load_scene("templates/five_bar.toml")) == 9
    assert methods.method_progress_steps(load_scene("templates/actuator_linkage.toml")) == 10
