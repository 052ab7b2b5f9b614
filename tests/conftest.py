"""Shared pytest fixtures.

The tests mirror the package (tests/<package>/test_<module>.py, each folder a package so
that two folders may hold test files of one name); the helpers they share
(corpus_audits.py, lo_sheet.py, mp_reference.py...) sit at the top of tests/, which is
put on the import path here.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

_TESTS = str(Path(__file__).resolve().parent)
if _TESTS not in sys.path:
    sys.path.insert(0, _TESTS)

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


@pytest.fixture(scope="session")
def corpus_audits():
    """{file name: Outcome} for every workbook of ../shared/corpus/xlsx, audited once."""
    from corpus_audits import CORPUS, audit_corpus
    if not CORPUS.is_dir():
        pytest.fail(f"the corpus is missing: {CORPUS} (see /work/shared/corpus/README.md)",
                    pytrace=False)
    return audit_corpus()
