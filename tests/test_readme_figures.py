"""The README's measured figures are what scripts/readme_figures.py makes of the committed
tradeoff output, and its list of `audit --json` keys is what an audit prints (issue 12
item 12): they cannot drift."""

from __future__ import annotations

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _script():
    spec = importlib.util.spec_from_file_location("readme_figures",
                                                  ROOT / "scripts" / "readme_figures.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_readme_blocks_equal_what_the_script_makes_of_the_committed_data():
    figures = _script()
    text = figures.README.read_text(encoding="utf-8")
    data = figures.load()
    assert set(data) == set(figures.SCENES), sorted(data)
    blocks = figures.BLOCK.findall(text)
    assert {b[2] for b in blocks if b[2]} == set(figures.SCENES)
    assert any(b[1] == "runtime" for b in blocks) and any(b[1] == "audit-json" for b in blocks)
    assert figures.render(text, data) == text, (
        "README.md is out of date: run python scripts/readme_figures.py")


def test_a_changed_figure_is_caught():
    figures = _script()
    text = figures.README.read_text(encoding="utf-8")
    data = figures.load()
    data["sewing_machine"]["rows"][0]["cells"] += 1
    assert figures.render(text, data) != text
