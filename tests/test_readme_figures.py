"""The README's measured figures are what scripts/readme_figures.py makes of the committed
tradeoff and benchmark output, and its list of `audit --json` keys is what an audit prints
(issue 12 item 12): they cannot drift.  The renderer is checked on fixture records (targets
reached or not, load, missing CPU times), and --measure-bench's path (a benchmark's --json
file rendered) end to end on small sizes."""

from __future__ import annotations

import copy
import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def _script():
    spec = importlib.util.spec_from_file_location("readme_figures",
                                                  ROOT / "scripts" / "readme_figures.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def figures():
    return _script()


def _record(figures: dict, load: float = 0.3) -> dict:
    return {"command": "python bench/x.py",
            "machine": {"cpu": "Test CPU", "cores": 2, "arch": "x86_64", "system": "Linux 6",
                        "python": "3.11.7", "libreoffice": "7.4.7.2",
                        "packages": {"XlsxWriter": "3.3.1"}},
            "run": {"started": "2026-11-23T18:00:00Z", "finished": "2026-11-23T18:05:00Z",
                    "load_start": load, "load_end": load},
            "figures": figures}


GENERATE = {"scene": "templates/sewing_machine.toml",
            "steps": [{"step": 10.0, "rows": 37, "cells": 1036, "seconds": 0.06, "cpu": 0.05,
                       "numpy": 0.008, "numpy_cpu": 0.008, "worst_error": 1e-15},
                      {"step": 0.1, "rows": 3601, "cells": 100828, "seconds": 1.6, "cpu": 1.2,
                       "numpy": 0.02, "numpy_cpu": 0.02, "worst_error": 1.7e-15}],
            "per_variant": {"variants": 50, "workbook_ms": 56.0, "workbook_cpu_ms": 50.0,
                            "numpy_ms": 7.5, "numpy_cpu_ms": 7.0}}


def _peer(total, status="ok", cpu=None):
    return {"phases": {"total": total} if total else {}, "total": total, "cells": 100,
            "status": status, "note": "", "cpu": cpu}


AUDIT = {"scene": "templates/sewing_machine.toml", "repeat": 1, "timeout": 600,
         "only": "lo-formualizer",
         "steps": [{"step": 0.1, "rows": 3601, "cells": 201747, "ours_eval": 0.7, "ours_cpu": 2.0,
                    "ours_ok": True, "numpy": 0.02,
                    "ours_timings": {"read": 1.0, "evaluate": 0.7, "compare": 0.2},
                    "ours": _peer(2.0), "lo": _peer(9.0, cpu=8.0), "formualizer": _peer(1.9),
                    "formulas": _peer(None, "failed"), "pycel": _peer(None, "failed")}]}

BATCH = {"scene": "templates/sewing_machine.toml", "jobs": 2,
         "files": {"variants": 1000, "seconds": 19.0, "cpu": 36.0, "loop_seconds": 38.0},
         "summary_only": {"variants": 100000, "seconds": 12.0, "peak_mb": 500.0,
                          "worker_peak_mb": 300.0, "cpu": 8.0, "worker_cpu": 9.0,
                          "columns": 71},
         "dask": {"variants": 1000, "workers": 2, "seconds": 26.0, "jobs_before": 19.0,
                  "jobs_after": 21.0}}


def test_readme_blocks_equal_what_the_script_makes_of_the_committed_data(figures):
    text = figures.README.read_text(encoding="utf-8")
    data, bench = figures.load(), figures.load_bench()
    assert set(data) == set(figures.SCENES), sorted(data)
    assert set(bench) == set(figures.BENCHES), sorted(bench)
    blocks = figures.BLOCK.findall(text)
    assert {b[2] for b in blocks if b[1] == "tradeoff"} == set(figures.SCENES)
    kinds = {b[1] for b in blocks}
    assert {"runtime", "audit-json", "advice", "newton", "bench-machine", "bench-generate",
            "bench-audit", "bench-read", "bench-batch", "bench-batch-notes"} <= kinds
    assert figures.render(text, data, bench) == text, (
        "README.md is out of date: run python scripts/readme_figures.py")


def test_a_changed_figure_is_caught(figures):
    text = figures.README.read_text(encoding="utf-8")
    data, bench = figures.load(), figures.load_bench()
    changed = copy.deepcopy(data)
    changed["sewing_machine"]["rows"][0]["cells"] += 1
    assert figures.render(text, changed, bench) != text
    changed = copy.deepcopy(bench)
    changed["batch"]["figures"]["files"]["seconds"] *= 1.5
    assert figures.render(text, data, changed) != text


def test_targets_are_computed_from_the_data(figures):
    fb = figures.figures_bench
    quiet = fb.generate_block(_record(GENERATE))
    assert "quiet machine" in quiet and "judged on the wall time: **not reached**" in quiet
    loaded = fb.generate_block(_record(GENERATE, load=3.2))
    assert "measured under load 3.2" in loaded
    assert "judged on the CPU time: **reached**" in loaded  # 1.2 s CPU <= 1.5 s

    audit = fb.audit_block(_record(AUDIT))
    assert "4.5x, **reached**" in audit                    # 9.0 / 2.0 >= 4
    assert "2 s against 1.9 s, **not reached**" in audit   # slower than formualizer
    assert "`formulas`" not in audit and "read is the largest" in audit
    faster = copy.deepcopy(AUDIT)
    faster["steps"][0]["lo"] = _peer(7.0)
    assert "3.5x, **not reached**" in fb.audit_block(_record(faster))
    faster["steps"][0]["rounds"] = [[2.0, 1.9], [2.1, 2.4], [1.8, 2.5]]
    assert "ours took less time in 2 of the 3 rounds run in turn" in \
        fb.audit_block(_record(faster))

    batch = fb.batch_block(_record(BATCH))
    assert "<= 20 s: reached" in batch and ">= 1.7x: reached" in batch   # 19 s, 2.00x
    assert "<= 10 s: not reached; >= 200x: not reached" in batch        # 12 s, 158x
    assert "<= 1 GB: reached" in batch and "1.30x the time" in batch
    assert "<= 1.3x: reached" in batch                                  # 26 / 20
    assert "(wall time, under load)" in fb.batch_block(_record(BATCH, load=4.0))
    small = copy.deepcopy(BATCH)
    small["files"]["variants"] = 20
    assert "for 1,000 variants: not assessed" in fb.batch_block(_record(small))
    notes = fb.batch_notes_block(_record(BATCH), _record(GENERATE))
    assert "50 ms" in notes and "take 25 s" in notes  # 1000 x 50 ms / 2 cores
    assert "the workers' evaluation is the larger part" in notes


CORPUS = {"files": 76, "fully": 66, "cells": 57344, "evaluated": 56849,
          "classes": {"pass": 70, "disagreements": 6},
          "not_fully": {"a.xlsx": {"class": "pass", "formula_cells": 9, "evaluated": 8,
                                   "disagree": 0}},
          "line": "coverage: 66 of 76 files fully audited, 56849 of 57344 formula cells "
                  "evaluated (99.1%)"}


def test_corpus_targets_are_computed_from_the_data(figures):
    fb = figures.figures_bench
    block = fb.corpus_block(_record(CORPUS))
    assert "(87%; target 90%: not reached)" in block           # 66 / 76
    assert "(99.1%; target 95%: reached)" in block
    assert "- `a.xlsx`: 8 of 9 formula cells recomputed, 0 disagree" in block
    more = copy.deepcopy(CORPUS)
    more["fully"] = 69
    assert "(91%; target 90%: reached)" in fb.corpus_block(_record(more))


def test_corpus_bench_reads_coverage_output():
    spec = importlib.util.spec_from_file_location("bench_corpus", ROOT / "bench" / "corpus.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    results = {"a.xlsx": {"class": "pass", "fully": True, "formula_cells": 3, "evaluated": 3},
               "b.xlsx": {"class": "disagreements", "fully": False, "formula_cells": 5,
                          "evaluated": 4, "mismatches": 2}}
    f = module.figures(results, "coverage: 1 of 2 files fully audited, 7 of 8 formula cells "
                                "evaluated (87.5%)\n")
    assert (f["fully"], f["files"], f["evaluated"], f["cells"]) == (1, 2, 7, 8)
    assert f["classes"] == {"pass": 1, "disagreements": 1}
    assert list(f["not_fully"]) == ["b.xlsx"] and f["not_fully"]["b.xlsx"]["disagree"] == 2
    with pytest.raises(SystemExit):
        module.figures(results, "something else")


def test_advice_follows_the_data(figures):
    fa = figures.figures_advice
    data = figures.load()
    advice = fa.advice_block(data, figures.LABELS)
    steps = [r for r in data["sewing_machine"]["rows"] if r["dimension"] == "step"]
    # the coarsest step within 1e-2, as the tier says
    coarsest = next(r for r in steps if r["max_error"] <= 1e-2)
    assert f"*Quick look, charts, design iterations*: {coarsest['setting'].split()[0]}°" in advice
    changed = copy.deepcopy(data)
    for r in changed["sewing_machine"]["rows"]:
        if r["dimension"] == "step":
            r["max_error"] /= 1000  # every step 1000x more accurate: 10 deg reaches 1e-4
            r["cpu_seconds"] = 0.5
    advice = fa.advice_block(changed, figures.LABELS)
    assert "*Quick look, charts, design iterations*: 10° (0.5 s CPU" in advice
    assert "or better the coarse table plus a local refinement" in advice
    worse = copy.deepcopy(data)
    for r in worse["sewing_machine"]["rows"]:
        if r["dimension"] == "step":
            r["max_error"] = 0.5 * float(r["setting"].split()[0])  # never within 1e-2
    advice = fa.advice_block(worse, figures.LABELS)
    assert advice.count("no step of the table reaches it") == 3
    assert ": use a coarse table plus a local refinement" in advice
    # five-bar without its flagged rows: the Newton sentence says so
    five = copy.deepcopy(data["five_bar"])
    for r in five["rows"]:
        r["note"] = ""
    assert "the audit flags none" in fa.newton_block(five)


def test_measure_bench_writes_json_that_renders(figures, tmp_path):
    """--measure-bench's path on small sizes: read_xlsx and generate write their --json,
    the blocks render from them (the machine and the load are recorded)."""
    figures.measure_bench(tmp_path, figures.QUICK, names=["read_xlsx", "generate"])
    bench = figures.load_bench(tmp_path)
    assert set(bench) == {"read_xlsx", "generate"}
    for record in bench.values():
        assert record["machine"]["cores"] >= 1 and record["machine"]["python"]
        assert record["run"]["load_start"] is not None and "--json" not in record["command"]
    read = figures.figures_bench.read_block(bench["read_xlsx"])
    assert "200 x 30 workbook" in read
    generate = figures.figures_bench.generate_block(bench["generate"])
    assert "| 1° | 361 | 11,552 |" in generate and "not measured in this run" in generate
    json.dumps(bench)  # plain JSON


def test_bench_json_refuses_a_missing_folder(tmp_path):
    done = subprocess.run([sys.executable, "bench/read_xlsx.py", "--rows", "10", "--json",
                           str(tmp_path / "no" / "x.json")], cwd=ROOT, capture_output=True,
                          text=True)
    assert done.returncode == 2 and "no such folder" in done.stderr
    assert not (tmp_path / "no").exists()
