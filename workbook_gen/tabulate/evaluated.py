"""A scene evaluated: the Table's columns, and on first use everything else a workbook
shows (the Checks' residuals, the design conditions, the extremes and the Summary).

``evaluate`` computes the Table's columns at once; the rest is computed when first read
and kept (``functools.cached_property``), so a caller that needs the columns only (the
tradeoff's studies, ``compute``) does not pay for the residuals.
"""

from __future__ import annotations

from functools import cached_property

from ..scene import Scene
from .checks import CheckValues, Conditions, check_values, condition_values
from .extremes import Extremes, output_extremes
from .summary import SummaryValues, summary_values
from .table import Table, derived_cells, evaluate_table


class Evaluated(Table):
    """Everything the workbook of one scene shows, computed; ``workbook/`` lays it out."""

    @cached_property
    def derived(self) -> dict[str, object]:
        """The derived values' cells on the Parameters sheet, by name."""
        return derived_cells(self)

    @cached_property
    def checks(self) -> CheckValues:
        return check_values(self)

    @cached_property
    def conditions(self) -> Conditions:
        return condition_values(self)

    @cached_property
    def extremes(self) -> dict[str, Extremes]:
        """Each output's extremes over the ok rows (``extremes.ok_extremes``)."""
        return output_extremes(self)

    @cached_property
    def summary(self) -> SummaryValues:
        return summary_values(self, self.extremes)


def evaluate(scene: Scene) -> Evaluated:
    """Every column of the scene's Table; refuses a sweep where nothing assembles."""
    return evaluate_table(scene, Evaluated)
