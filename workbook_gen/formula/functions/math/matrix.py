"""Matrices and paired sums: MMULT, MINVERSE, MDETERM, MUNIT, SUMX2MY2,
SUMX2PY2, SUMXMY2, SUMPRODUCT. Matrix arguments must hold numbers only (else #VALUE!); results that
are arrays are returned as array Ranges (spread over an array formula's cells, or their
first item where one value is wanted)."""

from __future__ import annotations

import math

import numpy as np

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.math.core import fsum
from workbook_gen.formula.functions.registry import register
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError


def matrix(v) -> np.ndarray | ExcelError:
    """An area of numbers as a float matrix (an error cell is that error, other
    non-numbers #VALUE!)."""
    area = c.as_area(v)
    if not area.rows or not area.rows[0]:
        return ExcelError.VALUE
    err = c.first_error(area.flat())
    if err is not None:
        return err
    if not all(c.is_number(x) for x in area.flat()):
        return ExcelError.VALUE
    return np.array([[float(x) for x in row] for row in area.rows], dtype=float)


def array(m: np.ndarray) -> Range | ExcelError:
    if not np.all(np.isfinite(m)):
        return ExcelError.NUM
    return Range.array_of([[c.result(float(x)) for x in row] for row in m])


@register("MMULT", 2, 2, "range", omitted=True)
def _mmult(ctx, a, b):
    """An omitted argument is #VALUE! (Excel, ironcalc MMULT.xlsx: MMULT(,)), LibreOffice's
    the number 0."""
    if ctx is not None and ctx.dialect == "libreoffice":
        a, b = (0.0 if v is None else v for v in (a, b))
    x, y = matrix(a), matrix(b)
    for v in (x, y):
        if isinstance(v, ExcelError):
            return v
    if x.shape[1] != y.shape[0]:
        return ExcelError.VALUE
    xs, ys = x.tolist(), y.T.tolist()  # Python floats: an overflow is inf, and #NUM! below
    out = [[fsum(p * q for p, q in zip(row, col)) for col in ys] for row in xs]
    return array(np.array(out))


def _square(v):
    m = matrix(v)
    if isinstance(m, ExcelError):
        return m
    return m if m.shape[0] == m.shape[1] else ExcelError.VALUE


@register("MDETERM", 1, 1, "range")
def _mdeterm(ctx, v):
    m = _square(v)
    if isinstance(m, ExcelError):
        return m
    return c.result(float(np.linalg.det(m)))


@register("MINVERSE", 1, 1, "range")
def _minverse(ctx, v):
    m = _square(v)
    if isinstance(m, ExcelError):
        return m
    if np.linalg.det(m) == 0:
        return ExcelError.NUM
    try:
        return array(np.linalg.inv(m))
    except np.linalg.LinAlgError:
        return ExcelError.NUM


@register("MUNIT", 1, 1)
def _munit(ctx, n):
    k = c.to_number(n)
    if isinstance(k, ExcelError):
        return k
    k = math.trunc(k)
    if k < 1:
        return ExcelError.VALUE
    return array(np.eye(k))


def _paired(fn):
    def scalar(ctx, a, b):
        x, y = c.flat(c.as_area(a)), c.flat(c.as_area(b))
        if len(x) != len(y):
            return ExcelError.NA
        err = c.first_error(x + y)
        if err is not None:
            return err
        terms = [fn(float(p), float(q)) for p, q in zip(x, y)
                 if c.is_number(p) and c.is_number(q)]
        return c.result(fsum(terms)) if terms else ExcelError.DIV0  # no pair: Excel's #DIV/0!
    return scalar


register("SUMX2MY2", 2, 2, "range")(_paired(lambda x, y: x * x - y * y))
register("SUMX2PY2", 2, 2, "range")(_paired(lambda x, y: x * x + y * y))
register("SUMXMY2", 2, 2, "range")(_paired(lambda x, y: (x - y) ** 2))


@register("SUMPRODUCT", 1, -1, "range")
def _sumproduct(ctx, *args):
    areas = [c.as_area(a) for a in args]
    shape = areas[0].shape
    if any(a.shape != shape for a in areas):  # Excel: an error in the arrays first (Mac
        # Excel's 'MATH & TRIG'!AE75:AF75: the first array's #NUM!, #REF!); LibreOffice
        # (7.4, measured): #VALUE!
        if ctx is not None and ctx.dialect == "libreoffice":
            return ExcelError.VALUE
        return next((v for a in areas for v in a.flat() if isinstance(v, ExcelError)),
                    ExcelError.VALUE)
    columns = [list(a.flat()) for a in areas]
    lo = ctx.dialect == "libreoffice"  # a boolean is a number there
    if shape == (1, 1) and not lo and any(isinstance(v, (str, bool)) for (v,) in columns):
        # single values multiply as direct arguments: text is #VALUE!, not the zero of a
        # non-numeric array entry (POI FormulaEvalTestData.xlsx J1328: SUMPRODUCT(G1330:G1330,
        # I1330:I1330) over "4" and 2)
        return c.first_error([v for (v,) in columns]) or ExcelError.VALUE
    total = []
    for row in zip(*columns):
        err = c.first_error(row)
        if err is not None:
            return err
        total.append(math.prod(float(v) if c.is_number(v) or (lo and isinstance(v, bool))
                               else 0.0 for v in row))
    return c.result(fsum(total))
