"""Time pycel on one workbook; runs inside pycel's own virtual environment.

pycel needs openpyxl < 3.1, so bench/audit.py runs this file with the interpreter of
bench/.venv-pycel. It loads the workbook with ``pycel.ExcelCompiler``, evaluates every
formula cell of the SHEETS (default Table and Checks), and prints one JSON object:
``{"load": s, "evaluate": s, "cells": n, "errors": n, "disagree": n}``. A cell whose
evaluation raises counts as an error (it is still timed); ``disagree`` counts values that
differ from the workbook's cached value (relative 1e-9; checked after timing).

    bench/.venv-pycel/bin/python bench/pycel_runner.py FILE [SHEET ...]
"""

from __future__ import annotations

import json
import math
import sys
import time

import openpyxl
from openpyxl.utils import get_column_letter
from pycel import ExcelCompiler


def formula_cells(path: str, sheets: list[str]) -> list[str]:
    """Addresses (``Sheet!B2``) of the formula cells of ``sheets``, in row order."""
    wb = openpyxl.load_workbook(path)
    cells = []
    for name in sheets:
        for row in wb[name].iter_rows():
            for c in row:
                if isinstance(c.value, str) and c.value.startswith("="):
                    cells.append(f"{name}!{get_column_letter(c.column)}{c.row}")
    return cells


def _same(got: object, cached: object) -> bool:
    if isinstance(cached, (int, float)) and isinstance(got, (int, float)):
        return math.isclose(got, cached, rel_tol=1e-9, abs_tol=1e-9)
    return got == cached


def main() -> None:
    path, sheets = sys.argv[1], sys.argv[2:] or ["Table", "Checks"]
    cells = formula_cells(path, sheets)
    start = time.perf_counter()
    excel = ExcelCompiler(filename=path)
    loaded = time.perf_counter()
    errors, got = 0, {}
    for address in cells:
        try:
            got[address] = excel.evaluate(address)
        except Exception:  # noqa: BLE001 - a failing cell is counted, not fatal
            errors += 1
    done = time.perf_counter()
    cached = openpyxl.load_workbook(path, data_only=True)
    disagree = 0
    for address, value in got.items():
        sheet, ref = address.split("!")
        disagree += not _same(value, cached[sheet][ref].value)
    print(json.dumps({"load": loaded - start, "evaluate": done - loaded,
                      "cells": len(cells), "errors": errors, "disagree": disagree}))


if __name__ == "__main__":
    main()
