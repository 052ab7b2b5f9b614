"""evaluator.store: cell values held column by column. Reference: a plain dict
{(sheet, row, col): value} fed the same writes (hypothesis draws them), read back
cell by cell; Excel's rules for what a cell holds (no -0, ECMA-376 Part 1 18.3.1.4:
a cell holds a number, text, a boolean or an error); defined names resolved as Excel
resolves them (a sheet-scoped name wins on its own sheet:
https://support.microsoft.com/en-us/office/define-and-use-names-in-formulas-4d0f13ac-53b7-422e-afd2-abd7ff379c64)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings, strategies as st

from workbook_gen.evaluator.store import (BIG_ROWS, Names, NumBlock, ObjBlock, SheetResolver,
                                          Store, error_codes, to_items, value_scale)
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

VALUES = st.one_of(st.floats(-1e6, 1e6, allow_nan=False), st.sampled_from(
    [ExcelError.NA, ExcelError.DIV0, "text", "", True, False, None, 0.0, 1.0, -2.5]))
CELLS = st.tuples(st.sampled_from(["S", "T"]), st.integers(1, 12), st.integers(1, 3))
WRITES = st.lists(st.one_of(
    st.tuples(st.just("put"), CELLS, VALUES),
    st.tuples(st.just("constants"), st.dictionaries(CELLS, VALUES, max_size=8)),
    st.tuples(st.just("block"), CELLS, st.lists(VALUES, min_size=1, max_size=6)),
    st.tuples(st.just("numblock"), CELLS, st.lists(st.floats(-9, 9), min_size=1, max_size=6)),
), max_size=12)


def _apply(writes):
    store, model = Store(["S", "T"]), {}
    for w in writes:
        if w[0] == "put":
            store.put(*w[1], w[2])
            model[w[1]] = w[2]
        elif w[0] == "constants":
            store.put_constants(w[1])
            model.update(w[1])
        else:
            (sheet, row, col), values = w[1], w[2]
            if w[0] == "numblock":  # NaN in a NumBlock is an error row (#NUM!)
                err = np.array([ExcelError.NUM.code if math.isnan(v) else 0 for v in values],
                               np.uint8)
                block = NumBlock(np.array(values), err)
                values = [ExcelError.NUM if math.isnan(v) else v for v in values]
            else:
                block = ObjBlock(list(values))
            store.put_block(sheet, col, row, block, np.zeros(len(values)))
            for i, v in enumerate(values):
                model[(sheet, row + i, col)] = v
    return store, model


def _norm(v):
    """What a cell holds of a written value: numbers as floats, ints too."""
    if isinstance(v, int) and not isinstance(v, bool):
        return float(v)
    return v


def _same(a, b):
    return type(a) is type(b) and (a == b or (isinstance(a, float) and a == b))


@settings(max_examples=150, deadline=None)
@given(WRITES)
def test_reads_give_what_was_written(writes):
    store, model = _apply(writes)
    for sheet in ("S", "T"):
        for col in (1, 2, 3):
            want = [_norm(model.get((sheet, r, col))) for r in range(1, 20)]
            got = [store.get(sheet, r, col) for r in range(1, 20)]
            assert all(map(_same, got, want)), (got, want)
            assert all(map(_same, store.column_values(sheet, col, 1, 19), want))
            block = store.block(sheet, col, 1, 19)
            items = to_items(block) if isinstance(block, NumBlock) else block.items
            assert all(map(_same, items, want))
            # numbers(): a number exactly where the cell holds a float
            if (sheet, col) in store.cols:
                rows = np.arange(1, min(13, len(store.cols[(sheet, col)].val)))
                is_num, vals, _ = store.numbers(sheet, col, rows)
                assert is_num.tolist() == [type(want[r - 1]) is float for r in rows]
                assert [v for v, k in zip(vals.tolist(), is_num) if k] == \
                    [want[r - 1] for r in rows if type(want[r - 1]) is float]
    rect = store.rect("S", 2, 1, 6, 3)
    assert [list(r) for r in rect.rows] == [[_norm(model.get(("S", r, c))) for c in (1, 2, 3)]
                                            for r in range(2, 7)]
    want_scale = max((abs(v) for (s, r, c), v in model.items() if s == "S" and 2 <= r <= 6
                      and type(_norm(v)) is float), default=0.0)
    assert store.rect_scale("S", 2, 1, 6, 3) == want_scale


def test_a_cell_never_holds_negative_zero():
    store = Store(["S"])
    store.put_constants({("S", 1, 1): -0.0, ("S", 2, 1): 3.0})
    assert math.copysign(1.0, store.get("S", 1, 1)) == 1.0


def test_huge_ranges_are_cut_to_the_used_area_and_sheets_found_in_any_case():
    store = Store(["Data", "Other"], order=["Other", "Data"])
    store.put("Data", 7, 2, 1.0)
    assert store.clip("Data", 1, 1, 1_048_576, 1) == (1, 1, 7, 1)      # A:A
    assert store.clip("Data", 1, 1, 1, 16_384) == (1, 1, 1, 2)          # 1:1
    assert store.clip("Data", 1, 1, BIG_ROWS + 1, 1) == (1, 1, 7, 1)   # 65,536 rows: cut
    assert store.clip("Data", 1, 1, BIG_ROWS, 1) == (1, 1, BIG_ROWS, 1)  # one fewer: kept
    assert store.sheet("DATA") == "Data" and store.sheet("nope") == "nope"
    assert store.sheets_between("data", "OTHER") == ["Other", "Data"]
    assert store.sheets_between("data", "x") is None


def test_formula_texts_array_formulas_and_subtotals():
    store = Store(["S"])
    store.formula_texts = {("S", 1, 1): "SUBTOTAL(9,B1:B4)", ("S", 2, 1): "1+1"}
    store.array_formulas = {("S", 5, 1): ("_xlfn.AGGREGATE(9,0,B1:B4)", (6, 2))}
    store.unparsed = {("S", 9, 9): "1+("}
    assert store.formula_text("S", 2, 1) == ("1+1", False)
    assert store.formula_text("S", 6, 2) == ("_xlfn.AGGREGATE(9,0,B1:B4)", True)
    assert store.formula_text("S", 7, 1) is None
    assert store.has_formula("S", 9, 9) and store.has_formula("S", 5, 2)
    assert not store.has_formula("S", 3, 1)
    assert sorted(store.subtotal_cells("S")) == [(1, 1), (5, 1), (5, 2), (6, 1), (6, 2)]


def test_helpers():
    assert error_codes([1.0, ExcelError.NA, "x", [1]]).tolist() == [0, ExcelError.NA.code, 0, 0]
    assert to_items(NumBlock(np.array([1.0, np.nan]), np.array([0, 7], np.uint8), True)) == \
        [True, ExcelError.from_code(7)]
    assert value_scale(Range(((1.0, -4.0), ("x", True)))) == 4.0
    assert value_scale(math.inf) == 0.0 and value_scale(True) == 0.0


def test_names_a_sheet_scoped_name_wins_on_its_sheet():
    names = Names({"Rate": "Data!$A$1", "Bad": "1+("}, {"Calc": {"rate": "Data!$A$2"}})
    store = Store(["Data", "Calc"])
    store.put_constants({("Data", 1, 1): 0.25, ("Data", 2, 1): 0.5})
    value = lambda home, name, sheet: SheetResolver(store, names, home).name(name, sheet)
    assert value("Data", "RATE", None).rows == ((0.25,),)
    assert value("Calc", "Rate", None).rows == ((0.5,),)
    assert value("Data", "rate", "Calc").rows == ((0.5,),)  # Calc!rate
    assert SheetResolver(store, names, "Data").name("nothing", None) == ExcelError.NAME
    assert names.error("bad") == "BAD" and names.error("rate", home="Calc") is None
    assert names.node("Rate", "[1]Book") is None  # another workbook's name
