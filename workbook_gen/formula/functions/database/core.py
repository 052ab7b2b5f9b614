"""The database functions D*(database, field, criteria): DAVERAGE, DCOUNT, DCOUNTA, DGET,
DMAX, DMIN, DPRODUCT, DSTDEV, DSTDEVP, DSUM, DVAR, DVARP.

``database`` is a range whose first row holds the labels; ``field`` is a label (any case)
or a 1-based column number; ``criteria`` is a range whose first row holds labels and
each further row a set of conditions (all in one row must hold, any row may match; an
empty cell is no condition). A condition is as COUNTIF's (``">2"``, ``"<>x"``, ``"=2"``,
wildcards) except that plain text matches every value beginning with it (Excel's
filter rule). DCOUNT and DCOUNTA without a field (omitted or 0) count the records."""

from __future__ import annotations

import math

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.math.core import fsum
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError


def _label(v) -> str:
    return "" if v is None else str(c.to_text(v)).strip().upper()


def _condition(v):
    if isinstance(v, str) and not v.startswith(c.CRITERION_OPERATORS):
        if isinstance(c.text_to_number(v), float) or v.upper() in ("TRUE", "FALSE"):
            return c.criterion(v)
        return c.criterion(v + "*")
    return c.criterion(v)


def _records(database, criteria):
    """(labels, matching records) or an error."""
    for v in (database, criteria):
        if isinstance(v, ExcelError):
            return v
    db, cr = c.as_area(database), c.as_area(criteria)
    if len(db.rows) < 1 or len(cr.rows) < 1:
        return ExcelError.VALUE
    labels = [_label(v) for v in db.rows[0]]
    tests = []
    for row in cr.rows[1:]:
        conds = []
        for head, v in zip(cr.rows[0], row):
            if v is None or v == "":
                continue
            if isinstance(v, ExcelError):
                return v
            name = _label(head)
            if name not in labels:
                return ExcelError.VALUE  # a computed criterion (formula) is not supported
            conds.append((labels.index(name), _condition(v)))
        tests.append(conds)
    if not tests:
        return ExcelError.VALUE
    out = [rec for rec in db.rows[1:]
           if any(all(pred(rec[i]) for i, pred in conds) for conds in tests)]
    return labels, out


def _column(labels, field):
    if field is None:
        return None
    if isinstance(field, str):
        name = field.strip().upper()
        return labels.index(name) if name in labels else ExcelError.VALUE
    x = c.to_number(field)
    if isinstance(x, ExcelError):
        return x
    k = math.trunc(x)
    if k == 0:
        return None
    return k - 1 if 1 <= k <= len(labels) else ExcelError.VALUE


def _dfunc(name, reduce, count_all=False):
    def fn(ctx, database, field, criteria):
        got = _records(database, criteria)
        if isinstance(got, ExcelError):
            return got
        labels, records = got
        col = _column(labels, field)
        if isinstance(col, ExcelError):
            return col
        if col is None:
            return float(len(records)) if count_all else ExcelError.VALUE
        return reduce([rec[col] for rec in records])
    register(name, 3, 3, ("range", "scalar", "range"))(fn)


def _numbers(vals):
    err = c.first_error(vals)
    return err if err is not None else [float(v) for v in vals if c.is_number(v)]


def _num_reduce(fn):
    def reduce(vals):
        xs = _numbers(vals)
        return xs if isinstance(xs, ExcelError) else c.result(fn(xs))
    return reduce


def _var(xs, ddof):
    if len(xs) - ddof <= 0:
        return ExcelError.DIV0
    m = fsum(xs) / len(xs)
    return fsum((x - m) ** 2 for x in xs) / (len(xs) - ddof)


def _root(v):
    return v if isinstance(v, ExcelError) else math.sqrt(v)


def _get(vals):
    if not vals:
        return ExcelError.VALUE
    if len(vals) > 1:
        return ExcelError.NUM
    return 0.0 if vals[0] is None else vals[0]


_dfunc("DSUM", _num_reduce(fsum))
_dfunc("DAVERAGE", _num_reduce(lambda xs: fsum(xs) / len(xs) if xs else ExcelError.DIV0))
_dfunc("DCOUNT", lambda vals: float(sum(1 for v in vals if c.is_number(v))), count_all=True)
_dfunc("DCOUNTA", lambda vals: float(sum(1 for v in vals if v is not None and v != "")),
       count_all=True)
_dfunc("DMAX", _num_reduce(lambda xs: max(xs, default=0.0)))
_dfunc("DMIN", _num_reduce(lambda xs: min(xs, default=0.0)))
_dfunc("DPRODUCT", _num_reduce(lambda xs: math.prod(xs) if xs else 0.0))
_dfunc("DVAR", _num_reduce(lambda xs: _var(xs, 1)))
_dfunc("DVARP", _num_reduce(lambda xs: _var(xs, 0)))
_dfunc("DSTDEV", _num_reduce(lambda xs: _root(_var(xs, 1))))
_dfunc("DSTDEVP", _num_reduce(lambda xs: _root(_var(xs, 0))))
_dfunc("DGET", _get)
