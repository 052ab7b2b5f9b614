"""The mechanism templates, by id."""

from __future__ import annotations

from ..errors import SceneError
from .actuator_linkage import TEMPLATE as _ACTUATOR
from .base import Template
from .five_bar import TEMPLATE as _FIVE_BAR
from .four_bar import TEMPLATE as _FOUR_BAR
from .parallel_4dof import TEMPLATE as _PARALLEL_4DOF
from .sewing_machine import TEMPLATE as _SEWING
from .slider_crank import TEMPLATE as _SLIDER
from .walking_beam import TEMPLATE as _WALKING_BEAM

TEMPLATES: dict[str, Template] = {t.id: t for t in (_SLIDER, _SEWING, _ACTUATOR, _FIVE_BAR,
                                                  _FOUR_BAR, _WALKING_BEAM, _PARALLEL_4DOF)}


def get_template(template_id: str) -> Template:
    try:
        return TEMPLATES[template_id]
    except KeyError:
        raise SceneError(f"unknown mechanism {template_id!r}; known: "
                         + ", ".join(sorted(TEMPLATES))) from None
