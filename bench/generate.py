"""Time to generate the sewing-machine workbook at 10, 1 and 0.1 deg, against plain numpy
evaluating the same closed form (the peer, same run), and the worst error of the written
cached values against the independent reference model; then the cost per design variant
of the 10-deg workbook built in memory (``workbook_bytes``, what ``batch`` pays per
variant in a worker), against plain numpy on the same variants.

    python bench/generate.py [--variants N] [--steps 10,1,0.1] [--json FILE]

``--json FILE`` also writes the figures with the machine and the load (bench/benchinfo.py).
"""

from __future__ import annotations

import argparse
import platform
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from workbook_gen.tabulate import evaluate
from workbook_gen.reference import solve
from workbook_gen.scene import load_scene, parse_scene
from workbook_gen.workbook import workbook_bytes, write_workbook

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchinfo  # noqa: E402

SCENE = "templates/sewing_machine.toml"


def best(fn, repeat: int, clock=time.perf_counter) -> float:
    times = []
    for _ in range(repeat):
        start = clock()
        fn()
        times.append(clock() - start)
    return min(times)


def per_variant(count: int) -> dict:
    """ms per 10-deg variant (l_BC swept) in one process: wall and CPU, best of 3 passes."""
    text = Path(SCENE).read_text(encoding="utf-8")
    scenes = [parse_scene(text, SCENE, overrides={"l_BC": 100.0 + 0.01 * i})
              for i in range(count)]
    workbook_bytes(scenes[0], "warm-up.xlsx")  # first-use costs: imports, printed templates

    def run(fn) -> tuple[float, float]:
        walls, cpus = [], []
        for _ in range(3):
            wall, cpu = time.perf_counter(), time.process_time()
            for scene in scenes:
                fn(scene)
            walls.append(time.perf_counter() - wall)
            cpus.append(time.process_time() - cpu)
        return 1000 * min(walls) / count, 1000 * min(cpus) / count

    book_wall, book_cpu = run(lambda scene: workbook_bytes(scene, "variant.xlsx"))
    numpy_wall, numpy_cpu = run(evaluate)
    print(f"\nper 10-deg variant, {count} variants of l_BC, one process (best of 3):")
    print(f"  workbook_bytes: {book_wall:7.1f} ms wall {book_cpu:7.1f} ms CPU")
    print(f"  plain numpy:    {numpy_wall:7.1f} ms wall {numpy_cpu:7.1f} ms CPU "
          f"(the closed form alone; workbook / numpy = {book_cpu / numpy_cpu:.1f} in CPU)")
    return {"variants": count, "workbook_ms": book_wall, "workbook_cpu_ms": book_cpu,
            "numpy_ms": numpy_wall, "numpy_cpu_ms": numpy_cpu}


def main() -> None:
    args = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    args.add_argument("--variants", type=int, default=100, help="variants for the per-variant "
                      "figure (default 100)")
    args.add_argument("--steps", default="10,1,0.1", help="steps in deg (default 10,1,0.1)")
    args.add_argument("--json", metavar="FILE", help="also write the figures, the machine and "
                      "the load to FILE")
    parsed = args.parse_args()
    count = parsed.variants
    benchinfo.check_writable(parsed.json)
    record, steps = benchinfo.Record(), []
    print(f"machine: {platform.machine()}, {platform.python_implementation()} "
          f"{platform.python_version()}, {platform.platform()}")
    print(f"{'step':>6}{'rows':>7}{'formula cells':>15}{'generate s':>12}{'CPU s':>8}"
          f"{'numpy s':>10}{'ratio':>8}{'worst vs reference':>20}")
    for step in (float(x) for x in parsed.steps.split(",")):
        scene = load_scene(SCENE, step=step)
        with tempfile.TemporaryDirectory() as out:
            seconds = best(lambda: write_workbook(scene, out, force=True), 3 if step < 1 else 5)
            cpu = best(lambda: write_workbook(scene, out, force=True), 3 if step < 1 else 5,
                       time.process_time)
        numpy_seconds = best(lambda: evaluate(scene), 5)
        numpy_cpu = best(lambda: evaluate(scene), 5, time.process_time)
        result = evaluate(scene)
        ref = solve(scene.template.id, scene.parameters, result.inputs)
        worst = max(float(np.nanmax(np.abs(col.val - ref[name])) / np.nanmax(np.abs(ref[name])))
                    for name, col in result.columns.items() if name in ref)
        cells = result.rows * (len(result.model.columns) + 1)
        print(f"{step:>6g}{result.rows:>7}{cells:>15,}{seconds:>12.3f}{cpu:>8.3f}"
              f"{numpy_seconds:>10.4f}"
              f"{seconds / numpy_seconds:>8.0f}{worst:>20.2e}")
        steps.append({"step": step, "rows": result.rows, "cells": cells, "seconds": seconds,
                      "cpu": cpu, "numpy": numpy_seconds, "numpy_cpu": numpy_cpu,
                      "worst_error": worst})
    print("formula cells: the Table's (the Checks sheet adds its residuals and shared terms); "
          "ratio: generate / numpy closed form (wall); CPU s: process time of generate "
          "(the figure to read on a loaded machine)")
    variants = per_variant(count)
    if parsed.json:
        record.write(parsed.json, {"scene": SCENE, "steps": steps, "per_variant": variants})


if __name__ == "__main__":
    main()
