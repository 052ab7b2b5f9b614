#!/usr/bin/env bash
# Install what the test suite needs: LibreOffice Calc (the engine the tests recalculate
# workbooks with) and poppler-utils (pdftotext reads the PDF LibreOffice prints, in
# tests/workbook/test_layout.py) when they are missing, then this package with its test extras
# (pytest, hypothesis, dask and distributed). Idempotent; non-interactive (works with CI=true
# and no stdin). Debian/Ubuntu (apt-get).
set -euo pipefail
cd "$(dirname "$0")/.."

have_soffice() {
    command -v soffice >/dev/null 2>&1 || command -v libreoffice >/dev/null 2>&1 \
        || [ -x /usr/lib/libreoffice/program/soffice ]
}

have_pdftotext() {
    command -v pdftotext >/dev/null 2>&1
}

APT_UPDATED=""

# ensure CHECK PACKAGE: install the Debian package PACKAGE with apt-get unless CHECK succeeds.
ensure() {
    local check="$1" package="$2"
    if "$check"; then
        return 0
    fi
    if ! command -v apt-get >/dev/null 2>&1; then
        echo "$package is missing and apt-get is not available: install it by hand" >&2
        exit 1
    fi
    local sudo=""
    if [ "$(id -u)" -ne 0 ]; then
        sudo="sudo -n"
    fi
    echo "Installing $package with apt-get"
    if [ -z "$APT_UPDATED" ]; then
        $sudo apt-get update </dev/null
        APT_UPDATED=1
    fi
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
        "$package" </dev/null
    if ! "$check"; then
        echo "$package installed but still not found" >&2
        exit 1
    fi
}

ensure have_soffice libreoffice-calc
ensure have_pdftotext poppler-utils

PYTHON="${PYTHON:-python}"
"$PYTHON" -m pip install -e '.[test]' </dev/null
