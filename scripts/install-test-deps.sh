#!/usr/bin/env bash
# Install what the test suite needs: LibreOffice Calc (the engine the tests recalculate
# workbooks with) when soffice is missing, then this package with its test extras.
# Idempotent; non-interactive (works with CI=true and no stdin). Debian/Ubuntu (apt-get).
set -euo pipefail
cd "$(dirname "$0")/.."

have_soffice() {
    command -v soffice >/dev/null 2>&1 || command -v libreoffice >/dev/null 2>&1 \
        || [ -x /usr/lib/libreoffice/program/soffice ]
}

if have_soffice; then
    echo "LibreOffice found: $(command -v soffice || command -v libreoffice || echo /usr/lib/libreoffice/program/soffice)"
else
    if ! command -v apt-get >/dev/null 2>&1; then
        echo "LibreOffice (soffice) is missing and apt-get is not available: install LibreOffice Calc by hand" >&2
        exit 1
    fi
    SUDO=""
    if [ "$(id -u)" -ne 0 ]; then
        SUDO="sudo -n"
    fi
    echo "Installing LibreOffice Calc with apt-get"
    $SUDO apt-get update </dev/null
    $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
        libreoffice-calc </dev/null
    if ! have_soffice; then
        echo "libreoffice-calc installed but soffice is still not found" >&2
        exit 1
    fi
fi

# poppler-utils: pdftotext reads the PDF that LibreOffice prints (tests/test_printing.py)
if ! command -v pdftotext >/dev/null 2>&1; then
    if ! command -v apt-get >/dev/null 2>&1; then
        echo "pdftotext is missing and apt-get is not available: install poppler-utils by hand" >&2
        exit 1
    fi
    SUDO=""
    if [ "$(id -u)" -ne 0 ]; then
        SUDO="sudo -n"
    fi
    echo "Installing poppler-utils with apt-get"
    $SUDO apt-get update </dev/null
    $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
        poppler-utils </dev/null
fi

PYTHON="${PYTHON:-python}"
"$PYTHON" -m pip install -e '.[test]' </dev/null
