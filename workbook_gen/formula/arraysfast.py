"""Element-wise operators of array formulas at C speed, for the common cases: the same
values :func:`arrays._broadcast` gives element by element with the scalar operator.

- ``+ - * /`` between arrays (or an array and a single value) of numbers and booleans:
  numpy, with Excel's results where they are not numbers (``/`` by 0 is #DIV/0!, an
  overflow #NUM!, no negative zero); a boolean is its number, as in Excel's arithmetic;
- a comparison of an array with a single value: numpy for numbers with a number, else
  the scalar comparison once per distinct element (a status column compared with "ok"
  has two or three distinct texts).

Anything else (text in arithmetic, empty cells, errors, ``&``, ``^``, shapes that
broadcast otherwise) returns None, and the caller goes element by element.
"""

from __future__ import annotations

import numpy as np

from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError

ARITHMETIC = {"+": np.add, "-": np.subtract, "*": np.multiply, "/": np.divide}
NUMERIC_COMPARE = {"=": np.equal, "<>": np.not_equal, "<": np.less, ">": np.greater,
                   "<=": np.less_equal, ">=": np.greater_equal}
COMPARISONS = frozenset(NUMERIC_COMPARE)
MIN_ELEMENTS = 64  # below this the element loop is as fast


def _numbers(items: list) -> np.ndarray | None:
    """The items as floats if every one is a float, int or bool (not an empty cell)."""
    kinds = set(map(type, items))
    if not kinds <= {float, int, bool}:
        return None
    return np.array(items, dtype=float)


def _shaped(flat: list, shape: tuple[int, int]) -> Range:
    """The array of ``flat`` in rows of ``shape[1]`` (grouped by zip, at C speed)."""
    return Range(tuple(zip(*[iter(flat)] * shape[1])), array=True)


def operate(op: str, left, right, scalar_op) -> Range | None:
    """``left op right`` over arrays, or None where this module does not apply;
    ``scalar_op(op, a, b)`` is the scalar operator (the dialect's)."""
    arrays = [v for v in (left, right) if isinstance(v, Range)]
    shapes = {v.shape for v in arrays}
    if len(shapes) != 1:
        return None
    shape = shapes.pop()
    if shape[0] * shape[1] < MIN_ELEMENTS:
        return None
    if op in COMPARISONS:
        if len(arrays) != 1:
            return None
        items = list(arrays[0].flat())
        single = right if arrays[0] is left else left
        if isinstance(single, Range):
            return None
        if type(single) in (float, int) and set(map(type, items)) <= {float, int}:
            with np.errstate(all="ignore"):  # numbers with a number: exactly, as compare
                a, b = np.array(items, dtype=float), float(single)
                found = NUMERIC_COMPARE[op](a, b) if arrays[0] is left else \
                    NUMERIC_COMPARE[op](b, a)
            return _shaped(found.tolist(), shape)
        # keyed by type too: TRUE, 1 and 1.0 are one key of a dict but compare otherwise
        keys = list(zip(map(type, items), items))
        try:
            seen = dict.fromkeys(keys)
            if arrays[0] is left:
                answer = {k: scalar_op(op, k[1], single) for k in seen}
            else:
                answer = {k: scalar_op(op, single, k[1]) for k in seen}
            return _shaped([answer[k] for k in keys], shape)
        except (TypeError, KeyError):  # (unhashable, or NaN: element by element)
            return None
    fn = ARITHMETIC.get(op)
    if fn is None:
        return None
    sides = []
    for v in (left, right):
        if isinstance(v, Range):
            side = _numbers(list(v.flat()))
        elif type(v) in (float, int, bool):
            side = float(v)
        else:
            return None
        if side is None:
            return None
        sides.append(side)
    with np.errstate(all="ignore"):
        result = fn(sides[0], sides[1]) + 0.0  # (+ 0.0: no negative zero)
    out = result.tolist()
    bad = ~np.isfinite(result)
    if op == "/":
        zero = np.broadcast_to(np.asarray(sides[1]) == 0, result.shape)
        for i in np.flatnonzero(zero).tolist():
            out[i] = ExcelError.DIV0
        bad &= ~zero
    for i in np.flatnonzero(bad).tolist():
        out[i] = ExcelError.NUM
    return _shaped(out, shape)
