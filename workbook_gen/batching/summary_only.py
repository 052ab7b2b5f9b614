"""``--summary-only``: the summary rows of every variant without their workbooks.

The scene's expression trees are evaluated once per block of variants over a
variants x rows array (held flattened, variant after variant): each parameter is a
column holding its variant's value on every row of that variant, so one numpy call
per tree node serves thousands of variants.  The numeric code is the one that makes
the workbooks' cached values (``compile_numpy``, ``xlmath``), and the figures come
from ``rows.summarise`` as in the per-variant job, so the extremes are the same
numbers.  Blocks keep memory bounded whatever the number of variants.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..errors import SceneError
from ..scene import MAGNITUDE, Scene, parse_scene
from ..tabulate.table import status_texts
from .broadcast import Plan
from .job import JobSpec, refused_reason, unassembled_reason, variant_scene
from .blocktext import TEXT_COLUMNS, block_texts, has_value, value_kind
from .rows import ROW_COUNTS, figure_values, summarise, text_figures, value_columns
from .summary import BlockText
from .specs import shown
from .variants import Variant

# Elements (variants x rows) per block: 512 KB per float column (blocks of 2^18 took
# ~15% more CPU: their ~100 columns and temporaries do not stay in the caches).
BLOCK_ELEMENTS = 1 << 16


def _screen(base: Scene, spec: JobSpec, variants: Sequence[Variant],
            values: dict[str, np.ndarray]) -> dict[int, str]:
    """Variants the scene's rules refuse (a non-positive length, the template's own
    rule), by position, with the reason ``generate`` would give."""
    template = base.template
    suspect = np.zeros(len(variants), dtype=bool)
    for p in template.parameters:  # parse_scene's rules, widened: it has the last word
        column = values[p.name]
        suspect |= np.abs(column) > MAGNITUDE[1]
        if p.positive:
            suspect |= column < MAGNITUDE[0]
    names = list(values)
    columns = [values[n].tolist() for n in names]
    for i, row in enumerate(zip(*columns)):
        if not suspect[i] and template.validate(dict(zip(names, row))):
            suspect[i] = True
    refused = {}
    for i in np.flatnonzero(suspect):
        try:
            variant_scene(spec, variants[i])
        except SceneError as exc:
            refused[int(i)] = f"refused: {refused_reason(spec, exc)}"
    return refused


def _block(base: Scene, plan: Plan, spec: JobSpec, variants: Sequence[Variant]
           ) -> dict[str, list[object]]:
    """The summary columns of a block of variants (refused ones hold no numbers)."""
    names = value_columns(plan.model)
    size = len(variants)
    out: dict[str, list[object]] = {name: [math.nan] * size for name in names}
    out["status"] = [""] * size
    values = {name: np.full(size, value) for name, value in base.parameters.items()}
    for i, variant in enumerate(variants):
        for name, value in variant.values:
            values[name][i] = value
    refused = _screen(base, spec, variants, values)
    keep = np.array([i not in refused for i in range(size)], dtype=bool)
    count = int(keep.sum())
    if count:
        params = plan.parameters_of({k: v[keep] for k, v in values.items()}, count)
        inputs = np.array(base.sweep.values())
        columns, status = plan.evaluate(params, inputs, count)
        figures = figure_values(plan.model, params, count)
        made = summarise(plan.model, inputs, columns, status_texts(status), figures, count,
                         arrays=True)
        if count == size:
            out.update({name: made[name] for name in names + ["status"]})
        else:
            where = np.flatnonzero(keep)
            for name in names + ["status"]:
                column = np.array(out[name], dtype=object)
                column[where] = np.array(made[name], dtype=object)
                out[name] = column.tolist()
        for j in np.flatnonzero(np.array(made["rows_not_assembled"]) == len(inputs)).tolist():
            i = int(np.flatnonzero(keep)[j])
            point = {name: float(values[name][i]) for name in base.parameters}
            refused[i] = f"refused: {unassembled_reason(base, point)}"
    for i, status in refused.items():
        for name in names:
            out[name][i] = None if name in ROW_COUNTS else math.nan
        out["status"][i] = status
    out["file"] = [""] * size
    out["audit"] = [""] * size
    return out


@functools.lru_cache(maxsize=64)
def _prepared(spec: JobSpec, options: tuple[tuple[str, object], ...] = ()
              ) -> tuple[Scene, Plan]:
    """The scene with the command's --set and --step (and a combination of varied
    options), and its trees compiled: once per process, whatever the number of blocks
    it runs.  SceneError when the scene refuses the options."""
    base = parse_scene(spec.text, spec.source, {**dict(spec.sets), **dict(options)} or None,
                       spec.step)
    return base, Plan(base)


def _options_block(spec: JobSpec, variants: Sequence[Variant], options: frozenset[str],
                   columns: Sequence[str]) -> dict[str, list[object]]:
    """``_block`` of variants that vary template options: each combination of options
    evaluated with its own scene and trees, in the table's ``columns`` (None where a
    combination has no such column); a combination the scene refuses is refused for
    each of its variants with ``generate``'s reason."""
    size = len(variants)
    groups: dict[tuple, list[int]] = {}
    for i, variant in enumerate(variants):
        key = tuple((n, v) for n, v in variant.values if n in options)
        groups.setdefault(key, []).append(i)
    out: dict[str, list[object]] = {name: [None] * size for name in columns}
    out.update(status=[""] * size, file=[""] * size, audit=[""] * size)
    for key, where in groups.items():
        members = [variants[i] for i in where]
        try:
            base, plan = _prepared(spec, key)
        except SceneError:
            base = None
        varied = {n for v in members for n, _ in v.values if n not in options}
        if base is None or not varied <= set(base.parameters):
            for i, variant in zip(where, members):
                try:
                    variant_scene(spec, variant)
                    reason = "the options and parameters do not fit together"
                except SceneError as exc:
                    reason = refused_reason(spec, exc)
                out["status"][i] = f"refused: {reason}"
            continue
        # the options as --set for the group: a refusal's reason is generate's
        stripped = [v._replace(values=tuple((n, x) for n, x in v.values if n not in options))
                    for v in members]
        block = _block(base, plan, dataclasses.replace(spec, sets=tuple(spec.sets) + key),
                       stripped)
        for name in value_columns(plan.model) + ["status"]:
            column, made = out[name], block[name]
            if isinstance(made, np.ndarray):
                made = made.tolist()
            for i, value in zip(where, made):
                column[i] = value
    return out


