"""Rewrite the README's measured figures from the committed tradeoff and benchmark output,
so the two cannot drift apart.

    python scripts/readme_figures.py                  # rewrite the marked blocks of README.md
    python scripts/readme_figures.py --check          # exit 1 if README.md is not up to date
    python scripts/readme_figures.py --measure        # re-measure the tradeoffs (~20 min)
    python scripts/readme_figures.py --measure --only sewing_machine   # one scene
    python scripts/readme_figures.py --measure-bench  # re-run the benchmarks (~10 min)
    python scripts/readme_figures.py --measure-bench --quick /tmp/q   # check the chain

Before each scene or benchmark, the measuring waits (at most 2 min) for the 1-minute load
average to fall below 1, so that one run's own load is not recorded as the next one's.

The data: ``workbook-gen tradeoff SCENE --json``, one file per scene under docs/tradeoff/
(``--measure`` writes them, with the machine and the load around the run), and the
``--json`` output of bench/generate.py, audit.py, batch.py, read_xlsx.py and corpus.py under
docs/bench/ (``--measure-bench`` writes them).  A block of README.md between
``<!-- figures: KIND [NAME] -->`` and ``<!-- /figures -->`` is rewritten: ``tradeoff NAME``
the tables of NAME.json; ``runtime`` the whole-run times; ``advice`` the Advice paragraph
and ``newton`` the sentence under the five-bar's table (scripts/figures_advice.py);
``audit-json`` the keys of ``audit --json``; ``bench-machine``, ``bench-generate``,
``bench-audit``, ``bench-read``, ``bench-batch``, ``bench-batch-notes`` the speed figures,
``bench-corpus`` the audit on the real-world corpus and ``bench-peers`` the engines
reproducing its cached values (scripts/figures_bench.py); ``functions``
the size of the evaluator's function registry.  Everything else in the README is left as written.
tests/test_readme_figures.py checks the README equals what the script makes from the
committed data.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "docs" / "tradeoff"
BENCH = ROOT / "docs" / "bench"
sys.path[:0] = [str(ROOT / "scripts"), str(ROOT / "bench")]
import benchinfo  # noqa: E402
import figures_advice  # noqa: E402
import figures_bench  # noqa: E402

# docs/bench/NAME.json <- the command that measures it (at the sizes the README quotes)
BENCHES = {
    "generate": ["bench/generate.py", "--variants", "50"],
    "audit": ["bench/audit.py", "--only", "lo-formualizer", "--repeat", "5"],
    "read_xlsx": ["bench/read_xlsx.py"],
    "batch": ["bench/batch.py"],
    "corpus": ["bench/corpus.py"],
    "peers": ["bench/peers.py", "--timeout", "240"],  # the whole corpus: about an hour
}
README = ROOT / "README.md"
# name -> (scene file, options replaced in a copy: the five-bar copy uses Newton steps)
SCENES = {
    "sewing_machine": ("templates/sewing_machine.toml", {}),
    "actuator_linkage": ("templates/actuator_linkage.toml", {}),
    "five_bar": ("templates/five_bar.toml", {"method": '"newton"', "iterations": "6"}),
}
LABELS = {"sewing_machine": "sewing machine", "actuator_linkage": "actuator",
          "five_bar": "five-bar"}
BLOCK = re.compile(r"(<!-- figures: ([\w-]+)(?: (\w+))? -->\n)(.*?)(<!-- /figures -->)", re.S)


def _e(x) -> str:
    return "n/a" if x is None else f"{x:.1e}"


def _count(x) -> str:
    return "" if x is None else f"{x:,}"


def _bytes(x) -> str:
    if x is None:
        return ""
    return f"{x / 1e6:.1f} M" if x >= 1e6 else f"{x / 1e3:.0f} k"


def _secs(x) -> str:
    return "" if x is None else f"{x:.2f}"


def _rows(data, dimension):
    return [r for r in data["rows"] if r["dimension"] == dimension]


def tradeoff_block(data: dict) -> str:
    """The tables of one scene's tradeoff run."""
    steps = _rows(data, "step")
    deriv = {r["setting"]: r for r in _rows(data, "derivative")}
    unit = f" ({steps[0]['setting'].split()[-1]})" if steps else ""
    cpu = any(r.get("cpu_seconds") is not None for r in steps)  # older files: wall only
    lines = [f"| step{unit} | extremes error | seconds |{' CPU s |' if cpu else ''} cells | "
             "bytes | central diff. | forward diff. |", "|---|---|---|" + "---|" * cpu
             + "---|---|---|---|"]
    for r in steps:
        step = r["setting"].split()[0]
        central = deriv.get(f"central, {r['setting']}", {}).get("max_error")
        forward = deriv.get(f"forward, {r['setting']}", {}).get("max_error")
        lines.append(f"| {step} | {_e(r['max_error'])} | {_secs(r['seconds'])} | "
                     + (f"{_secs(r.get('cpu_seconds'))} | " if cpu else "")
                     + f"{_count(r['cells'])} | {_bytes(r['bytes'])} | {_e(central)} | "
                     f"{_e(forward)} |")
    methods = [r for r in _rows(data, "method") if r["max_error"] is not None]
    if methods:
        lines += ["", f"| method | error | seconds |{' CPU s |' if cpu else ''} cells | note |",
                  "|---|---|---|" + "---|" * cpu + "---|---|"]
        for r in methods:
            lines.append(f"| {r['setting']} | {_e(r['max_error'])} | {_secs(r['seconds'])} | "
                         + (f"{_secs(r.get('cpu_seconds'))} | " if cpu else "")
                         + f"{_count(r['cells'])} | {r['note']} |")
    analytic = [r["max_error"] for r in deriv.values()
                if r["setting"].startswith("analytic") and r["max_error"] is not None]
    precision = {r["setting"]: r["max_error"] for r in _rows(data, "precision")}
    notes = []
    if analytic:
        notes.append(f"Analytic velocity and acceleration columns: at most {_e(max(analytic))} "
                     "at every step.")
    table = precision.get("float64, whole table")
    near = precision.get("float64, near the extremes")
    if table is not None:
        notes.append(f"Float64 against 50 digits: {_e(table)} over the table, {_e(near)} "
                     "next to the extremes.")
    if not methods:
        notes.append("No iterative method (n/a).")
    whole = data.get("cpu_seconds")
    whole = f" ({whole:.0f} s CPU)" if whole is not None else ""
    notes.append(f"Whole run: {data['seconds']:.0f} s{whole}.")
    return "\n".join(lines) + "\n\n" + " ".join(notes) + "\n"


