"""evaluator.evaluation: what evaluate_cells gives back. The values are checked against
hand-derived arithmetic; the column views (numbers, column_values, clip) against the
same cells read one by one through the Mapping; CellMap against a dict."""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbook_gen.evaluator import evaluate_cells
from workbook_gen.evaluator.evaluation import CellMap, Evaluation, GroupStats
from workbook_gen.xlerror import ExcelError

ROWS = 8


@pytest.fixture(scope="module")
def result() -> Evaluation:
    constants = {("S", r, 1): float(r) for r in range(1, ROWS + 1)}
    constants[("S", 3, 1)] = "three"
    formulas = {("S", r, 2): f"A{r}*A{r}-1" for r in range(1, ROWS + 1)}
    formulas.update({("S", r, 3): f'IF(B{r}>20,"big",B{r}/(A{r}-5))' for r in range(1, ROWS + 1)})
    formulas[("S", 1, 4)] = "SUM(B:B)"
    return evaluate_cells(formulas, constants, {})


def _b(r):  # =A*A-1, Excel: text in arithmetic is #VALUE!
    return ExcelError.VALUE if r == 3 else float(r * r - 1)


def _c(r):
    b = _b(r)
    if isinstance(b, ExcelError):
        return b
    return "big" if b > 20 else (ExcelError.DIV0 if r == 5 else b / (r - 5))


def test_values_by_hand(result):
    for r in range(1, ROWS + 1):
        assert result.values[("S", r, 2)] == _b(r)
        assert result.values[("S", r, 3)] == _c(r)
    # SUM over a column with an error is the error (Excel's SUM propagates errors)
    assert result.values[("S", 1, 4)] == ExcelError.VALUE


def test_values_is_a_read_only_map_of_the_formula_cells(result):
    values = result.values
    assert isinstance(values, CellMap)
    assert len(values) == 2 * ROWS + 1 and set(values) == set(values.keyset)
    assert ("S", 1, 1) not in values  # a constant
    with pytest.raises(KeyError):
        values[("S", 1, 1)]
    with pytest.raises(TypeError):
        values[("S", 1, 2)] = 0.0  # type: ignore[index]


def test_numbers_are_the_float_cells_of_a_column(result):
    rows = np.arange(1, ROWS + 1)
    for col in (2, 3):
        is_num, vals, scales = result.numbers("S", col, rows)
        want = [result.values[("S", r, col)] for r in rows]
        assert is_num.tolist() == [type(v) is float for v in want]
        assert [v for v, k in zip(vals.tolist(), is_num) if k] == \
            [v for v in want if type(v) is float]
        assert scales.tolist() == [result.operands_scale[("S", r, col)] for r in rows]
    # the operand scale: the largest magnitude among the numbers a formula reads
    # (its literals and cells): A*A-1 reads A and 1; text and errors count 0
    assert [result.operands_scale[("S", r, 2)] for r in rows] == \
        [1.0 if r == 3 else max(r, 1.0) for r in rows]
    assert [result.operands_scale[("S", r, 3)] for r in rows] == \
        [max(20.0, r * r - 1.0) if r != 3 else 20.0 for r in rows]


def test_column_values_mix_constants_and_formulas(result):
    assert result.column_values("S", 1, 1, 4) == [1.0, 2.0, "three", 4.0]
    assert result.column_values("S", 3, 4, 6) == [_c(4), _c(5), _c(6)]
    assert result.column_values("S", 9, 1, 2) == [None, None]


def test_clip_cuts_whole_columns_to_the_used_rows(result):
    assert result.clip("s", 1, 2, 1_048_576, 2) == (1, 2, ROWS, 2)
    assert result.clip("S", 2, 2, 5, 3) == (2, 2, 5, 3)


def test_defaults_and_group_stats(result):
    empty = Evaluation({}, {})
    assert empty.cycles == [] and empty.not_checked == {} and empty.groups == GroupStats()
    groups = result.groups
    assert groups.vector_cells + groups.scalar_cells == len(result.values)
    assert math.isfinite(sum(result.seconds.values()))
