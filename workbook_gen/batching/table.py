"""The summary table: one row per variant, the columns of docs/batch.md, summary.csv.

``variant``, ``file``, ``status``, the varied parameters and options (an option
that takes texts or true/false is a text column), then for each output
``<q>_min``, ``<q>_min_at``, ``<q>_max``, ``<q>_max_at``, the template's
classification (spans over the sweep, figures from the parameters),
``rows_not_assembled`` and ``audit``.  Numbers are floats, NaN or None where there
is none (a refused variant, a figure whose formula is an error).  Varied options may
change which quantities a variant has (``balance`` adds the counterweights' columns):
the columns are those of every option combination, in order, and a variant has no
value in the columns its combination lacks.

A table made with ``keep=False`` (``--summary-only``: up to a million variants) holds
no rows: each block goes on to the summaries' writer, and the table keeps only what
the summaries need of the whole (each figure column's kinds of value, the counts of
statuses and failing audits; the Statistics and Charts sheets read the columns they
need back from the Parquet file).
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field

import numpy as np
from typing import Iterable, Mapping, Sequence

from ..pruning import Model
from .blocktext import TEXT_COLUMNS, value_kind
from .rows import ROW_COUNTS, column_units, header, text_figures, value_columns
from .specs import shown
from .variants import Design, Variant


def merged_columns(models: Iterable[Model]) -> list[str]:
    """The value columns of every model, each once: the first model's in order, then
    each column another model adds, after the column it follows there."""
    merged: list[str] = []
    for model in models:
        before = None
        for name in value_columns(model):
            if name not in merged:
                merged.insert(0 if before is None else merged.index(before) + 1, name)
            before = name
    return merged


@dataclass
class Table:
    design: Design
    model: Model
    defaults: Mapping[str, object]    # the scene's parameters and options (with --set)
    data: dict[str, list[object]] = field(default_factory=dict)
    keep: bool = True                 # hold the rows (else only what ``kind`` needs)
    others: Sequence[Model] = ()      # the models of the other option combinations

    def __post_init__(self) -> None:
        size = len(self.design)
        models = [self.model, *self.others]
        self.values = merged_columns(models) if self.others else value_columns(self.model)
        self.columns = (["variant", "file", "status"] + list(self.design.names)
                        + self.values + ["audit"])
        self.units: dict[str, str] = {}
        for model in reversed(models):  # a column's unit from the first model having it
            self.units.update(column_units(model, self.design.names))
        self.headers = [header(name, self.units) for name in self.columns]
        self._kinds: dict[str, str] = {}
        self.figures = self._figures = set().union(*map(text_figures, models))
        self.defaults_shown = {name: shown(self.defaults[name]) for name in self.design.names}
        options = set(self.design.options)
        self.text_options = frozenset(  # int options are numbers
            name for name in options if not isinstance(self.defaults[name], int)
            or isinstance(self.defaults[name], bool))
        self._done = 0
        if not self.keep:
            self.data = {}
            self._types: dict[str, set] = {name: set() for name in self._figures}
            self._statuses: Counter = Counter()
            self._audit_failed = self._failed = 0
            return
        self.data = {name: [None] * size for name in self.columns}
        self.data["variant"] = [v.label for v in self.design.variants]
        varied = {name: self.data[name] for name in self.design.names}
        for name, column in varied.items():
            column[:] = [shown(self.defaults[name])] * size
        options = set(self.design.options)
        for i, variant in enumerate(self.design.variants):
            for name, value in variant.values:  # the last of a name given twice wins
                if name in varied:
                    varied[name][i] = shown(value) if name in options else value
        self._filled = [False] * size

    def put(self, variant: Variant, row: Mapping[str, object]) -> None:
        i = variant.index - 1
        for name in self.columns[3 + len(self.design.names):] + ["file", "status"]:
            self.data[name][i] = row.get(name)
        self._filled[i] = True

    def put_block(self, variants: Sequence[Variant], block: Mapping[str, list[object]]) -> None:
        if not self.keep:
            for name, types in self._types.items():
                types.update(map(type, block[name]))
            self._statuses.update(s.split(":")[0] for s in block["status"])
            self._audit_failed += sum(a == "fail" for a in block["audit"])
            self._failed += sum(s != "ok" or a == "fail"
                                for s, a in zip(block["status"], block["audit"]))
            self._done += len(variants)
            return
        first = variants[0].index - 1
        contiguous = variants[-1].index - variants[0].index == len(variants) - 1
        for name, values in block.items():
            if isinstance(values, np.ndarray):
                values = values.tolist()
            column = self.data[name]
            if contiguous:
                column[first:first + len(variants)] = values
            else:
                for variant, value in zip(variants, values):
                    column[variant.index - 1] = value
        for variant in variants:
            self._filled[variant.index - 1] = True

    def kind(self, name: str) -> str:
        """``text``, ``number`` (floats, NaN or None for none) or ``mixed`` (a figure
        that is a number for some variants and a text for others); asked once the
        table is complete."""
        kind = self._kinds.get(name)
        if kind is None:
            kind = self._kinds[name] = self._kind(name)
        return kind

    def _kind(self, name: str) -> str:
        if name in TEXT_COLUMNS or name in self.text_options:
            return "text"
        if name in self.design.names or name not in self._figures:
            return "number"
        if not self.keep:
            types = self._types[name] - {type(None)}
            if all(issubclass(t, (int, float)) for t in types):
                return "number"
            return "text" if types <= {str} else "mixed"   # as value_kind decides
        return value_kind(self.data[name])

    @property
    def complete(self) -> bool:
        return self._done == len(self.design) if not self.keep else all(self._filled)

    def tally(self) -> tuple[Counter, int]:
        """(variants by status: ``ok``, ``partial``, ``refused``; failing audits)."""
        if not self.keep:
            return self._statuses, self._audit_failed
        return (Counter(s.split(":")[0] for s in self.statuses()),
                sum(a == "fail" for a in self.data["audit"]))

    def failed_count(self) -> int:
        """Variants that make the exit code 1: not ok, or a failing audit (counted
        once)."""
        if not self.keep:
            return self._failed
        return sum(self.failed())

    def statuses(self) -> list[str]:
        return [s or "" for s in self.data["status"]]

    def failed(self) -> list[bool]:
        """Rows that make the exit code 1: not ok, or a failing audit."""
        return [s != "ok" or a == "fail" for s, a in zip(self.statuses(), self.data["audit"])]

    def frame(self):
        import pandas as pd
        out = {}
        for name in self.columns:
            values = self.data[name]
            kind = self.kind(name)
            if kind == "text":
                out[name] = ["" if v is None else str(v) for v in values]
            elif kind == "number" and name not in ROW_COUNTS:
                out[name] = np.array(values, dtype=float)  # None -> NaN
            else:
                out[name] = values
        frame = pd.DataFrame(out, columns=self.columns)
        frame.attrs["units"] = dict(self.units)
        for name in ROW_COUNTS:
            if name in frame:
                frame[name] = frame[name].astype("Int64")
        return frame
