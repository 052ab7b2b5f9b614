"""Criteria as the *IF(S) functions read them, shared by the statistical functions
(AVERAGEIF(S), COUNTIF(S), MAXIFS, MINIFS) and the math ones (SUMIF, SUMIFS): which cells of
a range meet every (range, criterion) pair, with LibreOffice's reading where its dialect
differs; the criterion text itself is read by :func:`.coerce.criterion`."""

from __future__ import annotations

from workbook_gen.formula.functions import coerce as c
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError


def _criterion_value(ctx, crit):
    """A criteria range is implicitly intersected with the formula's row or column; no
    shared cell is #VALUE!, a criterion that matches the cells holding #VALUE! (POI
    FormulaEvalTestData.xlsx: SUMIF(AA7:AA13,C10:D10,C7) in row 1324 is C9, 1.1)."""
    if not isinstance(crit, Range):
        return crit
    return ctx.scalar(crit) if ctx is not None else ExcelError.VALUE


def _lo_number(v):
    """A criterion as LibreOffice's, which has no boolean type: TRUE, "TRUE" are 1."""
    if isinstance(v, bool):
        return float(v)
    if isinstance(v, str):
        op = next((o for o in c.CRITERION_OPERATORS if v.startswith(o)), "")
        body = v[len(op):].upper()
        if body in ("TRUE", "FALSE"):
            return float(body == "TRUE") if not op else op + ("1" if body == "TRUE" else "0")
    return v


def _lo_values(crit, values):
    """LibreOffice 7.4 (measured: COUNTIF over {TRUE,1,"1"}) sees a boolean cell as its
    number except under a plain text criterion (" 1" counts 1 and "1", not TRUE)."""
    if isinstance(crit, str) and not crit.startswith(c.CRITERION_OPERATORS):
        return values
    return [float(v) if isinstance(v, bool) else v for v in values]


def matches(pairs, ctx=None) -> list[bool] | ExcelError:
    """Per cell of the first range, whether every (range, criterion) pair holds."""
    shape = None
    mask = None
    for rng, crit in pairs:
        area = c.as_area(rng)
        if shape is None:
            shape = area.shape
        elif area.shape != shape:
            return ExcelError.VALUE
        crit = _criterion_value(ctx, crit)
        values = area.flat()
        if ctx is not None and ctx.dialect == "libreoffice":  # no boolean type: TRUE is 1
            if isinstance(crit, ExcelError):  # an error criterion is the result (measured,
                return crit                   # tests/differential.py)
            crit = _lo_number(crit)
            values = _lo_values(crit, values)
        pred = c.criterion(crit)
        if isinstance(pred, ExcelError):
            return pred
        hits = [pred(v) for v in values]
        mask = hits if mask is None else [a and b for a, b in zip(mask, hits)]
    return mask


def _resized(area: Range, shape, ctx) -> list:
    """SUMIF's sum range takes the criteria range's shape from its top-left cell."""
    if area.shape == shape or area.ref is None:
        return list(area.flat())
    ref = area.ref
    from workbook_gen.formula.values import Ref
    grown = ctx.read(Ref(ref.sheet, ref.row1, ref.col1, ref.row1 + shape[0] - 1,
                         ref.col1 + shape[1] - 1))
    return list(area.flat()) if isinstance(grown, ExcelError) else list(grown.flat())


def picked(ctx, target, pairs):
    mask = matches(pairs, ctx)
    if isinstance(mask, ExcelError):
        return mask
    area = c.as_area(target)
    values = _resized(area, c.as_area(pairs[0][0]).shape, ctx)
    out = []
    for v, hit in zip(values, mask):
        if not hit:
            continue
        if isinstance(v, ExcelError):
            return v
        if c.is_number(v) or (ctx.dialect == "libreoffice" and isinstance(v, bool)):
            out.append(float(v))
    return out


def ifs_pairs(args):
    if len(args) % 2:
        return ExcelError.VALUE
    return [(args[i], args[i + 1]) for i in range(0, len(args), 2)]


def ifs(fn, empty):
    """The scalar form of SUMIFS, AVERAGEIFS, MAXIFS, MINIFS: ``fn`` of the target's numbers
    where every criterion holds, ``empty`` where none does."""
    def scalar(ctx, target, *args):
        pairs = ifs_pairs(args)
        if isinstance(pairs, ExcelError):
            return pairs
        if c.as_area(target).shape != c.as_area(pairs[0][0]).shape:
            return ExcelError.VALUE
        xs = picked(ctx, target, pairs)
        if isinstance(xs, ExcelError):
            return xs
        return c.result(fn(xs)) if xs else empty
    return scalar