def audit_json_block() -> str:
    """The keys ``audit --json`` prints, from a real audit of a workbook that disagrees
    in one cell (so that a mismatch's keys show too)."""
    import tempfile
    import zipfile

    from workbook_gen import audit, load_scene, write_workbook
    with tempfile.TemporaryDirectory() as tmp:
        path = write_workbook(load_scene(ROOT / "templates" / "slider_crank.toml"), tmp)
        bad = Path(tmp) / "edited.xlsx"
        with zipfile.ZipFile(path) as zin, zipfile.ZipFile(bad, "w") as zout:
            for item in zin.infolist():
                data = zin.read(item.filename)
                if item.filename == "xl/worksheets/sheet1.xml":  # one cached value changed
                    data = re.sub(rb'(<c r="H3"[^>]*><f>[^<]*</f><v>)([^<]*)',
                                  rb"\g<1>12345", data, count=1)
                zout.writestr(item, data)
        report = audit(bad).to_json()
    keys = ", ".join(f"`{k}`" for k in report)
    mismatch = ", ".join(f"`{k}`" for k in report["mismatches"][0]) if report["mismatches"] \
        else "none"
    return f"{keys}; each of `mismatches` has {mismatch}.\n"


def functions_block() -> str:
    """How many functions the evaluator's registry knows."""
    from workbook_gen.formula.functions.registry import REGISTRY
    return f"The evaluator knows {len(REGISTRY)} functions,\n"


def load() -> dict[str, dict]:
    return {path.stem: json.loads(path.read_text(encoding="utf-8"))
            for path in sorted(DATA.glob("*.json"))}


def load_bench(folder: Path = BENCH) -> dict[str, dict]:
    return {path.stem: json.loads(path.read_text(encoding="utf-8"))
            for path in sorted(folder.glob("*.json"))}


def render(text: str, all_data: dict[str, dict], bench: dict[str, dict] | None = None) -> str:
    """``text`` with every marked block rewritten from ``all_data`` (tradeoff) and ``bench``
    (benchmarks; the committed docs/bench/*.json if None)."""
    bench = load_bench() if bench is None else bench

    def need(source: dict, name: str, folder: Path) -> dict:
        if name not in source:
            raise SystemExit(f"README block needs {folder / name}.json, which is missing")
        return source[name]

    makers = {
        "runtime": lambda _: figures_advice.runtime_block(all_data, LABELS),
        "advice": lambda _: figures_advice.advice_block(all_data, LABELS),
        "newton": lambda _: figures_advice.newton_block(need(all_data, "five_bar", DATA)),
        "audit-json": lambda _: audit_json_block(),
        "tradeoff": lambda name: tradeoff_block(need(all_data, name, DATA)),
        "bench-machine": lambda _: figures_bench.machine_block(bench),
        "bench-generate": lambda _: figures_bench.generate_block(need(bench, "generate", BENCH)),
        "bench-audit": lambda _: figures_bench.audit_block(need(bench, "audit", BENCH)),
        "bench-read": lambda _: figures_bench.read_block(need(bench, "read_xlsx", BENCH)),
        "bench-batch": lambda _: figures_bench.batch_block(need(bench, "batch", BENCH)),
        "bench-corpus": lambda _: figures_bench.corpus_block(need(bench, "corpus", BENCH)),
        "bench-peers": lambda _: figures_bench.peers_block(need(bench, "peers", BENCH)),
        "functions": lambda _: functions_block(),
        "bench-batch-notes": lambda _: figures_bench.batch_notes_block(
            need(bench, "batch", BENCH), need(bench, "generate", BENCH)),
    }

    def block(match: re.Match) -> str:
        kind, name = match.group(2), match.group(3)
        if kind not in makers:
            raise SystemExit(f"README block 'figures: {kind}' is not a kind this script makes")
        return match.group(1) + makers[kind](name) + match.group(5)
    return BLOCK.sub(block, text)


