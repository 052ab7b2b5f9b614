"""Walking beam: the eight-bar transport mechanism (docs/mechanisms.md, walking_beam).

A crank-rocker four-bar (the trees of fourbar_core, same conventions as
four_bar) traces the coupler curve of C.  An identical four-bar, its ground
pivots shifted by l_CD along +x and its crank driven in phase with the first
(the parallelogram), traces the same curve shifted, so its coupler point
D = C + (l_CD, 0).  The beam 7, pinned at C and D, therefore translates: every
point of it has C's velocity and acceleration.

Defaults: Hoekens' straight-line linkage, crank 1, coupler 2.5, rocker 2.5,
ground 2, coupler point on the line A->B extended at 5 from A (l_AC = 5,
delta_C = 0), scaled by 20 mm (crank 20 mm).  On the open branch C runs along
the nearly straight line y_C = 4 * 20 = 80 mm while the crank turns from 90 to
270 deg (C from x = 80 to x = 0 mm, the flat stroke that carries the load),
then lifts on the return.
"""

from __future__ import annotations

import dataclasses
from typing import Mapping

from ..expr import Node, sqrt, wrap
from . import fourbar_core as core
from .base import Chart, Check, InputSpec, Link, OptionSpec, ParamSpec, Quantity, Span
from .base import Template, quantity_vars, symbols

(l_CD,) = symbols("l_CD")
x_C, y_C, x_D, y_D = quantity_vars("x_C y_C x_D y_D")

SCALE = 20.0  # mm per unit of Hoekens' proportions
PARAMETERS = core.parameters((2 * SCALE, SCALE, 2.5 * SCALE, 2.5 * SCALE, 5 * SCALE), 0.0,
                             10.0) + (
    ParamSpec("l_CD", 160.0, "mm", "beam CD (the parallelogram's offset along +x)",
              positive=True),
)


def quantities(branch: str) -> tuple[Quantity, ...]:
    beam = (
        Quantity("x_D", "mm", x_C + l_CD, "beam pin D (coupler point of the copy), x"),
        Quantity("y_D", "mm", y_C, "beam pin D (coupler point of the copy), y"),
    )
    return core.quantities(branch) + beam


CHECKS = core.checks() + (
    Check("beam_orientation", "position", sqrt((x_D - x_C - l_CD) ** 2 + (y_D - y_C) ** 2)
          / l_CD, "|D - C - (l_CD, 0)|, over l_CD: the beam keeps its orientation"),
)


def links() -> tuple[Link, ...]:
    """The four-bar's links, the copy's (shifted by l_CD) and the translating beam."""
    zero = wrap(0)
    copy = tuple(dataclasses.replace(link, name=f"{link.name}_copy",
                                     joint=(link.joint[0] + l_CD, link.joint[1]))
                 for link in core.links())
    beam_acc: tuple[Node, Node] = (core.ax_C, core.ay_C)
    return core.links() + copy + (
        Link("beam", (x_C, y_C), beam_acc, zero, zero, zero),)


def _configure(template: Template, options: Mapping[str, object]) -> Template:
    branch = str(options["branch"])
    return dataclasses.replace(template, quantities=quantities(branch),
                               figures=core.figures(branch)[:1])


TEMPLATE = Template(
    id="walking_beam",
    title="Walking beam (eight-bar transport mechanism)",
    description="Hoekens-type crank-rocker with coupler point C, copied by a parallelogram to "
                "D = C + (l_CD, 0); the beam CD translates along the coupler curve.",
    input=InputSpec("theta_2", "deg", "crank angle"),
    parameters=PARAMETERS,
    quantities=quantities("open"),
    derived=core.GAPS + core.GRASHOF,  # the Grashof class is its only figure
    status=core.STATUS,
    checks=CHECKS,
    charts=(
        Chart("Beam path (pin C)", "x_C", ("y_C",), "y_C [mm]", path=True),
        Chart("Beam position", "theta_2", ("x_C", "y_C"), "position of C [mm]"),
        Chart("Beam velocity", "theta_2", ("vx_C", "vy_C"), "v [mm/s]"),
        Chart("Beam acceleration", "theta_2", ("ax_C", "ay_C"), "a [mm/s^2]"),
        Chart("Coupler and rocker angles", "theta_2", ("theta_3", "theta_4"), "angle [deg]"),
        Chart("Angular velocities", "theta_2", ("omega_3", "omega_4"), "omega [rad/s]"),
        Chart("Angular accelerations", "theta_2", ("alpha_3", "alpha_4"), "alpha [rad/s^2]"),
        Chart("Transmission angle", "theta_2", ("mu",), "mu [deg]"),
    ),
    spans=(Span("beam horizontal travel", "x_C"), Span("beam lift", "y_C"),
           Span("rocker swing", "theta_4")),
    figures=core.figures("open")[:1],
    options=(OptionSpec("branch", "open", "assembly of both four-bars: open (B left of the "
                        "directed line A->O2, Norton) or crossed", choices=core.BRANCHES),),
    links=links(),
    length_unit_m=1e-3,
    configure=_configure,
    assembly_failure=core.why_not,
)
