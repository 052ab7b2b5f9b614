"""The summary table: one row per variant, the columns SPEC section 11 lists.

``variant``, ``file``, ``status``, the varied parameters, then for each output
``<q>_min``, ``<q>_min_at``, ``<q>_max``, ``<q>_max_at``, the template's
classification (spans over the sweep, figures from the parameters),
``rows_not_assembled`` and ``audit``.  Numbers are floats, NaN or None where there
is none (a refused variant, a figure whose formula is an error).

A table made with ``keep=False`` (``--summary-only``: up to a million variants) holds
no rows: each block goes on to the summaries' writer, and the table keeps only what
the summaries need of the whole (each figure column's kinds of value, the counts of
statuses and failing audits).
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field

import numpy as np
from typing import Mapping, Sequence

from ..model import Model
from .blocktext import TEXT_COLUMNS, value_kind
from .rows import text_figures, value_columns
from .variants import Design, Variant


@dataclass
class Table:
    design: Design
    model: Model
    defaults: Mapping[str, float]     # the scene's parameters (with --set)
    data: dict[str, list[object]] = field(default_factory=dict)
    keep: bool = True                 # hold the rows (else only what ``kind`` needs)

    def __post_init__(self) -> None:
        size = len(self.design)
        self.columns = (["variant", "file", "status"] + list(self.design.names)
                        + value_columns(self.model) + ["audit"])
        self._kinds: dict[str, str] = {}
        self._figures = text_figures(self.model)
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
            column[:] = [self.defaults[name]] * size
        for i, variant in enumerate(self.design.variants):
            for name, value in variant.values:  # the last of a name given twice wins
                if name in varied:
                    varied[name][i] = value
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
        if name in TEXT_COLUMNS:
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
            elif kind == "number" and name != "rows_not_assembled":
                out[name] = np.array(values, dtype=float)  # None -> NaN
            else:
                out[name] = values
        frame = pd.DataFrame(out, columns=self.columns)
        if "rows_not_assembled" in frame:
            frame["rows_not_assembled"] = frame["rows_not_assembled"].astype("Int64")
        return frame
