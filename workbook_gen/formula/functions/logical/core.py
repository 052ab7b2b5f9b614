"""Logical functions: IF, IFERROR, IFNA, IFS, SWITCH (lazy), AND, OR, XOR, NOT, TRUE, FALSE."""

from __future__ import annotations

import numpy as np

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.functions.registry import register
from workbook_gen.xlerror import ExcelError
from workbook_gen.xlmath import kernels as k


def _scalar(ctx, thunk):
    return ctx.scalar(thunk())


@register("IF", 1, 3, "lazy")
def _if(ctx, cond, then=None, other=None):
    b = c.to_bool(_scalar(ctx, cond))
    if isinstance(b, ExcelError):
        return b
    if b:
        return then() if then is not None else True
    return other() if other is not None else False


@register("IFERROR", 2, 2, "lazy")
def _iferror(ctx, value, fallback):
    v = _scalar(ctx, value)
    return fallback() if isinstance(v, ExcelError) else v


@register("IFNA", 2, 2, "lazy")
def _ifna(ctx, value, fallback):
    v = _scalar(ctx, value)
    return fallback() if v is ExcelError.NA else v


@register("IFS", 2, -1, "lazy")
def _ifs(ctx, *thunks):
    if len(thunks) % 2:
        return ExcelError.VALUE
    for i in range(0, len(thunks), 2):
        b = c.to_bool(_scalar(ctx, thunks[i]))
        if isinstance(b, ExcelError):
            return b
        if b:
            return thunks[i + 1]()
    return ExcelError.NA


@register("SWITCH", 3, -1, "lazy")
def _switch(ctx, expr, *thunks):
    v = _scalar(ctx, expr)
    if isinstance(v, ExcelError):
        return v
    pairs, default = (thunks, None) if len(thunks) % 2 == 0 else (thunks[:-1], thunks[-1])
    for i in range(0, len(pairs), 2):
        w = _scalar(ctx, pairs[i])
        if isinstance(w, ExcelError):
            return w
        if c.rank(w) == c.rank(v) and c.compare(v, w) == 0:
            return pairs[i + 1]()
    return default() if default is not None else ExcelError.NA


def _andor_vector(name):
    def vector(xs, n):
        err = k.first_error(*(e for _, e in xs))
        truth = np.array([v != 0 for v, _ in xs])
        val = truth.all(axis=0) if name == "AND" else truth.any(axis=0)
        return np.where(err != 0, np.nan, val.astype(float)), err, True
    return vector


@register("AND", 1, -1, "range", vector=_andor_vector("AND"))
def _and(ctx, *args):
    bs = c.logicals(args, ctx.dialect == "excel")
    return bs if isinstance(bs, ExcelError) else all(bs)


@register("OR", 1, -1, "range", vector=_andor_vector("OR"))
def _or(ctx, *args):
    bs = c.logicals(args, ctx.dialect == "excel")
    return bs if isinstance(bs, ExcelError) else any(bs)


@register("XOR", 1, -1, "range")
def _xor(ctx, *args):
    bs = c.logicals(args, ctx.dialect == "excel")
    return bs if isinstance(bs, ExcelError) else sum(bs) % 2 == 1


def _not_vector(xs, n):
    (x, e), = xs
    return np.where(e != 0, np.nan, (x == 0).astype(float)), e, True


@register("NOT", 1, 1, vector=_not_vector)
def _not(ctx, v):
    b = c.to_bool(v)
    return b if isinstance(b, ExcelError) else not b


register("TRUE", 0, 0)(lambda ctx: True)
register("FALSE", 0, 0)(lambda ctx: False)
