"""The mechanism templates, by id.

A template module builds its expression trees when imported; ``TEMPLATES``
imports a template's module the first time the template is asked for, so a
command that uses one template (``generate``) or none (``--version``) does not
build them all."""

from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING, Iterator, Mapping

from ..errors import SceneError

if TYPE_CHECKING:
    from .base import Template

# id -> module, in the order ``workbook-gen list`` shows them
_MODULES = {
    "slider_crank": "slider_crank",
    "sewing_machine": "sewing_machine",
    "actuator_linkage": "actuator_linkage",
    "five_bar": "five_bar",
    "four_bar": "four_bar",
    "walking_beam": "walking_beam",
    "parallel_4dof": "parallel_4dof",
}


class _Templates(Mapping[str, "Template"]):
    """A read-only mapping id -> Template that imports each template on first use."""

    def __getitem__(self, template_id: str) -> "Template":
        module = _MODULES[template_id]  # KeyError for an unknown id, as a dict
        return import_module(f"{__name__}.{module}").TEMPLATE

    def __iter__(self) -> Iterator[str]:
        return iter(_MODULES)

    def __len__(self) -> int:
        return len(_MODULES)

    def __contains__(self, template_id: object) -> bool:
        return template_id in _MODULES


TEMPLATES: Mapping[str, "Template"] = _Templates()


def get_template(template_id: str) -> "Template":
    try:
        return TEMPLATES[template_id]
    except KeyError:
        raise SceneError(f"unknown mechanism {template_id!r}; known: "
                         + ", ".join(sorted(TEMPLATES))) from None
