"""evaluator.taint: which rows of a filled-down block read a not-checked cell.

Reference: the rows found by brute force, each row's rectangle enumerated cell by cell
(row1 + i*rel1 .. row2 + i*rel2) and intersected with the tainted cells in plain Python.
"""

from __future__ import annotations

import itertools

from workbook_gen.evaluator.taint import Shape, Taint

ORIGIN = ("S", 4, 2)


def _brute(shape: Shape, tainted: set, n: int) -> set[int]:
    rows = set()
    for i in range(n):
        r1 = shape.row1 + (i if shape.rel1 else 0)
        r2 = shape.row2 + (i if shape.rel2 else 0)
        r1, r2 = min(r1, r2), max(r1, r2)  # B7:B$5 filled down is B5:B7
        for r, c in itertools.product(range(r1, r2 + 1), range(shape.col1, shape.col2 + 1)):
            if (shape.sheet, r, c) in tainted:
                rows.add(i)
    return rows


def _hit_rows(taint: Taint, shape: Shape, n: int) -> set[int]:
    out = set()
    for lo, hi, _ in taint.hits(shape, n):
        out |= set(range(lo, hi + 1))
    return out


def test_hits_match_brute_force_over_many_shapes():
    taint = Taint()
    taint.add("S", 2, 5, 7, ORIGIN)    # B5:B7
    taint.add("S", 4, 12, 12, ORIGIN)  # D12
    tainted = {("S", r, 2) for r in range(5, 8)} | {("S", 12, 4)}
    n = 15
    for row1, row2 in itertools.combinations_with_replacement(range(1, 16), 2):
        for rel1, rel2 in itertools.product((False, True), repeat=2):
            for col1, col2 in ((1, 1), (2, 2), (1, 4), (3, 4), (5, 6)):
                shape = Shape("S", row1, col1, row2, col2, rel1, rel2)
                assert _hit_rows(taint, shape, n) == _brute(shape, tainted, n), shape


def test_sum_from_an_absolute_top_is_tainted_from_the_source_row_on():
    # SUM($A$1:A1) filled down rows 1..10 with A6 not checked: rows 6..10 (offsets 5..9)
    taint = Taint()
    taint.add("S", 1, 6, 6, ORIGIN)
    assert taint.hits(Shape("S", 1, 1, 1, 1, False, True), 10) == [(5, 9, ORIGIN)]
    # another sheet or column is not hit
    assert taint.hits(Shape("T", 1, 1, 1, 1, False, True), 10) == []
    assert taint.hits(Shape("S", 1, 2, 1, 2, False, True), 10) == []


def test_mark_taints_without_a_cached_value_and_holds_it_otherwise():
    put = {}
    taint = Taint(cached={("S", 3, 1): 2.5}, put=lambda cell, v: put.__setitem__(cell, v))
    taint.mark(("S", 3, 1), ORIGIN)   # cached: its readers read 2.5, no taint
    taint.mark(("S", 4, 1), ORIGIN)   # not cached: taints
    assert not put and taint.pending == [(("S", 3, 1), 2.5)]
    assert dict(taint.intervals) == {("S", 1): [(4, 4, ORIGIN)]}
    taint.flush()
    assert put == {("S", 3, 1): 2.5} and taint.pending == []


def test_without_put_the_cache_is_ignored_and_an_empty_taint_is_false():
    taint = Taint(cached={("S", 3, 1): 2.5})
    assert not taint
    taint.mark(("S", 3, 1), ORIGIN)
    assert taint and taint.intervals[("S", 1)] == [(3, 3, ORIGIN)]


def test_a_range_whose_ends_cross_when_filled_down_is_tainted_past_the_crossing():
    # C_r = SUM(B_r:B$3) (Excel reads B3:B_r below row 3) and D_r = SUM(B$3:B_r) both read
    # B8, a formula that does not parse: rows 8..10 of both are not checked. (Found by
    # the brute force above: the rows past the crossing were missed.)
    from workbook_gen.evaluator import evaluate_cells
    formulas, constants = {}, {}
    for r in range(1, 11):
        constants[("S", r, 1)] = float(r)
        formulas[("S", r, 2)] = f"A{r}*2"
        formulas[("S", r, 3)] = f"SUM(B{r}:B$3)"
        formulas[("S", r, 4)] = f"SUM(B$3:B{r})"
    formulas[("S", 8, 2)] = "1+("
    result = evaluate_cells(formulas, constants, {})
    for col in (3, 4):
        tainted = [r for r in range(1, 11) if ("S", r, col) in result.not_checked]
        assert tainted == [8, 9, 10], col
