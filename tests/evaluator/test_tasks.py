"""evaluator.tasks: what a run of formulas reads and how it is evaluated. References:
the rectangles written out by hand from each formula's text (A1 references,
https://support.microsoft.com/en-us/office/create-or-change-a-cell-reference-c7b8b95d-c594-4488-947e-c835903cebaa:
a $ row stays, a relative row moves with the row), the documented behaviour of ROWS
(reads no cell's value) and INDIRECT with constant text, and a run evaluated as a block
against the same cells evaluated one by one with the scalar evaluator."""

from __future__ import annotations

from workbook_gen.evaluator.store import Names, SheetResolver, Store
from workbook_gen.evaluator.taint import Shape
from workbook_gen.evaluator.tasks import (Task, cell_scale, evaluate_task, reads_only_above,
                                          rects, shapes_of, singles)
from workbook_gen.evaluator.vector import compile_block
from workbook_gen.formula import parse, render
from workbook_gen.formula.scalar import evaluate
from workbook_gen.xlerror import ExcelError

STORE = Store(["S", "T", "U"], order=["S", "T", "U"])
NAMES = Names({"Rate": "T!$B$2", "Both": "Rate+S!$C$1", "Broken": "1+("})


def _shapes(text, first=2, last=5):
    return shapes_of(Task("S", 4, first, last, parse(text)), STORE, NAMES)


def test_shapes_follow_the_dollars_names_and_3d_references():
    shapes, bad = _shapes("A2+SUM($B$1:B2)+Rate")
    assert sorted(shapes) == sorted([
        Shape("S", 2, 1, 2, 1, True, True),      # A2
        Shape("S", 1, 2, 2, 2, False, True),     # $B$1:B2
        Shape("T", 2, 2, 2, 2, False, False)])   # Rate -> T!$B$2
    assert bad == []
    shapes, _ = _shapes("Both*2")  # a name reading a name
    assert sorted(shapes) == [Shape("S", 1, 3, 1, 3, False, False),
                              Shape("T", 2, 2, 2, 2, False, False)]
    shapes, _ = _shapes("SUM(S:U!A1)")
    assert [s.sheet for s in shapes] == ["S", "T", "U"]
    assert _shapes("Broken+1")[1] == ["BROKEN"]
    # ROWS reads no cell; INDIRECT of constant text reads the cell it names
    assert _shapes("ROWS(A1:A9)")[0] == []
    assert _shapes('INDIRECT("C7")')[0] == [Shape("S", 7, 3, 7, 3, False, False)]
    # a range written bottom-up is read top-down
    assert _shapes("SUM(B5:A$1)")[0] == [Shape("S", 1, 1, 5, 2, False, True)]


def test_rects_cover_every_row_of_the_run():
    task = Task("S", 4, 2, 5, parse("A2+SUM($B$1:B2)"))
    shaped = shapes_of(task, STORE, NAMES)
    assert sorted(rects(task, shaped)) == [("S", 1, 2, 5, 2), ("S", 2, 1, 5, 1)]


def test_reads_only_above_and_cells_and_singles():
    chain = Task("S", 4, 2, 5, parse("D1+1"))
    # D2 reads D1, D3 reads D2...: each row reads its own column above it (a chain)
    assert reads_only_above(chain, shapes_of(chain, STORE, NAMES)[0])
    below = Task("S", 4, 2, 5, parse("D9+1"))
    assert not reads_only_above(below, shapes_of(below, STORE, NAMES)[0])
    inside = Task("S", 4, 2, 5, parse("SUM($D$1:D2)"))  # D2 reads D1:D2, itself
    assert not reads_only_above(inside, shapes_of(inside, STORE, NAMES)[0])
    assert chain.cells() == [("S", r, 4) for r in range(2, 6)]
    array = Task("S", 1, 1, 1, parse("A1"), area=(2, 3))
    assert len(array.cells()) == 6
    assert [render(t.node) for t in singles(chain)] == ["D1+1", "D2+1", "D3+1", "D4+1"]


def _store():
    store = Store(["S"])
    store.put_constants({("S", r, 1): float(r) for r in range(1, 8)})
    store.put("S", 3, 1, "x")
    store.put("S", 1, 3, 100.0)
    return store


def test_a_run_evaluated_as_a_block_equals_cell_by_cell():
    text = "IF(A2>4,A2*$C$1,A2/(A2-2))"
    node = parse(text)
    block_store, cell_store = _store(), _store()
    names = Names({})
    task = Task("S", 2, 2, 7, node, block=compile_block(node, "S", 2, 2, 7))
    evaluate_task(task, block_store, names)
    for single in singles(Task("S", 2, 2, 7, node)):
        evaluate_task(single, cell_store, names)
    want = {2: ExcelError.DIV0, 3: ExcelError.VALUE, 4: 2.0, 5: 500.0, 6: 600.0, 7: 700.0}
    for r in range(2, 8):
        assert block_store.get("S", r, 2) == cell_store.get("S", r, 2) == want[r], r
        assert block_store.scale("S", r, 2) == cell_store.scale("S", r, 2)


def test_a_chain_is_evaluated_row_after_row():
    store = _store()
    store.put("S", 1, 2, 1.0)
    evaluate_task(Task("S", 2, 2, 6, parse("B1*2"), sequential=True), store, Names({}))
    assert [store.get("S", r, 2) for r in range(1, 7)] == [1.0, 2.0, 4.0, 8.0, 16.0, 32.0]


def test_cell_scale_is_the_largest_number_read():
    store = _store()
    resolver = SheetResolver(store, Names({"Big": "S!$C$1"}), "S")
    assert cell_scale(parse("A2*3"), resolver) == 3.0
    assert cell_scale(parse("SUM(A1:A7)-0.5"), resolver) == 7.0
    assert cell_scale(parse("Big+A3"), resolver) == 100.0  # text counts 0
    assert evaluate(parse("SUM(A1:A7)"), resolver) == 1 + 2 + 4 + 5 + 6 + 7.0


def test_a_range_whose_first_row_passes_its_fixed_last_row():
    # B_r = SUM(C_r:C$3): below row 3 Excel reads C3:C_r, so the run reads down to C10
    task = Task("S", 2, 1, 10, parse("SUM(C1:C$3)"))
    assert rects(task, shapes_of(task, STORE, NAMES)) == [("S", 1, 3, 10, 3)]
    # end to end: C4:C10 (another run than C1:C3) must be computed before B reads them
    from workbook_gen.evaluator import evaluate_cells
    constants = {("S", r, 1): float(r) for r in range(1, 11)}
    formulas = {}
    for r in range(1, 11):
        formulas[("S", r, 2)] = f"SUM(C{r}:C$3)"
        formulas[("S", r, 3)] = f"A{r}*2" if r <= 3 else f"A{r}*3"
    c = {r: 2 * r if r <= 3 else 3 * r for r in range(1, 11)}
    want = [float(sum(c[k] for k in range(min(r, 3), max(r, 3) + 1))) for r in range(1, 11)]
    for vectorize in (True, False):
        result = evaluate_cells(formulas, constants, {}, vectorize=vectorize)
        assert [result.values[("S", r, 2)] for r in range(1, 11)] == want, vectorize
