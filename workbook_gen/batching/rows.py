"""The summary's figures for a block of variants: one code path for the per-variant
job (a block of one) and for ``--summary-only`` (blocks of thousands).

Columns arrive flattened, variant after variant (``V * n`` rows, ``n`` rows per
variant); extremes are taken over the ok rows as the workbook's Summary takes them
(tabulate/extremes.py: a flagged row or one that cannot be assembled is left out),
the ``_at`` value is the input of the first ok row where the extreme occurs.
"""

from __future__ import annotations

import re
from typing import Mapping, Sequence

import numpy as np

from .. import xlmath as xm
from ..expr import Bin, Call, Neg, Node, Param, Var
from ..expr.numeric import compile_numpy
from ..tabulate.extremes import OK, ok_extremes
from ..tabulate.table import CANNOT_ASSEMBLE
from ..pruning import Model

#: The summary's counts of a variant's rows left out of its extremes: flagged (a dead
#: centre, a toggle, not converged: the workbook's Summary counts them too) and those
#: that cannot be assembled.
ROW_COUNTS = ("rows_flagged", "rows_not_assembled")
_PARAM = "\x00param:"  # Var names for parameters: no quantity can be named so


def as_columns(node: Node) -> Node:
    """The tree with every parameter read from a column (one value per row) instead of
    one number: the same tree evaluated for many variants at once."""
    if isinstance(node, Param):
        return Var(_PARAM + node.name)
    if isinstance(node, Neg):
        return Neg(as_columns(node.operand))
    if isinstance(node, Bin):
        return Bin(node.op, as_columns(node.left), as_columns(node.right))
    if isinstance(node, Call):
        return Call(node.fn, tuple(as_columns(a) for a in node.args))
    return node


def param_columns(values: Mapping[str, np.ndarray], repeat: int) -> dict[str, xm.XArray]:
    """Parameter columns for ``as_columns`` trees: each variant's value ``repeat`` times
    (NaN, a derived value in error, behaves as the number NaN does in ``compile_numpy``)."""
    columns = {}
    for name, per_variant in values.items():
        val = np.repeat(np.asarray(per_variant, dtype=float), repeat)
        columns[_PARAM + name] = xm.XArray(val, np.zeros(val.shape, np.uint8))
    return columns


def snake(label: str) -> str:
    """A summary column name for a template's figure label: ``needle stroke, exact`` ->
    ``needle_stroke_exact``."""
    return re.sub(r"[^0-9a-z]+", "_", label.lower()).strip("_")


def figure_columns(model: Model) -> list[str]:
    """The classification columns: the spans (max - min over the sweep), then the
    figures computed from the parameters."""
    return [snake(s.label) for s in model.spans] + [snake(f.label) for f in model.figures]


def text_figures(model: Model) -> set[str]:
    """The figure columns that may hold texts (not the spans, always numbers)."""
    return set(figure_columns(model)) - {snake(s.label) for s in model.spans}


def value_columns(model: Model) -> list[str]:
    """Every summary column a variant's evaluation fills, in order."""
    names = []
    for q in model.outputs():
        names += [f"{q.name}_min", f"{q.name}_min_at", f"{q.name}_max", f"{q.name}_max_at"]
    return names + figure_columns(model) + list(ROW_COUNTS)


def column_units(model: Model, varied: Sequence[str]) -> dict[str, str]:
    """The unit of each summary column that has one, from the template's own specs: a
    varied parameter's, an output's for its extremes, the sweep input's for the
    ``_at`` columns (where an extreme occurs), a span's quantity's, a figure's."""
    template = model.template
    params = {p.name: p.unit for p in template.parameters}
    units = {name: params[name] for name in varied if params.get(name)}
    at = template.input.unit
    for q in model.outputs():
        if q.unit:
            units[f"{q.name}_min"] = units[f"{q.name}_max"] = q.unit
        if at:
            units[f"{q.name}_min_at"] = units[f"{q.name}_max_at"] = at
    for span in model.spans:
        unit = template.quantity(span.quantity).unit
        if unit:
            units[snake(span.label)] = unit
    for figure in model.figures:
        if figure.unit:
            units[snake(figure.label)] = figure.unit
    return units


def header(name: str, units: Mapping[str, str]) -> str:
    """A summary column's header: its name and unit, ``y_C_max [mm]``."""
    unit = units.get(name)
    return f"{name} [{unit}]" if unit else name


def figure_values(model: Model, params: Mapping[str, np.ndarray], variants: int
                  ) -> dict[str, list[object]]:
    """The template's figures from the parameters: a number, a text (Grashof class) or
    NaN where the formula gives an error."""
    columns = param_columns(params, 1)
    out = {}
    for figure in model.figures:
        value = compile_numpy(as_columns(figure.expr))(columns, {}, variants)
        out[snake(figure.label)] = [
            None if e else (v if isinstance(v, str) else float(v))
            for v, e in zip(value.val.tolist(), value.err.tolist())]
    return out


def summarise(model: Model, inputs: np.ndarray, columns: Mapping[str, xm.XArray],
              status: np.ndarray, figures: Mapping[str, list[object]],
              variants: int, arrays: bool = False) -> dict[str, list[object]]:
    """For each of ``value_columns(model)`` and ``status`` (``ok`` or ``partial``), a list
    with one entry per variant (NaN or None: no number); ``arrays``: the columns of
    floats as float arrays instead (NaN: no number)."""
    table: dict[str, np.ndarray | list] = {}
    extremes = {}
    for q in model.outputs():
        column = columns[q.name]
        found = ok_extremes(column.val, column.err, status, inputs, variants)
        extremes[q.name] = (found.lo, found.hi)
        table[f"{q.name}_min"], table[f"{q.name}_min_at"] = found.lo, found.lo_at
        table[f"{q.name}_max"], table[f"{q.name}_max_at"] = found.hi, found.hi_at
    for span in model.spans:  # a span's quantity is always an output (model.select)
        lo, hi = extremes[span.quantity]
        table[snake(span.label)] = hi - lo
    table.update(figures)
    texts = np.asarray(status, dtype=object).reshape(variants, len(inputs))
    missing = (texts == CANNOT_ASSEMBLE).sum(axis=1)
    table["rows_flagged"] = ((texts != CANNOT_ASSEMBLE) & (texts != OK)).sum(axis=1).tolist()
    table["rows_not_assembled"] = missing
    table["rows_not_assembled"] = missing.tolist()
    out = {name: (table[name] if arrays else table[name].tolist())
           if isinstance(table[name], np.ndarray) else list(table[name])
           for name in value_columns(model)}
    out["status"] = ["partial" if m else "ok" for m in out["rows_not_assembled"]]
    return out
