"""Time the workbook evaluator on the sewing-machine workbook at 0.1 degree steps.

Figures, in one process: reading the formulas with openpyxl (reported apart), the
vectorised evaluation (whole call, and its phases), the scalar cell-by-cell
evaluation, and plain numpy evaluating the closed form (``tabulate.evaluate``), which is
the peer: ratios are against it. Best of REPEAT runs (the scalar path runs once).

    python bench/evaluator.py [--step 0.1] [--repeat 3] [--no-scalar]
"""

from __future__ import annotations

import argparse
import platform
import tempfile
import time

import openpyxl

from workbook_gen.tabulate import evaluate
from workbook_gen.evaluator import evaluate_cells
from workbook_gen.scene import load_scene
from workbook_gen.workbook import write_workbook
from workbook_gen.xlerror import ExcelError


def read_cells(path):
    """Formulas, constants and defined names of an xlsx, read with openpyxl."""
    wb = openpyxl.load_workbook(path)
    formulas, constants = {}, {}
    for ws in wb.worksheets:
        for row in ws.iter_rows():
            for c in row:
                if c.value is None:
                    continue
                key = (ws.title, c.row, c.column)
                if isinstance(c.value, str) and c.value.startswith("="):
                    formulas[key] = c.value[1:]
                elif isinstance(c.value, str) and ExcelError.from_text(c.value):
                    constants[key] = ExcelError.from_text(c.value)
                elif isinstance(c.value, int) and not isinstance(c.value, bool):
                    constants[key] = float(c.value)
                else:
                    constants[key] = c.value
    names = {name: d.attr_text for name, d in wb.defined_names.items()}
    return formulas, constants, names


def best(fn, repeat: int):
    times, result = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - start)
    return min(times), result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--step", type=float, default=0.1)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--no-scalar", action="store_true", help="skip the slow scalar path")
    args = parser.parse_args()

    scene = load_scene("templates/sewing_machine.toml", step=args.step)
    with tempfile.TemporaryDirectory() as tmp:
        path = write_workbook(scene, tmp)
        t_read, (formulas, constants, names) = best(lambda: read_cells(path), 1)
    t_numpy, _ = best(lambda: evaluate(scene), max(args.repeat, 5))
    t_vec, fast = best(lambda: evaluate_cells(formulas, constants, names), args.repeat)

    print(f"machine: {platform.processor() or platform.machine()}, Python "
          f"{platform.python_version()}")
    print(f"sewing_machine, step {args.step} deg: {len(formulas)} formula cells, "
          f"{fast.groups.vector_groups} vector groups ({fast.groups.vector_cells} cells), "
          f"{fast.groups.scalar_cells} cells one by one")
    print(f"{'openpyxl read (apart)':32s} {t_read:9.3f} s")
    print(f"{'numpy closed form (peer)':32s} {t_numpy:9.4f} s   1.0x")
    print(f"{'vectorised evaluate_cells':32s} {t_vec:9.3f} s   {t_vec / t_numpy:7.1f}x numpy")
    for phase, seconds in fast.seconds.items():
        print(f"  {phase:30s} {seconds:9.4f} s   {seconds / t_numpy:7.1f}x numpy")
    if not args.no_scalar:
        t_scalar, slow = best(lambda: evaluate_cells(formulas, constants, names,
                                                     vectorize=False), 1)
        print(f"{'scalar cell by cell':32s} {t_scalar:9.3f} s   {t_scalar / t_numpy:7.1f}x "
              f"numpy, {t_scalar / t_vec:.1f}x vectorised")
        print(f"  {'vector phase vs scalar path':30s} "
              f"{t_scalar / fast.seconds['vector']:9.1f}x faster (Table/Checks columns)")


if __name__ == "__main__":
    main()
