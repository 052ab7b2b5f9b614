"""Four-bar linkage with a coupler point (docs/mechanisms.md, four_bar); the trees live in
fourbar_core.

Defaults: Norton's example 100/40/120/80 (ground, crank, coupler, rocker), for
which theta_2 = 40 deg gives theta_3 = 20.30 deg, theta_4 = 57.32 deg on the
open branch; coupler point C at 60 from A, 30 deg from A->B; omega_2 = 10 rad/s.
Option ``branch``: "open" (B left of the directed line A->O2) or "crossed".
Option ``balance`` (with ``[masses]``): counterweights on crank and rocker for full
shaking-force balance; they need the masses, so dynamics.add_dynamics adds them (balance.py).
"""

from __future__ import annotations

import dataclasses
from typing import Mapping

from . import fourbar_core as core
from .base import InputSpec, OptionSpec, Span, Template


def _configure(template: Template, options: Mapping[str, object]) -> Template:
    branch = str(options["branch"])
    return dataclasses.replace(template, quantities=core.quantities(branch),
                               figures=core.figures(branch))


TEMPLATE = Template(
    id="four_bar",
    title="Four-bar linkage with a coupler point",
    description="Crank O1A, coupler AB with coupler point C, rocker O2B; open or crossed "
                "branch; transmission angle, Grashof class, toggle positions, time ratio.",
    input=InputSpec("theta_2", "deg", "crank angle"),
    parameters=core.parameters((100.0, 40.0, 120.0, 80.0, 60.0), 30.0, 10.0),
    quantities=core.quantities("open"),
    derived=core.DERIVED,
    status=core.STATUS,
    checks=core.checks(),
    charts=core.charts(),
    spans=(Span("rocker swing", "theta_4"), Span("coupler swing", "theta_3"),
           Span("coupler point, x range", "x_C"), Span("coupler point, y range", "y_C")),
    figures=core.figures("open"),
    options=(OptionSpec("branch", "open", "assembly: open (B left of the directed line "
                        "A->O2, Norton) or crossed", choices=core.BRANCHES),
             OptionSpec("balance", False, "with [masses]: counterweights on crank and rocker "
                        "that balance the shaking force fully (Berkof-Lowen)")),
    links=core.links(),
    length_unit_m=1e-3,
    configure=_configure,
    assembly_failure=core.why_not,
)
