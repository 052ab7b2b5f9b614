"""docs/functions.md is the registry's own description, current (issue 23 item 5)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from workbook_gen.formula.functions import REGISTRY
from workbook_gen.formula.functions.catalog import markdown

ROOT = Path(__file__).resolve().parents[3]


def test_functions_doc_is_current():
    done = subprocess.run([sys.executable, "scripts/functions_doc.py", "--check"], cwd=ROOT,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_every_registered_function_has_a_row_with_its_arity():
    text = markdown(ROOT)
    for name, f in REGISTRY.items():
        row = next(l for l in text.splitlines() if l.startswith(f"| `{name}` |"))
        cells = [c.strip() for c in row.strip("|").split("|")]
        assert cells[1] == f.family
        low = int(cells[3].split("-")[0].rstrip("+"))
        assert low == f.min_args, (name, cells[3])
