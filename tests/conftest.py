"""Shared pytest fixtures."""

from __future__ import annotations

import pytest

from workbook_gen.engines.libreoffice import find_soffice


@pytest.fixture(scope="session")
def libreoffice() -> str:
    """Path of soffice; fails (never skips) when LibreOffice is missing."""
    path = find_soffice()
    if path is None:
        pytest.fail("LibreOffice is required: run bash scripts/install-test-deps.sh", pytrace=False)
    return path


@pytest.fixture(scope="session")
def generate(tmp_path_factory):
    """generate(scene_path, **load_scene options) -> path of a freshly written workbook."""
    from workbook_gen.scene import load_scene
    from workbook_gen.workbook import write_workbook

    def make(scene_path: str = "templates/sewing_machine.toml", **options):
        scene = load_scene(scene_path, **options)
        return write_workbook(scene, tmp_path_factory.mktemp("wb"))
    return make


@pytest.fixture(scope="session")
def sewing_workbook(generate):
    return generate()
