"""Time ``workbook-gen audit`` against its peers on the sewing-machine workbook.

For the workbook generated at 10, 1 and 0.1 degree steps (37, 361, 3601 rows), in one
run: our audit (best of REPEAT; total and its evaluate phase), LibreOffice headless
recalculating the file (one run, start-up included), ``formualizer`` (a Rust engine:
``load_workbook(path).evaluate_all()``, load and evaluate; best of REPEAT, each run right
after one of ours), the ``formulas``
package (load + compile, calculate; one run), ``pycel`` in its own virtual environment (Table and Checks
formula cells; one run) and plain numpy evaluating the closed form (best of 5). Prints
absolute times and ratios against our audit. A peer that fails or times out is reported
as such; a peer run whose predicted time (per-cell time of the largest finished size x
cells) exceeds the timeout is not started, and its figure is extrapolated and marked "~".

    python bench/audit.py [--quick] [--timeout 600] [--repeat 3] [--json FILE]

``--json FILE`` also writes the figures with the machine and the load (bench/benchinfo.py).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCENE = ROOT / "templates" / "sewing_machine.toml"
sys.path.insert(0, str(ROOT / "bench"))
import benchinfo  # noqa: E402

PYCEL_VENV = ROOT / "bench" / ".venv-pycel"
PYCEL_RUNNER = ROOT / "bench" / "pycel_runner.py"
STEPS = (10.0, 1.0, 0.1)


@dataclass
class Peer:
    """One peer's figures at one size: phase -> seconds, the cells it evaluated."""
    phases: dict[str, float] = field(default_factory=dict)
    cells: int = 0
    status: str = "ok"      # ok | extrapolated | lower bound | timeout | failed
    note: str = ""
    cpu: float | None = None  # CPU seconds (user + sys, all its processes), where measured

    @property
    def total(self) -> float | None:
        return sum(self.phases.values()) if self.phases else None

    @property
    def per_cell(self) -> float | None:
        return self.total / self.cells if self.phases and self.cells else None

    def to_json(self) -> dict:
        return {"phases": self.phases, "total": self.total, "cells": self.cells,
                "status": self.status, "note": self.note, "cpu": self.cpu}


# ---------------------------------------------------------------- peers run in a child

def formulas_runner(path: str) -> None:
    """Child process: time formulas' load+compile and calculate, print JSON."""
    import formulas
    start = time.perf_counter()
    model = formulas.ExcelModel().loads(path).finish()
    loaded = time.perf_counter()
    solution = model.calculate()
    done = time.perf_counter()
    print(json.dumps({"load": loaded - start, "calculate": done - loaded,
                      "solution": len(solution)}))


def formualizer_runner(path: str) -> None:
    """Child process: time formualizer's load and evaluate_all, print JSON."""
    import formualizer
    start, cpu = time.perf_counter(), time.process_time()
    book = formualizer.load_workbook(path)
    loaded = time.perf_counter()
    book.evaluate_all()
    done = time.perf_counter()
    print(json.dumps({"load": loaded - start, "evaluate": done - loaded,
                      "cpu": time.process_time() - cpu}))


def _child(cmd: list[str], timeout: float) -> dict:
    """Run a timing child; its last stdout line is JSON. Raises TimeoutError/RuntimeError."""
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        raise TimeoutError(f"killed after {timeout:g} s") from None
    lines = done.stdout.strip().splitlines()
    if done.returncode != 0 or not lines:
        detail = " ".join((done.stderr or done.stdout).split()[-12:])
        raise RuntimeError(f"exit {done.returncode}: {detail}")
    return json.loads(lines[-1])


def ensure_pycel() -> Path:
    """The interpreter of bench/.venv-pycel, created with pycel and openpyxl<3.1 if missing."""
    python = PYCEL_VENV / "bin" / "python"
    probe = [str(python), "-c", "import pycel, openpyxl"]
    if python.exists() and subprocess.run(probe, capture_output=True).returncode == 0:
        return python
    print(f"creating {PYCEL_VENV.relative_to(ROOT)} (pycel, openpyxl<3.1) ...", flush=True)
    subprocess.run([sys.executable, "-m", "venv", str(PYCEL_VENV)], check=True)
    subprocess.run([str(python), "-m", "pip", "install", "-q", "pycel", "openpyxl<3.1"],
                   check=True)
    return python


def ensure_formualizer() -> None:
    try:
        import formualizer  # noqa: F401
    except ImportError:
        print("installing formualizer ...", flush=True)
        subprocess.run([sys.executable, "-m", "pip", "install", "-q", "formualizer"],
                       check=True)


