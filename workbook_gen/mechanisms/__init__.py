"""The mechanism templates, by id."""

from __future__ import annotations

from ..errors import SceneError
from .base import Template
from .sewing_machine import TEMPLATE as _SEWING
from .slider_crank import TEMPLATE as _SLIDER

TEMPLATES: dict[str, Template] = {t.id: t for t in (_SLIDER, _SEWING)}


def get_template(template_id: str) -> Template:
    try:
        return TEMPLATES[template_id]
    except KeyError:
        raise SceneError(f"unknown mechanism {template_id!r}; known: "
                         + ", ".join(sorted(TEMPLATES))) from None
