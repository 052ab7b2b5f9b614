"""The Summary sheet's values: each output's extremes over the ok rows and where they
occur (or a tie), the spans (stroke, swing), the figures from the parameters, and the
counts of rows left out of the extremes."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..expr.magnitude import magnitude, scope
from ..expr.numeric import compile_numpy
from ..xlerror import ExcelError
from .extremes import Extremes, ok_rows
from .table import CANNOT_ASSEMBLE, STATUS_OK, Table, cached_values

# where no row is ok: #N/A (AGGREGATE of nothing is #NUM! in Excel, #VALUE! in LibreOffice)
NONE_OK = ExcelError.NA.value

# A column whose max - min is within TIE_ULPS ulps of the magnitudes its formula cancels
# (expr/magnitude.py) is constant to rounding: its extremes are a tie, not a location
# (a balanced shaking force, a centre of mass that stands still).  Engines round such
# noise differently (LibreOffice makes near-equal differences 0), so a location there
# would be an accident of the engine.
TIE_ULPS = 4096
TIE = "tie"


def tie_threshold(table: Table, name: str, shared=None) -> float:
    """Largest max - min that is rounding noise for quantity ``name`` (0 if none).
    ``shared``: a magnitude ``scope`` of ``table`` kept over its outputs."""
    quantity = table.model.template.quantity(name)
    m = magnitude(quantity.expr, table.columns, table.params, table.rows, shared)
    m = m[np.isfinite(m)]
    bound = TIE_ULPS * np.finfo(float).eps * float(m.max()) if m.size else 0.0
    return float(f"{bound:.3g}")  # as written in the formula


@dataclass(frozen=True)
class OutputExtremes:
    """An output's row of the Summary as its formulas give it: max, its input, min, its
    input (#N/A where no row counts; the inputs "tie" where the column is constant to
    rounding), and the tie threshold its formulas hold."""

    hi: float | str
    at_hi: float | str
    lo: float | str
    at_lo: float | str
    tie: float
    tied: bool

    @property
    def span(self) -> float | str:
        """max - min (0 where tied), as the span's formula gives it."""
        if self.tied:
            return 0.0
        both = isinstance(self.hi, float) and isinstance(self.lo, float)
        return self.hi - self.lo if both else self.hi


@dataclass(frozen=True)
class SummaryValues:
    outputs: dict[str, OutputExtremes]   # by output name, in Table order
    spans: tuple[float | str, ...]       # the model's spans, in order
    figures: tuple[object, ...]          # the model's figures, in order
    rows: int
    rows_ok: int                         # rows in the extremes
    rows_not_assembled: int
    flagged: dict[str, int]              # rows flagged, by status text (sorted)

    @property
    def rows_flagged(self) -> int:
        return sum(self.flagged.values())


def _output(found: Extremes, tie: float) -> OutputExtremes:
    if not found.counted[0]:
        return OutputExtremes(NONE_OK, NONE_OK, NONE_OK, NONE_OK, tie, False)
    hi, at_hi = float(found.hi[0]), float(found.hi_at[0])
    lo, at_lo = float(found.lo[0]), float(found.lo_at[0])
    if hi - lo <= tie:
        return OutputExtremes(hi, TIE, lo, TIE, tie, True)
    return OutputExtremes(hi, at_hi, lo, at_lo, tie, False)


def summary_values(table: Table, extremes: dict[str, Extremes]) -> SummaryValues:
    """``extremes``: each output's (``extremes.output_extremes``)."""
    shared = scope(table.columns, table.params, table.rows)  # outputs share subtrees
    outputs = table.model.outputs()
    shared.measure(tuple(q.expr for q in outputs))
    found = {q.name: _output(extremes[q.name], tie_threshold(table, q.name, shared))
             for q in outputs}
    figures = tuple(cached_values(compile_numpy(f.expr)({}, table.params, 1))[0]
                    for f in table.model.figures)
    status = table.status
    texts = sorted({t for t in status if t not in (STATUS_OK, CANNOT_ASSEMBLE)})
    return SummaryValues(
        found, tuple(found[s.quantity].span for s in table.model.spans), figures,
        table.rows, int(np.sum(ok_rows(status))), int(np.sum(status == CANNOT_ASSEMBLE)),
        {t: int(np.sum(status == t)) for t in texts})