def ensure_formulas() -> None:
    try:
        import formulas  # noqa: F401
    except ImportError:
        print("installing formulas ...", flush=True)
        subprocess.run([sys.executable, "-m", "pip", "install", "-q", "formulas"], check=True)


# ---------------------------------------------------------------- one size

def run_peer(name: str, cmd: list[str], cells: int, phases: tuple[str, ...], timeout: float,
             previous: tuple[Peer, float, int] | None, total_cells: int) -> Peer:
    """Run one peer child at one size, or extrapolate from ``previous`` (peer, step, cells
    of the workbook) when it is predicted to exceed, or does exceed, the timeout."""
    expected = cells or (round(previous[0].cells * total_cells / previous[2]) if previous else 0)

    def extrapolated(why: str) -> Peer:
        peer, step, _ = previous
        scale = expected / peer.cells
        return Peer({k: v * scale for k, v in peer.phases.items()}, expected, "extrapolated",
                    f"{why}; per-cell time as at {step:g} deg")

    predicted = previous[0].per_cell * expected if previous else None
    if predicted is not None and predicted > timeout:
        return extrapolated(f"not run: predicted {predicted:.0f} s > timeout {timeout:g} s")
    try:
        result = _child(cmd, timeout)
    except TimeoutError as exc:
        # the per-cell time grows with size: the timeout itself is the honest bound
        return Peer({"total": timeout}, expected, "lower bound",
                    f"timed out ({exc}); figures are lower bounds") if expected else \
            Peer(status="timeout", note=str(exc))
    except (RuntimeError, OSError, ValueError, KeyError) as exc:
        return Peer(status="failed", note=f"{name}: {exc}")
    peer = Peer({k: result[k] for k in phases}, result.get("cells", cells),
                cpu=result.get("cpu"))
    if result.get("errors") or result.get("disagree"):
        peer.note = f"{result.get('errors', 0)} errors, {result.get('disagree', 0)} disagree"
    return peer


def measure(step: float, tmp: Path, args, prev: dict) -> dict:
    from workbook_gen import audit
    from workbook_gen.tabulate import evaluate
    from workbook_gen.engines.libreoffice import recalculate
    from workbook_gen.errors import WorkbookGenError
    from workbook_gen.scene import load_scene
    from workbook_gen.workbook import write_workbook

    scene = load_scene(SCENE, step=step)
    path = write_workbook(scene, tmp / f"step{step:g}", force=True)
    row: dict = {"step": step}

    # our audit and formualizer in turn, so that the machine's drift (these shared machines
    # vary by a fifth from minute to minute) falls on both alike
    reports, cpus, theirs = [], [], []
    for _ in range(args.repeat):
        cpu = time.process_time() + _children_cpu()
        reports.append(audit(path))
        # the audit's own forked reader counts too (workbook_gen/forked.py waits for it)
        cpus.append(time.process_time() + _children_cpu() - cpu)
        if args.formualizer_ok:
            theirs.append(run_peer("formualizer", [sys.executable, __file__,
                                                   "--formualizer-runner", str(path)],
                                   reports[0].formula_cells, ("load", "evaluate"),
                                   args.timeout, prev.get("formualizer"),
                                   reports[0].formula_cells))
    if not all(r.ok for r in reports):
        print(f"warning: audit at {step:g} deg is not ok", file=sys.stderr)
    cells = reports[0].formula_cells
    row["cells"] = cells
    row["rows"] = scene.sweep.rows
    row["ours"] = Peer({"total": min(r.seconds for r in reports)}, cells)
    row["ours_eval"] = min(r.timings["evaluate"] for r in reports)
    row["ours_cpu"] = min(cpus)  # CPU of the whole audit() call, its forked child included
    row["ours_ok"] = all(r.ok for r in reports)
    row["ours_timings"] = min(reports, key=lambda r: r.seconds).timings  # the best run's phases

    start, children = time.perf_counter(), _children_cpu()
    try:
        recalculate(path, tmp / f"lo{step:g}", timeout=args.timeout)
        row["lo"] = Peer({"total": time.perf_counter() - start}, cells,
                         cpu=_children_cpu() - children)
    except WorkbookGenError as exc:
        row["lo"] = Peer(status="failed", note=str(exc))

    if args.formualizer_ok:  # best of REPEAT, as our audit, run in turn with it
        finished = [p for p in theirs if p.status == "ok"]
        row["formualizer"] = min(finished, key=lambda p: p.total) if finished else theirs[0]
        row["rounds"] = [[r.seconds, p.total] for r, p in zip(reports, theirs)]
    else:
        row["formualizer"] = Peer(status="failed", note=args.formualizer_why)

    if args.formulas_ok:
        row["formulas"] = run_peer(
            "formulas", [sys.executable, __file__, "--formulas-runner", str(path)], cells,
            ("load", "calculate"), args.timeout, prev.get("formulas"), cells)
    else:
        row["formulas"] = Peer(status="failed", note=args.formulas_why)

    if args.pycel_python:
        row["pycel"] = run_peer(
            "pycel", [str(args.pycel_python), str(PYCEL_RUNNER), str(path), "Table", "Checks"],
            0, ("load", "evaluate"), args.timeout, prev.get("pycel"), cells)
    else:
        row["pycel"] = Peer(status="failed", note=args.pycel_why)

    times = []
    for _ in range(5):
        t = time.perf_counter()
        evaluate(scene)
        times.append(time.perf_counter() - t)
    row["numpy"] = min(times)
    return row


