"""The array formulas' fast operators (formula/arraysfast.py) give exactly what the
element-by-element path gives, on random arrays of every kind of value: numbers (zeros,
huge ones that overflow, negative zero), booleans, TRUE beside 1 and 1.0, texts, empty
cells and errors, in both dialects."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings, strategies as st

from workbook_gen.formula import arrays, arraysfast
from workbook_gen.formula.scalar import Evaluator
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

NUMBERS = st.one_of(st.sampled_from([0.0, -0.0, 1.0, 1, 2.5, 1e308, -1e308, 3]),
                    st.floats(-1e6, 1e6, allow_nan=False))
ANY = st.one_of(NUMBERS, st.booleans(), st.sampled_from(["ok", "OK", "x", "", "1", None,
                                                         ExcelError.DIV0, ExcelError.NA]))
OPS = sorted(arraysfast.ARITHMETIC) + sorted(arraysfast.COMPARISONS)


def _same(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return a == b and math.copysign(1, a) == math.copysign(1, b)
    return type(a) is type(b) and a == b


def _slow(op, left, right, apply):
    return arrays._broadcast(lambda a, b: apply(op, a, b), [left, right])


@settings(max_examples=300, deadline=None)
@given(op=st.sampled_from(OPS), items=st.lists(st.one_of(NUMBERS, st.booleans()), min_size=80,
                                                max_size=80),
       other=st.one_of(NUMBERS, st.booleans(), st.lists(NUMBERS, min_size=80, max_size=80)),
       dialect=st.sampled_from(["excel", "libreoffice"]), swap=st.booleans())
def test_numbers_and_booleans_as_element_by_element(op, items, other, dialect, swap):
    apply = Evaluator(None, dialect, None).apply
    left = Range.array_of([items[i:i + 8] for i in range(0, 80, 8)])
    right = (Range.array_of([other[i:i + 8] for i in range(0, 80, 8)])
             if isinstance(other, list) else other)
    if swap:
        left, right = right, left
    fast = arraysfast.operate(op, left, right, apply)
    if fast is None:  # (two arrays compared: element by element, by design)
        assert op in arraysfast.COMPARISONS
        return
    slow = _slow(op, left, right, apply)
    assert all(_same(a, b) for ra, rb in zip(fast.rows, slow.rows) for a, b in zip(ra, rb))


@settings(max_examples=200, deadline=None)
@given(op=st.sampled_from(OPS), items=st.lists(ANY, min_size=70, max_size=70), single=ANY,
       dialect=st.sampled_from(["excel", "libreoffice"]))
def test_any_values_against_one_value_as_element_by_element(op, items, single, dialect):
    apply = Evaluator(None, dialect, None).apply
    array = Range.array_of([items[i:i + 7] for i in range(0, 70, 7)])
    for left, right in ((array, single), (single, array)):
        fast = arraysfast.operate(op, left, right, apply)
        if fast is None:
            continue
        slow = _slow(op, left, right, apply)
        assert all(_same(a, b) for ra, rb in zip(fast.rows, slow.rows)
                   for a, b in zip(ra, rb)), (op, single)


def test_true_and_one_are_told_apart():
    apply = Evaluator(None, "excel", None).apply
    array = Range.array_of([[True, 1.0, 1, False, 0.0] * 20])
    fast = arraysfast.operate("=", array, 1.0, apply)
    assert list(fast.rows[0][:5]) == [False, True, True, False, False]


def test_division_by_zero_and_overflow_are_excel_errors():
    apply = Evaluator(None, "excel", None).apply
    array = Range.array_of([[1.0, 0.0, 1e308, -2.0] * 20])
    assert list(arraysfast.operate("/", 1.0, array, apply).rows[0][:4]) == [
        1.0, ExcelError.DIV0, 1e-308, -0.5]
    assert arraysfast.operate("*", array, 10.0, apply).rows[0][2] is ExcelError.NUM
    assert arraysfast.operate("&", array, "x", apply) is None
    assert arraysfast.operate("+", Range.array_of([[None] * 80]), 1.0, apply) is None


@pytest.mark.parametrize("rows", [3, 200])
def test_aggregate_over_the_ok_rows_without_array_entry(rows):
    """The Summary's formula (workbook/summary.py), short and long: the fast path and the
    element loop agree, and the largest ok value is found."""
    from workbook_gen.formula import DictResolver, evaluate, parse
    cells = {f"A{i}": float(i % 17) for i in range(1, rows + 1)}
    cells.update({f"B{i}": "ok" if i % 5 else "toggle" for i in range(1, rows + 1)})
    expected = max(v for i, v in enumerate(cells[f"A{i}"] for i in range(1, rows + 1))
                   if (i + 1) % 5)
    got = evaluate(parse(f'=_xlfn.AGGREGATE(14,6,A1:A{rows}/(B1:B{rows}="ok"),1)'),
                   DictResolver(cells, {}), dialect="excel")
    assert got == expected


@settings(max_examples=200, deadline=None)
@given(flags=st.lists(st.one_of(st.booleans(), ANY), min_size=60, max_size=60),
       then=st.one_of(ANY, st.lists(ANY, min_size=60, max_size=60)),
       other=st.one_of(ANY, st.lists(ANY, min_size=60, max_size=60)),
       wide=st.booleans())
def test_if_over_an_array_of_flags_as_element_by_element(flags, then, other, wide):
    """``IF(C2:C61="ok", F2:F61)`` (the batch summary's Statistics sheet) row by row: what
    the element loop gives, whatever the flags (booleans, or anything: then the loop
    itself), branches arrays of the flags' shape or single values."""
    cols = 6 if wide else 1

    def shaped(items):
        return Range.array_of([items[i:i + cols] for i in range(0, 60, cols)]) \
            if isinstance(items, list) else items
    cond, yes, no = shaped(flags), shaped(then), shaped(other)

    def pick(c, a, b):
        from workbook_gen.formula import values as xv
        flag = xv.to_bool(c)
        return flag if isinstance(flag, ExcelError) else (a if flag else b)
    fast = arrays._picked(cond, yes, no)
    slow = arrays._broadcast(pick, [cond, yes, no])
    if fast is None:
        assert not all(type(f) is bool for f in flags)
        return
    assert fast.shape == slow.shape
    assert all(_same(a, b) for ra, rb in zip(fast.rows, slow.rows) for a, b in zip(ra, rb))
