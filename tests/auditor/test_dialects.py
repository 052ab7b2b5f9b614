"""auditor/dialects.py: a cell LibreOffice computes by its own rules is LibreOffice's
difference, not the file's failure; any other value it computes apart from ours is a
mismatch.

The file is written with XlsxWriter holding Excel's values (=0^0 is #NUM! in Excel,
https://support.microsoft.com/en-us/office/power-function-d3f2908b-56f4-4c3f-895a-07fb519c362a
and the operator alike); LibreOffice recalculating it (one soffice run for the file) is
the reference for LibreOffice's side: it gives 1 for 0^0."""

from __future__ import annotations

import time
from types import SimpleNamespace

import pytest
import xlsxwriter

from workbook_gen.auditor.dialects import against_libreoffice, libreoffice_explains
from workbook_gen.auditor.inputs import read_inputs
from workbook_gen.auditor.recomputed import Recomputed
from workbook_gen.cellref import cell_name
from workbook_gen.engines.libreoffice import recalculated_values
from workbook_gen.evaluator import evaluate_cells
from workbook_gen.xlerror import ExcelError

B1, B2, B3 = ("S", 1, 2), ("S", 2, 2), ("S", 3, 2)
NO_AGGREGATES = SimpleNamespace(values={}, operands_scale={})


@pytest.fixture(scope="module")
def case(libreoffice, tmp_path_factory):
    path = tmp_path_factory.mktemp("dialects") / "dialects.xlsx"
    book = xlsxwriter.Workbook(str(path))
    s = book.add_worksheet("S")
    s.write_number("A1", 0)
    s.write_number("A2", 0)
    s.write_number("A3", 4)
    s.write_formula("B1", "=A1^A2", None, "#NUM!")  # Excel's value
    s.write_formula("B2", "=A3*2", None, 8)
    s.write_formula("B3", "=SQRT(A3)", None, 2)
    book.close()
    inputs = read_inputs(path)
    evaluation = evaluate_cells(inputs.formulas, inputs.constants, inputs.book.defined_names,
                                book=inputs.book_info())
    return inputs, Recomputed(evaluation, inputs.constants), recalculated_values(path)


def test_libreoffice_computes_its_own_power_of_zero(case):
    inputs, value_of, theirs = case
    assert inputs.cached[B1] == ExcelError.NUM and value_of(*B1) == ExcelError.NUM
    assert theirs["S"] == {"B1": 1.0, "B2": 8.0, "B3": 2.0}
    assert libreoffice_explains(inputs, B1, value_of, theirs["S"]["B1"])
    assert not libreoffice_explains(inputs, B1, value_of, 0.0)
    assert libreoffice_explains(inputs, B2, value_of, 8.0)
    assert not libreoffice_explains(inputs, B2, value_of, 9.0)
    assert not libreoffice_explains(inputs, ("S", 9, 9), value_of, 1.0)  # no formula: ""


def _against(case, theirs, skip=()):
    inputs, value_of, _ = case
    return against_libreoffice(inputs, theirs, NO_AGGREGATES, value_of, {}, set(skip),
                               time.perf_counter(), cell_name)


def test_the_difference_is_libreoffices_and_nothing_fails(case):
    result = _against(case, case[2])
    assert (result.engine, result.cells, result.mismatches) == ("libreoffice", 3, [])
    assert result.libreoffice_semantics == 1
    [d] = result.differences
    assert (d.cell, d.cached, d.recomputed) == ("S!B1", 1.0, ExcelError.NUM)


def test_another_value_from_libreoffice_is_a_mismatch(case):
    theirs = {"S": {**case[2]["S"], "B2": 9.0}}
    result = _against(case, theirs, skip=[B3])
    assert result.cells == 2
    assert [(m.cell, m.cached, m.recomputed) for m in result.mismatches] == [("S!B2", 9.0, 8)]
    aggregate = SimpleNamespace(values={B2: 9.0}, operands_scale={B2: 4.0})
    inputs, value_of, _ = case
    result = against_libreoffice(inputs, theirs, aggregate, value_of, {}, {B1, B3},
                                 time.perf_counter(), cell_name)
    # against what it makes of LibreOffice's own range it agrees; but not our value, and
    # no dialect explains it: no mismatch counted, no difference either
    assert (result.cells, result.mismatches, result.differences) == (1, [], [])
