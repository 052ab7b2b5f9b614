"""formula/functions/database.py: the D* functions against pandas filtering the same
table (labels in the first row; criteria rows OR-ed, conditions in one row AND-ed; a
number condition with an operator; plain text matching the values that begin with it),
on Microsoft's orchard example and random tables."""

from __future__ import annotations

import random

import numpy as np
import pandas as pd
import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)
TREES = ["Apple", "Pear", "Cherry", "Apricot", "Plum"]


def sheet(frame: pd.DataFrame, criteria: list[list]) -> dict:
    cells = {}
    for j, name in enumerate(frame.columns):
        cells[f"{'ABCD'[j]}1"] = name
        for i, v in enumerate(frame[name].tolist(), 2):
            cells[f"{'ABCD'[j]}{i}"] = v
    for i, row in enumerate(criteria, 1):
        for j, v in enumerate(row):
            if v is not None:
                cells[f"{'FGHI'[j]}{i}"] = v
    return cells


def ev(text: str, cells: dict):
    return evaluate(parse(text), DictResolver(cells))


def orchard(n: int) -> pd.DataFrame:
    return pd.DataFrame({"Tree": [RNG.choice(TREES) for _ in range(n)],
                         "Height": [float(RNG.randint(5, 25)) for _ in range(n)],
                         "Age": [float(RNG.randint(5, 25)) for _ in range(n)],
                         "Yield": [round(RNG.uniform(5, 15), 2) for _ in range(n)]})


REDUCE = {"DSUM": np.sum, "DAVERAGE": np.mean, "DMAX": np.max, "DMIN": np.min,
          "DPRODUCT": np.prod, "DCOUNT": len, "DCOUNTA": len,
          "DSTDEV": lambda s: np.std(s, ddof=1), "DSTDEVP": np.std,
          "DVAR": lambda s: np.var(s, ddof=1), "DVARP": np.var}


@pytest.mark.parametrize("seed", range(8))
def test_as_pandas(seed):
    frame = orchard(RNG.randint(4, 15))
    tree, low, high = RNG.choice(["Ap", "Pear", "Cherry"]), RNG.randint(5, 15), RNG.randint(15, 25)
    criteria = [["Tree", "Height", "Height"], [tree, f">={low}", f"<{high}"], ["Plum", None, None]]
    picked = frame[(frame.Tree.str.lower().str.startswith(tree.lower())
                    & (frame.Height >= low) & (frame.Height < high))
                   | (frame.Tree.str.lower().str.startswith("plum"))]
    cells = sheet(frame, criteria)
    n = len(frame) + 1
    for name, fn in REDUCE.items():
        got = ev(f'={name}(A1:D{n},"Yield",F1:H3)', cells)
        values = picked.Yield.to_numpy()
        if name in ("DSTDEV", "DVAR") and len(values) < 2:
            assert got == ExcelError.DIV0, name
        elif name in ("DAVERAGE", "DSTDEVP", "DVARP") and len(values) == 0:
            assert got == ExcelError.DIV0, name
        elif name in ("DMAX", "DMIN", "DPRODUCT", "DSUM") and len(values) == 0:
            assert got == 0, name
        else:
            assert got == pytest.approx(float(fn(values)), rel=1e-12), name
    assert ev(f"=DCOUNT(A1:D{n},,F1:H3)", cells) == len(picked)     # records, no field
    assert ev(f"=DSUM(A1:D{n},4,F1:H3)", cells) == pytest.approx(picked.Yield.sum())


def test_dget_one_record_or_an_error():
    frame = pd.DataFrame({"Tree": ["Apple", "Pear", "Apple"], "Height": [18.0, 12.0, 13.0],
                          "Age": [20.0, 12.0, 14.0], "Yield": [14.0, 10.0, 9.0]})
    cells = sheet(frame, [["Tree", "Height"], ["Apple", ">15"]])
    assert ev('=DGET(A1:D4,"Yield",F1:G2)', cells) == 14.0
    cells = sheet(frame, [["Tree"], ["Apple"]])
    assert ev('=DGET(A1:D4,"Yield",F1:F2)', cells) == ExcelError.NUM     # more than one
    cells = sheet(frame, [["Tree"], ["Fig"]])
    assert ev('=DGET(A1:D4,"Yield",F1:F2)', cells) == ExcelError.VALUE   # none
    assert ev('=DSUM(A1:D4,"Nope",F1:F2)', cells) == ExcelError.VALUE     # no such label
