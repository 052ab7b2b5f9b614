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
