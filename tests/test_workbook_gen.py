"""workbook_gen/__init__.py: the package face. compute, load_scene and write_workbook are
imported on first use (so that ``import workbook_gen`` and ``audit`` need no pandas);
batch and audit hand their arguments on unchanged. References: the modules' own
functions (identity), a fresh interpreter's sys.modules, pyproject.toml's version,
the signature of batching.batch (inspect), and a disagreement planted with XlsxWriter."""

from __future__ import annotations

import inspect
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

import workbook_gen
from workbook_gen import auditor, batching

from planted import planted_book

ROOT = Path(__file__).resolve().parent.parent


def test_importing_the_package_imports_no_pandas():
    code = ("import sys, workbook_gen; workbook_gen.audit; workbook_gen.batch; "
            "print('pandas' in sys.modules, 'workbook_gen.tabulate' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, check=True, env={"PYTHONPATH": str(ROOT), "PATH": ""})
    assert out.stdout.split() == ["False", "False"]


def test_the_lazy_names_are_the_modules_functions():
    from workbook_gen.scene import load_scene
    from workbook_gen.tabulate import compute
    from workbook_gen.workbook import write_workbook
    assert workbook_gen.load_scene is load_scene
    assert workbook_gen.compute is compute
    assert workbook_gen.write_workbook is write_workbook
    assert "compute" in vars(workbook_gen)  # kept once looked up
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        workbook_gen.nothing  # noqa: B018
    assert set(workbook_gen.__all__) <= set(dir(workbook_gen)) | {"compute", "load_scene",
                                                                  "write_workbook"}


def test_the_version_is_the_packages():
    with open(ROOT / "pyproject.toml", "rb") as f:
        assert workbook_gen.__version__ == tomllib.load(f)["project"]["version"]
    assert issubclass(workbook_gen.WorkbookGenError, Exception)


def test_batch_hands_every_argument_on_in_its_place(monkeypatch):
    seen, signature = {}, inspect.signature(batching.batch)

    def fake(*args, **kwargs):
        seen.update(signature.bind(*args, **kwargs).arguments)
        return "summary"
    monkeypatch.setattr(batching, "batch", fake)
    result = workbook_gen.batch("s.toml", {"l": [1, 2]}, "d.csv", "o", 3, "client", True,
                                step=5.0, seed=7)
    assert result == "summary"
    assert seen == {"scene": "s.toml", "vary": {"l": [1, 2]}, "design": "d.csv", "out": "o",
                    "jobs": 3, "client": "client", "summary_only": True, "step": 5.0,
                    "seed": 7}
    seen.clear()
    workbook_gen.batch("s.toml", out="x", summary_only=True)
    assert seen["out"] == "x" and seen["summary_only"] is True and seen["vary"] is None


def test_audit_is_the_auditors(tmp_path):
    path = planted_book(tmp_path / "p.xlsx")   # S!B3 =A1+A2 cached 99, recomputed 5
    report = workbook_gen.audit(path)
    assert [(m.cell, m.cached, m.recomputed) for m in report.mismatches] == [("S!B3", 99, 5)]
    assert report.formula_cells == auditor.audit(path).formula_cells == 6
    with pytest.raises(TypeError):
        workbook_gen.audit(path, no_such_option=1)
