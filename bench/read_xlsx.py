"""Time workbook_gen's xlsx reader against openpyxl on the same file, in one run.

The workbook has the shape of a generated Table sheet: ROWS rows x COLS formula
columns, each formula with its cached value (written by XlsxWriter).  Ours reads every
cell's value and formula text into what the audit takes (plain cells as columns: no Cell
object each; a second line times making them too); openpyxl is timed in its four modes,
read-only modes iterating every cell so that all the XML is parsed.  Each figure is the best
of REPEAT runs.

    python bench/read_xlsx.py [--rows 3600] [--cols 30] [--repeat 3] [--json FILE]

``--json FILE`` also writes the figures with the machine and the load (bench/benchinfo.py).
"""

from __future__ import annotations

import argparse
import math
import platform
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import openpyxl
import xlsxwriter

from workbook_gen.xlsx import read_workbook

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchinfo  # noqa: E402


def make_workbook(path: Path, rows: int, cols: int) -> None:
    wb = xlsxwriter.Workbook(str(path))
    ws = wb.add_worksheet("Table")
    ws.write_row(0, 0, ["theta [deg]"] + [f"q{k} [mm]" for k in range(1, cols + 1)])
    for r in range(1, rows + 1):
        theta = math.radians(r * 0.1)
        ws.write_number(r, 0, r * 0.1)
        for k in range(1, cols + 1):
            ws.write_formula(r, k, f"=SIN(RADIANS(A{r + 1}))*{k}+SQRT(ABS(A{r + 1}))", None,
                             math.sin(theta) * k + math.sqrt(r * 0.1))
    wb.close()


def ours(path: Path) -> int:
    return read_workbook(path).n_cells


def ours_cells(path: Path) -> int:
    """Reading, then a Cell object for every cell."""
    return sum(len(s.cells) for s in read_workbook(path).sheets)


def openpyxl_mode(data_only: bool, read_only: bool) -> Callable[[Path], int]:
    def run(path: Path) -> int:
        wb = openpyxl.load_workbook(path, data_only=data_only, read_only=read_only)
        n = sum(1 for ws in wb.worksheets for row in ws.iter_rows() for c in row
                if c.value is not None)
        wb.close()
        return n
    return run


def best_time(fn: Callable[[Path], int], path: Path, repeat: int) -> tuple[float, int]:
    best, n = math.inf, 0
    for _ in range(repeat):
        start = time.perf_counter()
        n = fn(path)
        best = min(best, time.perf_counter() - start)
    return best, n


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", type=int, default=3600)
    ap.add_argument("--cols", type=int, default=30)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--json", metavar="FILE", help="also write the figures, the machine and the "
                    "load to FILE")
    args = ap.parse_args()
    benchinfo.check_writable(args.json)
    record = benchinfo.Record()
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "bench.xlsx"
        make_workbook(path, args.rows, args.cols)
        size = path.stat().st_size / 1e6
        print(f"{args.rows} rows x {args.cols} formula columns, {size:.1f} MB; "
              f"Python {platform.python_version()}, openpyxl {openpyxl.__version__}, "
              f"{platform.machine()}; best of {args.repeat}")
        base, n_ours = best_time(ours, path, args.repeat)
        print(f"{'workbook_gen read_workbook':48s} {base:7.3f} s  {n_ours} cells   1.00x")
        with_cells, _ = best_time(ours_cells, path, args.repeat)
        print(f"{'workbook_gen read_workbook, Cell objects':48s} {with_cells:7.3f} s"
              f"{'':16s}{with_cells / base:5.2f}x")
        times = {}
        for data_only in (False, True):
            for read_only in (False, True):
                name = f"openpyxl data_only={data_only} read_only={read_only}"
                t, n = best_time(openpyxl_mode(data_only, read_only), path, args.repeat)
                times[data_only, read_only] = t
                print(f"{name:48s} {t:7.3f} s  {n} cells  {t / base:5.2f}x")
        # the auditor needs formula text and cached values: openpyxl reads the file twice
        both = times[False, True] + times[True, True]
        print(f"{'openpyxl formulas + values (2 read_only loads)':48s} {both:7.3f} s"
              f"{'':16s}{both / base:5.2f}x")
    if args.json:
        record.write(args.json, {
            "rows": args.rows, "cols": args.cols, "repeat": args.repeat, "cells": n_ours,
            "megabytes": size, "ours": base, "ours_cell_objects": with_cells,
            "openpyxl": [{"data_only": d, "read_only": r, "seconds": t}
                         for (d, r), t in times.items()],
            "openpyxl_formulas_and_values": both})


if __name__ == "__main__":
    main()