def settle(limit: float = 120.0, below: float = 1.0) -> None:
    """Wait (at most ``limit`` seconds) for the 1-minute load average to fall below
    ``below``: the previous run's own load would otherwise count as the next one's."""
    import time
    deadline = time.monotonic() + limit
    while os.getloadavg()[0] >= below and time.monotonic() < deadline:
        time.sleep(5)


def measure(only: list[str] | None = None) -> None:
    """Re-run the tradeoff of each scene (or of ``only``), recording the machine and the
    load around each run."""
    DATA.mkdir(parents=True, exist_ok=True)
    for name, (scene, options) in SCENES.items():
        if only and name not in only:
            continue
        text = (ROOT / scene).read_text(encoding="utf-8")
        for key, value in options.items():  # a copy of the scene with those options
            text = re.sub(rf"^{key} = .*$", f"{key} = {value}", text, count=1, flags=re.M)
        copy = DATA / f".{name}.toml"
        copy.write_text(text, encoding="utf-8")
        settle()
        record = benchinfo.Record()
        try:
            out = subprocess.run([sys.executable, "-m", "workbook_gen.cli", "tradeoff",
                                  str(copy), "--json"], check=True, capture_output=True,
                                 text=True, cwd=ROOT).stdout
        finally:
            copy.unlink(missing_ok=True)
        data = json.loads(out)
        data["scene"] = scene + "".join(f" ({k} = {v})" for k, v in options.items())
        data.update(record.describe())
        (DATA / f"{name}.json").write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")


def measure_bench(folder: Path = BENCH, extra: dict[str, list[str]] | None = None,
                  names: list[str] | None = None) -> None:
    """Run each benchmark (or those in ``names``) with ``--json FOLDER/NAME.json``, one after
    the other, their output on stderr (``extra``: more options per benchmark, e.g. QUICK)."""
    folder.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    for name, command in BENCHES.items():
        if names and name not in names:
            continue
        options = (extra or {}).get(name, [])
        if extra is None:
            settle()
        print(f"measuring {name}: python {' '.join(command + options)} ...", file=sys.stderr,
              flush=True)
        subprocess.run([sys.executable, *command, *options, "--json",
                        str(folder / f"{name}.json")], check=True, cwd=ROOT, env=env,
                       stdout=sys.stderr)


# Small sizes, to check --measure-bench end to end in a few minutes (not figures to quote).
QUICK = {"generate": ["--variants", "2", "--steps", "10,1"], "audit": ["--quick"],
         "read_xlsx": ["--rows", "200", "--repeat", "1"],
         "batch": ["--variants", "20", "--summary", "200"], "corpus": [],
         "peers": ["--limit", "3"]}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if README.md is not up "
                        "to date")
    parser.add_argument("--measure", action="store_true", help="re-run the tradeoffs (~20 min)")
    parser.add_argument("--only", action="append", choices=sorted(SCENES),
                        help="with --measure: only this scene (repeatable)")
    parser.add_argument("--measure-bench", action="store_true",
                        help="re-run the benchmarks into docs/bench (~10 min on a quiet machine)")
    parser.add_argument("--quick", metavar="DIR", type=Path,
                        help="with --measure-bench: small sizes, into DIR instead of docs/bench; "
                             "print the README made of them instead of writing it")
    args = parser.parse_args()
    if args.quick and not args.measure_bench:
        parser.error("--quick goes with --measure-bench")
    if args.measure:
        measure(args.only)
    if args.measure_bench:
        measure_bench(args.quick or BENCH, QUICK if args.quick else None)
    text = README.read_text(encoding="utf-8")
    if args.quick:
        print(render(text, load(), load_bench(args.quick)), end="")
        return 0
    new = render(text, load())
    if args.check:
        if new != text:
            print("README.md is not up to date: run python scripts/readme_figures.py",
                  file=sys.stderr)
            return 1
        return 0
    README.write_text(new, encoding="utf-8")
    return 0

if __name__ == "__main__":
    sys.exit(main())
