"""Prune a template to what a scene requires: the requested outputs and what they need.

The columns are the requested quantities and everything their trees refer to,
transitively (read off the trees with ``variables``), in the template's order,
plus what the status column needs.  Checks, charts and summary rows are kept
only when every column they refer to is present.
"""

from __future__ import annotations

from dataclasses import dataclass

from .expr import Node, variables
from .mechanisms.base import Chart, Check, Condition, Figure, Quantity, Span, Template


@dataclass(frozen=True)
class Model:
    template: Template
    requested: tuple[str, ...]
    columns: tuple[Quantity, ...]   # Table columns after the input, before the status
    checks: tuple[Check, ...]
    charts: tuple[Chart, ...]
    spans: tuple[Span, ...]
    figures: tuple[Figure, ...]
    status: Node                    # the status column's tree for these columns
    conditions: tuple[Condition, ...] = ()

    @property
    def names(self) -> tuple[str, ...]:
        """Every column name, input first (without the status)."""
        return (self.template.input.name,) + tuple(q.name for q in self.columns)

    def outputs(self) -> tuple[Quantity, ...]:
        """The columns the scene asked for, in Table order."""
        return tuple(q for q in self.columns if q.name in self.requested)


def needed(template: Template, roots: set[str]) -> set[str]:
    """``roots`` and every quantity their trees refer to, transitively."""
    by_name = {q.name: q for q in template.quantities}
    seen: set[str] = set()
    stack = list(roots)
    while stack:
        name = stack.pop()
        if name in seen or name not in by_name:
            continue
        seen.add(name)
        stack.extend(variables(by_name[name].expr))
    return seen


def select(template: Template, requested: tuple[str, ...]) -> Model:
    status = (template.status if template.status_for is None
              else template.status_for(frozenset(needed(template, set(requested)))))
    keep = needed(template, set(requested) | variables(status))
    columns = tuple(q for q in template.quantities if q.name in keep)
    present = keep | {template.input.name}
    return Model(
        template=template,
        requested=tuple(requested),
        columns=columns,
        checks=tuple(c for c in template.checks if variables(c.expr) <= present),
        charts=tuple(c for c in template.charts
                     if _chart_wanted(c, template, present, set(requested))),
        spans=tuple(s for s in template.spans if s.quantity in requested),
        figures=tuple(f for f in template.figures if _shown(f.needs, present)),
        status=status,
        conditions=tuple(c for c in template.conditions if _shown(c.needs, present)),
    )


def _shown(needs: tuple[str, ...], present: set[str]) -> bool:
    """A figure or condition about some columns is shown when one of them is."""
    return not needs or bool(set(needs) & present)


def _chart_wanted(chart: Chart, template: Template, present: set[str],
                  requested: set[str]) -> bool:
    """Drawn when its columns are present and it shows a requested quantity or an
    intermediate one (the path of the sewing machine's E) that the outputs need."""
    shown = {chart.x, *chart.ys} - {template.input.name}
    if not shown <= present:
        return False
    return any(n in requested or not template.quantity(n).output for n in shown)
