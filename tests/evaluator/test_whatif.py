"""evaluator.whatif: data tables recomputed as Excel computes them, against values
derived by hand from ECMA-376 Part 1, 18.3.1.40 (``f``: dt2D, dtr, r1, r2, del1) and
Microsoft's page on data tables
(https://support.microsoft.com/en-us/office/calculate-multiple-results-by-using-a-data-table-e95e2487-6ca6-4413-ad12-77542a5ea50b):
a one-variable table is its formula with the input cell holding each value in turn."""

from __future__ import annotations

from workbook_gen.evaluator import evaluate_cells
from workbook_gen.evaluator.whatif import DataTable
from workbook_gen.xlerror import ExcelError


def _table(ref, area, **attrs):
    row, col = ref
    return DataTable.of("S", row, col, area, {k: str(v) for k, v in attrs.items()})


def test_of_reads_the_f_elements_attributes():
    t = _table((5, 2), (6, 3), r1="$B$2", r2="B1", dt2D=1, dtr="true")
    assert (t.r1, t.r2, t.two_d, t.row_input, t.deleted) == ((2, 2), (1, 2), True, True, False)
    assert t.cells() == [("S", 5, 2), ("S", 5, 3), ("S", 6, 2), ("S", 6, 3)]
    assert t.text() == "TABLE(B2,B1)"
    assert _table((4, 3), (6, 3), r1="A1").text() == "TABLE(,A1)"       # column input
    assert _table((4, 3), (4, 5), r1="A1", dtr=1).text() == "TABLE(A1,)"  # row input
    assert _table((4, 3), (4, 3), r1="A1", del1=1).deleted


def test_plan_names_the_formula_and_the_heading_cells():
    # column input: formula above the area's column, value left of its row
    assert _table((4, 3), (6, 3), r1="A1").plan(5, 3) == ((3, 3), {(1, 1): (5, 2)})
    # row input: formula left of the row, value above the column
    assert _table((4, 3), (4, 5), r1="A1", dtr=1).plan(4, 5) == ((4, 2), {(1, 1): (3, 5)})
    # two-dimensional: formula at the corner; r1 takes the row above, r2 the column left
    two = _table((5, 2), (6, 3), r1="B2", r2="B1", dt2D=1)
    assert two.plan(6, 3) == ((4, 1), {(2, 2): (4, 3), (1, 2): (6, 1)})


def _evaluate(constants, formulas, tables):
    cached = {c: 0.0 for t in tables for c in t.cells()}  # the file's cached table values
    return evaluate_cells(formulas, {**constants, **cached}, {}, tables=tables)


def test_a_column_input_table():
    # A1 = 3 (input); C3 = A1^2 + 1; B4:B6 hold 1, 2, 10; C4:C6 = TABLE(,A1)
    constants = {("S", 1, 1): 3.0, ("S", 4, 2): 1.0, ("S", 5, 2): 2.0, ("S", 6, 2): 10.0}
    result = _evaluate(constants, {("S", 3, 3): "A1^2+1"}, [_table((4, 3), (6, 3), r1="A1")])
    assert [result.values[("S", r, 3)] for r in (4, 5, 6)] == [2.0, 5.0, 101.0]
    assert result.values[("S", 3, 3)] == 10.0  # the formula itself still sees A1 = 3


def test_a_row_input_table_through_a_chain():
    # A1 input; D1 = A1*2; B4 = D1+1; C3:E3 hold 1, 5, "x"; C4:E4 = TABLE(A1,)
    constants = {("S", 1, 1): 0.0, ("S", 3, 3): 1.0, ("S", 3, 4): 5.0, ("S", 3, 5): "x"}
    formulas = {("S", 1, 4): "A1*2", ("S", 4, 2): "D1+1"}
    result = _evaluate(constants, formulas, [_table((4, 3), (4, 5), r1="A1", dtr=1)])
    assert [result.values[("S", 4, c)] for c in (3, 4, 5)] == [3.0, 11.0, ExcelError.VALUE]


def test_a_two_dimensional_table():
    # B1 rate, B2 years, A4 = B1*B2; rows 5-6 vary B1 (column input r2), columns B-C vary
    # B2 (row input r1): cell = (row heading) * (column heading)
    constants = {("S", 1, 2): 0.5, ("S", 2, 2): 2.0, ("S", 4, 2): 10.0, ("S", 4, 3): 20.0,
                 ("S", 5, 1): 1.0, ("S", 6, 1): 3.0}
    table = _table((5, 2), (6, 3), r1="B2", r2="B1", dt2D=1)
    result = _evaluate(constants, {("S", 4, 1): "B1*B2"}, [table])
    assert {c: result.values[c] for c in table.cells()} == {
        ("S", 5, 2): 10.0, ("S", 5, 3): 20.0, ("S", 6, 2): 30.0, ("S", 6, 3): 60.0}


def test_a_deleted_input_cell_gives_ref_and_rand_is_not_checked():
    constants = {("S", 1, 1): 1.0, ("S", 4, 2): 2.0}
    deleted = _evaluate(constants, {("S", 3, 3): "A1*10"},
                        [_table((4, 3), (4, 3), r1="A1", del1=1)])
    assert deleted.values[("S", 4, 3)] == ExcelError.REF
    rand = _evaluate(constants, {("S", 3, 3): "A1*RAND()"}, [_table((4, 3), (4, 3), r1="A1")])
    assert "RAND" in rand.not_checked[("S", 4, 3)]