def summary_block(spec: JobSpec, variants: Sequence[Variant]) -> dict[str, list[object]]:
    """The summary columns of ``variants`` (no option varied)."""
    base, plan = _prepared(spec)
    return _block(base, plan, spec, variants)


def block_size(spec: JobSpec) -> int:
    """Variants per block: about BLOCK_ELEMENTS rows in all."""
    base, _ = _prepared(spec)
    return max(1, BLOCK_ELEMENTS // max(1, base.sweep.rows))


@dataclass(frozen=True)
class SummaryJob:
    """A ``--summary-only`` batch as its workers see it: the job, the varied
    parameters and options and the summary's columns, so each block comes back
    formatted."""

    spec: JobSpec
    names: tuple[str, ...]
    values: tuple[str, ...] = ()                # the table's value columns
    figures: frozenset[str] = frozenset()       # the figure columns that may hold texts
    options: tuple[str, ...] = ()               # which names are options
    text_options: frozenset[str] = frozenset()  # options shown as texts
    defaults: tuple[tuple[str, object], ...] = ()  # each name's value as shown, if not varied


def summary_rows(job: SummaryJob, variants: Sequence[Variant]
                 ) -> tuple[dict[str, list[object]], BlockText | None]:
    """The summary columns of ``variants`` (with their labels and varied values when
    consecutive) and, if they are consecutive, their rows formatted for summary.csv
    and the Variants sheet (the kinds of the figure
    columns taken from this block: the command checks them against the whole
    table's)."""
    base, plan = _prepared(job.spec)
    if job.options:
        block = _options_block(job.spec, variants, frozenset(job.options), job.values)
    else:
        block = _block(base, plan, job.spec, variants)
    first = variants[0].index
    if variants[-1].index - first != len(variants) - 1:
        return block, None
    values = list(job.values) or value_columns(plan.model)
    columns = ["variant", "file", "status"] + list(job.names) + values + ["audit"]
    data = dict(block)
    data["variant"] = [v.label for v in variants]
    chosen = [dict(v.values) for v in variants]
    defaults = dict(job.defaults)
    for name in job.names:
        default = defaults[name] if name in defaults else base.parameters[name]
        if name in job.options:
            data[name] = [shown(values[name]) if name in values else default
                          for values in chosen]
        else:
            data[name] = [values.get(name, default) for values in chosen]
    figures = job.figures or text_figures(plan.model)
    kinds = {name: "text" if name in TEXT_COLUMNS or name in job.text_options
             else value_kind(data[name]) if name in figures and name not in job.names
             else "number" for name in columns}
    csv_text, xml_text = block_texts(columns, kinds, data, first + 1, len(variants))
    own = tuple((name, kinds[name]) for name in columns if name in figures
                and name not in job.names and name not in TEXT_COLUMNS)
    filled = frozenset(name for name, _ in own if has_value(data[name]))
    return data, BlockText(csv_text, xml_text.encode(), own, filled)  # every column