def _children_cpu() -> float:
    """CPU seconds (user + sys) of the finished child processes so far."""
    import resource
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def to_json(rows: list[dict], args) -> dict:
    """The figures of ``rows`` as JSON: per step, each peer's phases and status."""
    out = []
    for r in rows:
        item = {k: r[k] for k in ("step", "rows", "cells", "ours_eval", "ours_cpu", "ours_ok",
                                  "ours_timings", "numpy")}
        item["rounds"] = r.get("rounds", [])  # (ours, formualizer) seconds, run in turn
        item.update({k: r[k].to_json() for k in ("ours", "lo", "formualizer", "formulas",
                                                 "pycel")})
        out.append(item)
    return {"scene": str(SCENE.relative_to(ROOT)), "repeat": args.repeat,
            "timeout": args.timeout, "only": args.only, "steps": out}


# ---------------------------------------------------------------- printing

def machine() -> str:
    cpu = "?"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        lo = subprocess.run(["soffice", "--version"], capture_output=True, text=True,
                            timeout=60).stdout.strip() or "?"
    except (OSError, subprocess.TimeoutExpired):
        lo = "not found"
    return (f"machine: {platform.platform()}, CPU {cpu}, {os.cpu_count()} cores, "
            f"Python {platform.python_version()}, {lo}")


_MARK = {"extrapolated": "~", "lower bound": ">"}


def _secs(peer: Peer, phase: str | None = None) -> str:
    if not peer.phases:
        return peer.status
    if phase is not None and phase not in peer.phases:
        return "-"
    value = peer.total if phase is None else peer.phases[phase]
    return _MARK.get(peer.status, "") + f"{value:.3f}"


def _per_cell(peer: Peer) -> str:
    if peer.per_cell is None:
        return peer.status
    return _MARK.get(peer.status, "") + f"{1e6 * peer.per_cell:.0f}"


def _ratio(value: float | None, ours: float, peer: Peer | None = None) -> str:
    if value is None:
        return peer.status if peer else "n/a"
    mark = _MARK.get(peer.status, "") if peer else ""
    return f"{mark}{value / ours:.1f}x"


def _rounds(rounds: list | None) -> str:
    """'k of n': the rounds (our audit, then formualizer) in which ours took less time."""
    if not rounds or any(f is None for _, f in rounds):
        return "n/a"
    return f"{sum(o < f for o, f in rounds)} of {len(rounds)}"


