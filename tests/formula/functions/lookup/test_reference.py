"""formula/functions/reference.py: ADDRESS in its four absolute forms and R1C1 against
openpyxl's column letters, ROW/COLUMN/ROWS/COLUMNS against openpyxl's range parsing,
OFFSET and INDIRECT reading the cells they name, TRANSPOSE as numpy's, AREAS."""

from __future__ import annotations

import random

import numpy as np
import pytest
from openpyxl.utils import get_column_letter, range_boundaries

from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula.arrays import evaluate_array

RNG = random.Random(23)
DATA = {f"{get_column_letter(c)}{r}": float(100 * r + c) for r in range(1, 30) for c in range(1, 30)}


def ev(text: str):
    value = evaluate_array(parse(text), DictResolver(DATA), "excel", ("Sheet1", 1, 1))
    if hasattr(value, "rows"):
        rows = [list(r) for r in value.rows]
        return rows[0][0] if len(rows) == 1 and len(rows[0]) == 1 else rows
    return value


def test_address_forms():
    for _ in range(200):
        r, c = RNG.randint(1, 1048576), RNG.randint(1, 16384)
        letters = get_column_letter(c)
        assert ev(f"=ADDRESS({r},{c})") == f"${letters}${r}"
        assert ev(f"=ADDRESS({r},{c},2)") == f"{letters}${r}"
        assert ev(f"=ADDRESS({r},{c},3)") == f"${letters}{r}"
        assert ev(f"=ADDRESS({r},{c},4)") == f"{letters}{r}"
        assert ev(f"=ADDRESS({r},{c},1,FALSE)") == f"R{r}C{c}"
        assert ev(f"=ADDRESS({r},{c},4,FALSE)") == f"R[{r}]C[{c}]"
    assert ev('=ADDRESS(2,3,1,TRUE,"My Sheet")') == "'My Sheet'!$C$2"


def test_row_column_rows_columns():
    for _ in range(100):
        c1, c2 = sorted(RNG.sample(range(1, 200), 2))
        r1, r2 = sorted(RNG.sample(range(1, 5000), 2))
        ref = f"{get_column_letter(c1)}{r1}:{get_column_letter(c2)}{r2}"
        min_col, min_row, max_col, max_row = range_boundaries(ref)
        assert ev(f"=ROWS({ref})") == max_row - min_row + 1
        assert ev(f"=COLUMNS({ref})") == max_col - min_col + 1
        assert ev(f"=ROW({ref.split(':')[0]})") == min_row
        assert ev(f"=COLUMN({ref.split(':')[0]})") == min_col


def test_offset_and_indirect_read_what_they_name():
    for _ in range(100):
        r, c = RNG.randint(1, 10), RNG.randint(1, 10)
        dr, dc, h, w = RNG.randint(0, 5), RNG.randint(0, 5), RNG.randint(1, 4), RNG.randint(1, 4)
        start = f"{get_column_letter(c)}{r}"
        want = sum(DATA[f"{get_column_letter(c + dc + j)}{r + dr + i}"]
                   for i in range(h) for j in range(w))
        assert ev(f"=SUM(OFFSET({start},{dr},{dc},{h},{w}))") == want
        name = f"{get_column_letter(c + dc)}{r + dr}"
        assert ev(f'=INDIRECT("{name}")') == DATA[name]
        assert ev(f'=INDIRECT("R{r + dr}C{c + dc}",FALSE)') == DATA[name]


def test_transpose_and_areas():
    a = np.arange(12.0).reshape(3, 4)
    text = "{" + ";".join(",".join(map(repr, r)) for r in a.tolist()) + "}"
    assert ev(f"=TRANSPOSE({text})") == a.T.tolist()
    assert ev("=AREAS((A1:B2,C3,D4:E9))") == 3 and ev("=AREAS(A1:C3)") == 1
