"""The audit on the real-world corpus, as the corpus's own ``coverage.py`` measures it.

Runs ``/work/shared/corpus/coverage.py`` (or the one in ``--corpus DIR``) over the
``workbook-gen`` on PATH, one audit at a time by default (two at once can push
formulas__test.xlsx past coverage.py's 120 s per file on a loaded machine), and prints its
last line. ``--json FILE`` also writes the figures the README quotes (files fully audited,
formula cells evaluated, the files per class and, for each file not fully audited, its
counts), with the machine and the load (bench/benchinfo.py).

    python bench/corpus.py [--corpus DIR] [--jobs 1] [--json docs/bench/corpus.json]
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
import benchinfo  # noqa: E402

CORPUS = Path("/work/shared/corpus")  # as the tests (tests/corpus_audits.py)
LAST = re.compile(r"coverage: (\d+) of (\d+) files fully audited, (\d+) of (\d+) formula cells")


def figures(results: dict, last_line: str) -> dict:
    """What the README quotes, from coverage.py's per-file JSON and its last line."""
    match = LAST.search(last_line)
    if match is None:
        raise SystemExit(f"coverage.py's last line is not its coverage line: {last_line!r}")
    fully, files, evaluated, cells = map(int, match.groups())
    classes: dict[str, int] = {}
    for r in results.values():
        classes[r["class"]] = classes.get(r["class"], 0) + 1
    short = {name: {"class": r["class"], "formula_cells": r["formula_cells"],
                    "evaluated": r["evaluated"], "disagree": r.get("mismatches", 0)}
             for name, r in sorted(results.items()) if not r["fully"]}
    return {"files": files, "fully": fully, "cells": cells, "evaluated": evaluated,
            "classes": classes, "not_fully": short, "line": last_line.strip()}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--corpus", type=Path, default=CORPUS,
                        help=f"the folder of coverage.py and xlsx/ (default {CORPUS})")
    parser.add_argument("--jobs", type=int, default=1, help="audits at once (default 1)")
    parser.add_argument("--json", metavar="FILE", help="also write the figures to FILE")
    args = parser.parse_args()
    benchinfo.check_writable(args.json)
    script = args.corpus / "coverage.py"
    if not script.is_file():
        print(f"no coverage.py in {args.corpus} (give the corpus folder with --corpus)",
              file=sys.stderr)
        return 2
    exe = shutil.which("workbook-gen")
    if exe is None:
        print("workbook-gen is not on PATH (pip install -e . first)", file=sys.stderr)
        return 2
    record = benchinfo.Record()
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "coverage.json"
        done = subprocess.run([sys.executable, str(script), exe, "--jobs", str(args.jobs),
                               "--budget", "1800", "--json", str(out)],
                              capture_output=True, text=True, check=True)
        results = json.loads(out.read_text(encoding="utf-8"))["files"]
    last = done.stdout.strip().splitlines()[-1]
    print(last)
    if args.json:
        record.write(args.json, figures(results, last))
    return 0


if __name__ == "__main__":
    sys.exit(main())
