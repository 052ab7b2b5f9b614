"""Time to generate the sewing-machine workbook at 10, 1 and 0.1 deg, against plain numpy
evaluating the same closed form (the peer, same run), and the worst error of the written
cached values against the independent reference model.

    python bench/generate.py
"""

from __future__ import annotations

import platform
import tempfile
import time

import numpy as np

from workbook_gen.compute import evaluate
from workbook_gen.reference import solve
from workbook_gen.scene import load_scene
from workbook_gen.workbook import write_workbook

SCENE = "templates/sewing_machine.toml"


def best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    print(f"machine: {platform.machine()}, {platform.python_implementation()} "
          f"{platform.python_version()}, {platform.platform()}")
    print(f"{'step':>6}{'rows':>7}{'formula cells':>15}{'generate s':>12}{'numpy s':>10}"
          f"{'ratio':>8}{'worst vs reference':>20}")
    for step in (10.0, 1.0, 0.1):
        scene = load_scene(SCENE, step=step)
        with tempfile.TemporaryDirectory() as out:
            seconds = best(lambda: write_workbook(scene, out, force=True), 3 if step < 1 else 5)
        numpy_seconds = best(lambda: evaluate(scene), 5)
        result = evaluate(scene)
        ref = solve(scene.template.id, scene.parameters, result.inputs)
        worst = max(float(np.nanmax(np.abs(col.val - ref[name])) / np.nanmax(np.abs(ref[name])))
                    for name, col in result.columns.items() if name in ref)
        cells = result.rows * (len(result.model.columns) + 1)
        print(f"{step:>6g}{result.rows:>7}{cells:>15,}{seconds:>12.3f}{numpy_seconds:>10.4f}"
              f"{seconds / numpy_seconds:>8.0f}{worst:>20.2e}")
    print("formula cells: the Table's (the Checks sheet adds as many again); ratio: "
          "generate / numpy closed form")


if __name__ == "__main__":
    main()
