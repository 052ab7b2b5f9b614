"""auditor/recomputed.py: the audit's value of every cell (recomputed formula, the file's
constant, None for an empty cell) and the scalar evaluator's view of it. The workbook is
planted with XlsxWriter (tests/planted.py: B3 =A1+A2 cached 99, recomputed 5); expected
values are derived by hand, SUM skipping text as Excel documents
(https://support.microsoft.com/en-us/office/sum-function-043e1c7d-7726-4e80-8f32-07b23e057f89:
"text values ... are ignored" in a reference)."""

from __future__ import annotations

import pytest

from workbook_gen.auditor.inputs import read_inputs
from workbook_gen.auditor.recomputed import Recomputed, RecomputedResolver
from workbook_gen.evaluator import evaluate_cells
from workbook_gen.formula import parse
from workbook_gen.formula.scalar import evaluate as evaluate_scalar
from workbook_gen.xlerror import ExcelError

from planted import planted_book


@pytest.fixture(scope="module")
def recomputed(tmp_path_factory):
    inputs = read_inputs(planted_book(tmp_path_factory.mktemp("recomputed") / "p.xlsx"))
    evaluation = evaluate_cells(inputs.formulas, inputs.constants, inputs.book.defined_names,
                                book=inputs.book_info(), arrays=inputs.arrays)
    return inputs, Recomputed(evaluation, inputs.constants)


def test_formulas_recomputed_constants_as_stored(recomputed):
    inputs, value_of = recomputed
    assert value_of("S", 3, 2) == 5          # =A1+A2, whatever the file cached (99)
    assert inputs.cached[("S", 3, 2)] == 99
    assert value_of("S", 1, 2) == 6 and value_of("S", 1, 4) == 20 and value_of("T", 1, 2) == 7
    assert value_of("S", 1, 1) == 2 and value_of("S", 3, 1) == "txt"
    assert value_of("S", 50, 50) is None
    assert value_of.clip("S", 1, 1, 1048576, 1) == (1, 1, 3, 1)  # A:A to the used rows


def _resolver(recomputed, sheet="S"):
    inputs, value_of = recomputed
    return RecomputedResolver(value_of, {"k": "S!$A$1", "Bad": "S!$A$1+("}, sheet,
                              inputs.is_formula)


def test_the_scalar_evaluator_reads_the_recomputed_workbook(recomputed):
    resolver = _resolver(recomputed)
    assert evaluate_scalar(parse("SUM(A:A)*K"), resolver) == 10   # (2 + 3) * 2, text skipped
    assert evaluate_scalar(parse("B3+T!B1"), resolver) == 12      # 5 + 7
    assert evaluate_scalar(parse("B1"), _resolver(recomputed, "T")) == 7  # T!B1 itself
    assert resolver.range("S", 1, 2, 3, 2) == [[6], [9], [5]]
    assert resolver.has_formula("S", 1, 2) and not resolver.has_formula("S", 1, 1)
    assert resolver.name("nothere", None) == ExcelError.NAME
    assert resolver.name("bad", None) == ExcelError.NAME  # does not parse
    assert resolver.name("k", None) == 2
