"""Everything a scene's workbook shows, computed with numpy (``workbook/`` lays it out):

- ``table``: the Table's columns and status texts, the parameters, ``compute()``;
- ``checks``: the Checks' residuals (with the terms they share, ``terms``), flags,
  maxima, verdicts, and the design conditions;
- ``extremes``: extremes over the ok rows, the one rule of the Summary, the batch summary
  and the tradeoff;
- ``summary``: the Summary's values (extremes or ties, spans, figures, row counts);
- ``evaluated``: ``evaluate(scene)``, the result that holds them all.
"""

from .evaluated import Evaluated, evaluate
from .table import STATUS_OK, compute, derived_values, headers

__all__ = ["Evaluated", "evaluate", "compute", "derived_values", "headers", "STATUS_OK"]
