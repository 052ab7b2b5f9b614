"""Centres of mass, shaking force and moment (SPEC 7.7): being built."""

from __future__ import annotations

from ..errors import SceneError


def add_dynamics(template, masses, options):
    raise SceneError(f"{template.id}: [masses] is not supported yet")