def print_table(rows: list[dict]) -> None:
    width = 16
    head = [f"{r['step']:g} deg" for r in rows]
    lines = [("", head), ("", [f"{r['rows']} rows" for r in rows])]

    def add(label, cells):
        lines.append((label, cells))

    add("formula cells", [str(r["cells"]) for r in rows])
    add("our audit, total [s]", [f"{r['ours'].total:.3f}" for r in rows])
    add("  of which evaluate [s]", [f"{r['ours_eval']:.3f}" for r in rows])
    add("LibreOffice recalc [s] (1)", [_secs(r["lo"]) for r in rows])
    add("formualizer load [s]", [_secs(r["formualizer"], "load") for r in rows])
    add("formualizer evaluate_all [s]", [_secs(r["formualizer"], "evaluate") for r in rows])
    add("formualizer total [s]", [_secs(r["formualizer"]) for r in rows])
    add("formulas load+compile [s]", [_secs(r["formulas"], "load") for r in rows])
    add("formulas calculate [s]", [_secs(r["formulas"], "calculate") for r in rows])
    add("formulas total [s]", [_secs(r["formulas"]) for r in rows])
    add("pycel load+evaluate [s] (2)", [_secs(r["pycel"]) for r in rows])
    add("pycel cells evaluated", [str(r["pycel"].cells) if r["pycel"].cells else "-"
                                  for r in rows])
    add("numpy closed form [s]", [f"{r['numpy']:.4f}" for r in rows])
    add("per cell [us]: our audit", [f"{1e6 * r['ours'].per_cell:.1f}" for r in rows])
    add("  formulas", [_per_cell(r["formulas"]) for r in rows])
    add("  pycel", [_per_cell(r["pycel"]) for r in rows])
    add("ratios", [""] * len(rows))
    add("LibreOffice / our audit (>=4)", [_ratio(r["lo"].total, r["ours"].total, r["lo"])
                                          for r in rows])
    add("formualizer / our audit (>1)", [_ratio(r["formualizer"].total, r["ours"].total,
                                                r["formualizer"]) for r in rows])
    add("rounds ours faster than formualizer", [_rounds(r.get("rounds")) for r in rows])
    add("our evaluate / numpy (<=20)", [_ratio(r["ours_eval"], r["numpy"]) for r in rows])
    add("formulas / ours per cell (>=100)",
        [_ratio(r["formulas"].per_cell, r["ours"].per_cell, r["formulas"]) for r in rows])
    add("pycel / ours per cell (>=100)",
        [_ratio(r["pycel"].per_cell, r["ours"].per_cell, r["pycel"]) for r in rows])
    label_w = max(len(label) for label, _ in lines) + 2
    for label, cells in lines:
        print(f"{label:<{label_w}}" + "".join(f"{c:>{width}}" for c in cells))
    print("(1) one run, LibreOffice start-up included (isolated profile, forced recalculation)")
    print("(2) Table and Checks formula cells, one run; per cell = (load+evaluate) / those cells")
    print("~ extrapolated linearly in cells from the largest size that ran (see notes; per-cell")
    print("  times grow with size, so these are likely underestimates); > lower bound (timed out)")
    for r in rows:
        for name in ("lo", "formualizer", "formulas", "pycel"):
            if r[name].note:
                print(f"note {r['step']:g} deg, {name}: {r[name].note}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="10 and 1 deg only")
    parser.add_argument("--timeout", type=float, default=600, help="per peer run [s]")
    parser.add_argument("--repeat", type=int, default=3, help="runs of our audit (best)")
    parser.add_argument("--formulas-runner", metavar="FILE", help=argparse.SUPPRESS)
    parser.add_argument("--formualizer-runner", metavar="FILE", help=argparse.SUPPRESS)
    parser.add_argument("--only", choices=["lo-formualizer"],
                        help="lo-formualizer: our audit, LibreOffice and formualizer only")
    parser.add_argument("--json", metavar="FILE", help="also write the figures, the machine "
                        "and the load to FILE")
    args = parser.parse_args()
    if args.formulas_runner:
        formulas_runner(args.formulas_runner)
        return
    if args.formualizer_runner:
        formualizer_runner(args.formualizer_runner)
        return
    benchinfo.check_writable(args.json)
    record = benchinfo.Record()
    args.formualizer_ok, args.formualizer_why = True, ""
    try:
        ensure_formualizer()
    except (subprocess.CalledProcessError, OSError) as exc:
        args.formualizer_ok, args.formualizer_why = False, f"cannot install formualizer: {exc}"

    args.formulas_ok, args.formulas_why = True, ""
    args.pycel_python, args.pycel_why = None, ""
    if args.only:
        args.formulas_ok, args.formulas_why = False, "not run (--only)"
        args.pycel_why = "not run (--only)"
    else:
        try:
            ensure_formulas()
        except (subprocess.CalledProcessError, OSError) as exc:
            args.formulas_ok, args.formulas_why = False, f"cannot install formulas: {exc}"
        try:
            args.pycel_python = ensure_pycel()
        except (subprocess.CalledProcessError, OSError) as exc:
            args.pycel_why = f"cannot set up pycel's venv: {exc}"

    print(machine())
    print(f"scene: {SCENE.relative_to(ROOT)}; timeout per peer run {args.timeout:g} s; "
          f"our audit best of {args.repeat}, numpy best of 5", flush=True)
    rows, prev = [], {}
    with tempfile.TemporaryDirectory(prefix="workbook-gen-bench-") as tmp:
        for step in STEPS[:2] if args.quick else STEPS:
            print(f"  measuring {step:g} deg ...", file=sys.stderr, flush=True)
            row = measure(step, Path(tmp), args, prev)
            rows.append(row)
            for name in ("formualizer", "formulas", "pycel"):
                if row[name].status == "ok":
                    prev[name] = (row[name], step, row["cells"])
    print()
    print_table(rows)
    if args.json:
        record.write(args.json, to_json(rows, args))


if __name__ == "__main__":
    main()
