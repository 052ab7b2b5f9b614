"""The README's speed figures, rendered from what the benchmarks measured (their ``--json``
output under docs/bench/: generate.json, audit.json, batch.json, read_xlsx.json; see
bench/benchinfo.py for the record's shape).  Each function returns one marked block's text.

Targets are the issues' (issue 9 "Speed", issue 10 "Figures"); whether one is reached is
computed here from the data, never written by hand.  A run whose 1-minute load average at
its start exceeds LOADED is said to be measured under load: its wall times are inflated,
and the figures that have a CPU time say so.
"""

from __future__ import annotations

import datetime

LOADED = 1.5

# issue 9 (Speed, bench/batch.py and bench/generate.py) and issue 10 (Figures, bench/audit.py)
GENERATE_MAX_S = 1.5        # generate at 0.1 deg in-process
FILES_VARIANTS, FILES_MAX_S, FILES_VS_LOOP = 1000, 20.0, 1.7
SUMMARY_VARIANTS, SUMMARY_MAX_S, SUMMARY_VS_FILES, SUMMARY_MAX_MB = 100_000, 10.0, 200.0, 1000.0
DASK_MAX_RATIO = 1.3
AUDIT_VS_LO = 4.0           # our audit at 0.1 deg, against LibreOffice recalculating the file
AUDIT_STEP = 0.1
CORPUS_FILES, CORPUS_CELLS = 0.90, 0.95  # issue 10: fully audited files, cells evaluated


def verdict(ok: bool) -> str:
    return "reached" if ok else "not reached"


def s(x: float) -> str:
    """Seconds to three significant digits."""
    return f"{x:.3g}" if x < 100 else f"{x:.0f}"


def count(x: int) -> str:
    return f"{x:,}"


def deg(step: float) -> str:
    return f"{step:g}°"


def loaded(record: dict) -> bool:
    load = record.get("run", {}).get("load_start")
    return load is not None and load > LOADED


def when(record: dict) -> str:
    """The UTC date of a run and, when it was loaded, what that means for its figures."""
    run = record.get("run", {})
    started = run.get("started")
    date = (datetime.datetime.strptime(started, "%Y-%m-%dT%H:%M:%SZ").strftime(
        "%-d %b %Y %H:%M UTC") if started else "date not recorded")
    load, end = run.get("load_start"), run.get("load_end")
    if load is None:
        return f"{date}, load not recorded"
    if loaded(record):
        return (f"{date}, measured under load {load:.1f} (1-minute load average at the start, "
                f"{end:.1f} at the end): wall times are inflated, CPU times much less")
    return f"{date}, quiet machine (load average {load:.1f} at the start)"


def machine_block(records: dict[str, dict]) -> str:
    machines = []
    for record in records.values():
        m = record["machine"]
        text = (f"{m['cores']}-core {m['cpu']} ({m['arch']}, {m['system'].split()[0]}), "
                f"Python {m['python']}, XlsxWriter {m['packages'].get('XlsxWriter')}, "
                f"LibreOffice {m['libreoffice'] or 'not found'}")
        if text not in machines:
            machines.append(text)
    return ("Measured on " + "; and on ".join(machines) + ", each figure against a peer run "
            "in the same script. The tables and figures of this section are rendered by "
            "`python scripts/readme_figures.py` from the scripts' `--json FILE` output "
            "(`docs/bench/*.json`: the figures, the machine, the UTC time and the load average "
            "at the start and end); `python scripts/readme_figures.py --measure-bench` re-runs "
            "the scripts and rewrites them, and a test checks that the README equals what the "
            "script makes of the committed files.\n")


def generate_block(record: dict) -> str:
    f = record["figures"]
    lines = [f"Generating (`{record['command']}`; peer: plain numpy evaluating the same closed "
             f"form; {when(record)}):", "",
             "| sewing machine | rows | Table formula cells | generate | CPU | numpy | "
             "worst error against the reference |", "|---|---|---|---|---|---|---|"]
    for r in f["steps"]:
        lines.append(f"| {deg(r['step'])} | {count(r['rows'])} | {count(r['cells'])} | "
                     f"{s(r['seconds'])} s | {s(r['cpu'])} s | {s(r['numpy'])} s | "
                     f"{r['worst_error']:.1e} |")
    v = f["per_variant"]
    first = f["steps"][0]
    lines.append(f"| per {deg(first['step'])} design variant (`workbook_bytes`, {v['variants']} "
                 f"variants of l_BC, one process) | {count(first['rows'])} | "
                 f"{count(first['cells'])} | {v['workbook_ms']:.1f} ms | "
                 f"{v['workbook_cpu_ms']:.1f} ms | {v['numpy_ms']:.1f} ms | |")
    lines.append("")
    fine = [r for r in f["steps"] if r["step"] == AUDIT_STEP]
    if fine:
        r = fine[0]
        figure, basis = (r["cpu"], "CPU") if loaded(record) else (r["seconds"], "wall")
        lines.append(f"Target (issue 9): `generate` at {deg(r['step'])} in <= "
                     f"{GENERATE_MAX_S:g} s in-process: {s(r['seconds'])} s wall, "
                     f"{s(r['cpu'])} s CPU; judged on the {basis} time: "
                     f"**{verdict(figure <= GENERATE_MAX_S)}**.")
    else:
        lines.append(f"Target (issue 9): `generate` at {deg(AUDIT_STEP)} in <= "
                     f"{GENERATE_MAX_S:g} s in-process: not measured in this run.")
    return "\n".join(lines) + "\n"


def _peer(p: dict) -> str:
    mark = {"extrapolated": "~", "lower bound": ">"}.get(p["status"], "")
    return f"{mark}{s(p['total'])} s" if p.get("total") is not None else p["status"]


def _ratio(a: float | None, b: float | None) -> str:
    return "n/a" if a is None or b is None else f"{a / b:.1f}x"


PEERS = (("lo", "LibreOffice recalculation"),
         ("formualizer", "`formualizer` (Rust) load + evaluate_all"),
         ("formulas", "`formulas` load + calculate"), ("pycel", "`pycel` load + evaluate"))


def _best_of(repeat: int) -> str:
    return ("ours and `formualizer` one run each" if repeat == 1
            else f"ours and `formualizer` best of {repeat}")


def audit_block(record: dict) -> str:
    f = record["figures"]
    steps = f["steps"]
    ran = [(key, label) for key, label in PEERS if any(r[key]["total"] for r in steps)]
    lines = [f"Auditing (`{record['command']}`, {when(record)}):", "",
             "| sewing machine | " + " | ".join(deg(r["step"]) for r in steps) + " |",
             "|---|" + "---|" * len(steps)]

    def row(label, cells):
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    row("formula cells", [count(r["cells"]) for r in steps])
    row("our audit", [f"{s(r['ours']['total'])} s" for r in steps])
    if all(r.get("ours_cpu") is not None for r in steps):
        row("our audit, CPU", [f"{s(r['ours_cpu'])} s" for r in steps])
    row("of which evaluate", [f"{s(r['ours_eval'])} s" for r in steps])
    for key, label in ran:
        row(label, [_peer(r[key]) for r in steps])
    row("numpy closed form", [f"{s(r['numpy'])} s" for r in steps])
    for key, label in ran:
        name = label.split(" load")[0].replace(" recalculation", "")
        row(f"{name} / our audit", [_ratio(r[key]["total"], r["ours"]["total"])
                                    for r in steps])
    row("our evaluate / numpy", [_ratio(r["ours_eval"], r["numpy"]) for r in steps])
    lines.append("")
    fine = [r for r in steps if r["step"] == AUDIT_STEP]
    if not fine:
        lines.append(f"Targets (issue 10) at {deg(AUDIT_STEP)}: not measured in this run.")
        return "\n".join(lines) + "\n"
    r = fine[0]
    ours, lo, fz = r["ours"]["total"], r["lo"]["total"], r["formualizer"]["total"]
    parts = []
    if lo:
        parts.append(f"our audit >= {AUDIT_VS_LO:g}x faster than LibreOffice recalculating "
                     f"the file: {lo / ours:.1f}x, **{verdict(lo / ours >= AUDIT_VS_LO)}**")
    else:
        parts.append(f"against LibreOffice: {r['lo']['status']}")
    if fz:
        close = abs(fz / ours - 1) < 0.1  # best-of-3 figures move by more between runs
        rounds = r.get("rounds") or []
        won = (f"; ours took less time in {sum(o < t for o, t in rounds)} of the "
               f"{len(rounds)} rounds run in turn" if rounds and all(t is not None for _, t in rounds) else "")
        parts.append(f"faster than `formualizer`: {s(ours)} s against {s(fz)} s, "
                     f"**{verdict(ours < fz)}**"
                     + (" by under 10%, within the run-to-run variation of these figures "
                        "(the two are at parity)" if close else "") + won)
    else:
        parts.append(f"against `formualizer`: {r['formualizer']['status']}")
    text = (f"Targets (issue 10), the {count(r['cells'])} formula cells at "
            f"{deg(r['step'])}: " + "; ".join(parts)
            + f" (wall times in one run: {_best_of(f.get('repeat', 1))}, LibreOffice once).")
    timings = r.get("ours_timings")
    if timings:
        phases = [(k, timings[k]) for k in ("read", "parse", "evaluate", "compare", "reference",
                                            "findings") if k in timings]
        top = max(phases, key=lambda kv: kv[1])
        text += (" Where our audit's time goes there (`audit --json` `timings`): "
                 + ", ".join(f"{k} {s(v)} s" for k, v in phases)
                 + f"; {top[0]} is the largest (parse and findings overlap the reading and "
                   "the evaluation, reference the comparison, on the other core).")
    if loaded(record) and r.get("ours_cpu") is not None and r["lo"].get("cpu"):
        text += (f" In CPU time (under load): our audit {s(r['ours_cpu'])} s, LibreOffice "
                 f"{s(r['lo']['cpu'])} s ({r['lo']['cpu'] / r['ours_cpu']:.1f}x).")
    lines.append(text)
    return "\n".join(lines) + "\n"


def read_block(record: dict) -> str:
    f = record["figures"]
    ratios = [m["seconds"] / f["ours"] for m in f["openpyxl"]]
    cells = f.get("ours_cell_objects")
    objects = (f"; making a Cell object of every cell as well takes it "
               f"{cells / f['ours']:.1f}x as long" if cells else "")
    return (f"Reading: our streaming reader is {min(ratios):.1f}x to {max(ratios):.1f}x faster "
            f"than openpyxl's four modes on a {count(f['rows'])} x {f['cols']} workbook of "
            f"formulas with cached values, and {f['openpyxl_formulas_and_values'] / f['ours']:.1f}x "
            f"faster than the two openpyxl loads the auditor would need (formulas and values), "
            f"reading every value and formula text into what the audit takes (plain cells as "
            f"columns){objects} (`{record['command']}`, {when(record)}).\n")


def batch_block(record: dict) -> str:
    f = record["figures"]
    jobs = f["jobs"]
    lines = [f"**Speed** (`{record['command']}`, ratios within one run, {when(record)}):", "",
             "| figure | measured | target (issue 9) |", "|---|---|---|"]
    files, summary, dask = f.get("files"), f.get("summary_only"), f.get("dask")

    def sized(n: int, target_n: int, text: str) -> str:
        return text if n == target_n else f"for {count(target_n)} variants: not assessed"
    under = " (wall time, under load)" if loaded(record) else ""
    rate = None
    if files:
        n, t = files["variants"], files["seconds"]
        rate = n / t
        lines.append(f"| {count(n)} sewing-machine variants at 10°, `--jobs {jobs}` | "
                     f"{s(t)} s ({rate:.1f} variants/s; {s(files['cpu'])} s CPU in all) | "
                     + sized(n, FILES_VARIANTS, f"<= {FILES_MAX_S:g} s: "
                             f"{verdict(t <= FILES_MAX_S)}{under}") + " |")
        loop = files["loop_seconds"]
        lines.append(f"| the same as a loop of `write_workbook` in one process | {s(loop)} s; "
                     f"`--jobs {jobs}` {loop / t:.2f}x faster | "
                     f">= {FILES_VS_LOOP:g}x: {verdict(loop / t >= FILES_VS_LOOP)} |")
    if summary:
        n, t = summary["variants"], summary["seconds"]
        versus = f", {n / t / rate:.0f}x the file batch's {rate:.1f}/s" if rate else ""
        target = sized(n, SUMMARY_VARIANTS, f"<= {SUMMARY_MAX_S:g} s: "
                       f"{verdict(t <= SUMMARY_MAX_S)}{under}")
        if rate:
            target += (f"; >= {SUMMARY_VS_FILES:g}x: "
                       f"{verdict(n / t / rate >= SUMMARY_VS_FILES)}")
        lines.append(f"| `--summary-only`, {count(n)} variants, `--jobs {jobs}` | {s(t)} s "
                     f"({n / t:,.0f} variants/s{versus}) | {target} |")
        peak = max(summary["peak_mb"], summary["worker_peak_mb"])
        lines.append(f"| its peak memory | {summary['peak_mb']:.0f} MB (the command), "
                     f"{summary['worker_peak_mb']:.0f} MB (the largest worker) | "
                     + sized(n, SUMMARY_VARIANTS, f"<= {SUMMARY_MAX_MB / 1000:g} GB: "
                             f"{verdict(peak <= SUMMARY_MAX_MB)}") + " |")
    if dask:
        n, t = dask["variants"], dask["seconds"]
        local = (dask["jobs_before"] + dask["jobs_after"]) / 2
        lines.append(f"| Dask LocalCluster ({dask['workers']} worker processes) against "
                     f"`--jobs {jobs}`, {count(n)} variants | {s(t)} s against "
                     f"{s(dask['jobs_before'])} s and {s(dask['jobs_after'])} s just before and "
                     f"after: {t / local:.2f}x the time, {(t - local) / n * 1000:+.1f} ms per "
                     f"variant | <= {DASK_MAX_RATIO:g}x: {verdict(t / local <= DASK_MAX_RATIO)} |")
    return "\n".join(lines) + "\n"


def batch_notes_block(batch: dict, generate: dict) -> str:
    """Where a batch's time goes, from the per-variant CPU time and the summary's CPU."""
    f = batch["figures"]
    jobs, parts = f["jobs"], []
    per = generate["figures"]["per_variant"]["workbook_cpu_ms"]
    files, summary = f.get("files"), f.get("summary_only")
    if files:
        n = files["variants"]
        parts.append(f"What bounds the file batch is the CPU time of one workbook, {per:.0f} ms "
                     f"for the 10° sewing machine (`{generate['command']}`): {count(n)} of them "
                     f"on {jobs} cores take {n * per / jobs / 1000:.0f} s before any overhead "
                     f"(the batch used {s(files['cpu'])} s of CPU in all): evaluating the "
                     "formulas with Excel's error masks, XlsxWriter's packaging and zlib.")
    if summary:
        n, cpu, workers = summary["variants"], summary["cpu"], summary["worker_cpu"]
        larger = ("the command's own work, not the workers' evaluation, is the larger part"
                  if cpu > workers else "the workers' evaluation is the larger part")
        parts.append(f"In `--summary-only` the workers spend {s(workers)} s of CPU evaluating "
                     f"{count(n)} variants and the command {s(cpu)} s (it hands out the "
                     f"variants and writes summary.csv and summary.xlsx, {summary['columns']} "
                     f"columns x {count(n)} rows, formatted exactly): {larger}.")
    return " ".join(parts) + "\n"


def corpus_block(record: dict) -> str:
    """The audit on the real-world corpus (bench/corpus.py, which runs its coverage.py)."""
    f = record["figures"]
    files, cells = f["fully"] / f["files"], f["evaluated"] / f["cells"]
    classes = ", ".join(f"{n} {k}" for k, n in sorted(f["classes"].items(), key=lambda kv: -kv[1]))
    lines = [f"On the {f['files']} real-world workbooks of `../shared/corpus` "
             f"(`{record['command']}`, {when(record)}): **{f['fully']} of {f['files']} files "
             f"audit fully** ({100 * files:.0f}%; target {100 * CORPUS_FILES:.0f}%: "
             f"{verdict(files >= CORPUS_FILES)}) and **{count(f['evaluated'])} of "
             f"{count(f['cells'])} formula cells are recomputed** ({100 * cells:.1f}%; target "
             f"{100 * CORPUS_CELLS:.0f}%: {verdict(cells >= CORPUS_CELLS)}); files per class: "
             f"{classes}. The files not fully audited:", ""]
    for name, r in f["not_fully"].items():
        lines.append(f"- `{name}`: {count(r['evaluated'])} of {count(r['formula_cells'])} "
                     f"formula cells recomputed, {count(r['disagree'])} disagree")
    return "\n".join(lines) + "\n"


PEER_NAMES = {"ours": "ours (`workbook-gen audit`)", "formualizer": "formualizer",
              "ironcalc": "IronCalc", "libreoffice": "LibreOffice (headless, recalculated)"}


def peers_block(record: dict) -> str:
    """The corpus's cached values each engine reproduces (bench/peers.py)."""
    f = record["figures"]
    t = f["totals"]
    lines = [f"On the {t['files']} corpus workbooks (`{record['command']}`, {when(record)}), "
             f"{count(t['cells'])} formula cells that hold a cached value and call no "
             f"volatile function ({count(t['volatile'])} volatile cells left out): how many "
             "cached values each engine reproduces (equal to 1e-9 relative), contradicts, "
             "or does not compute (an error of its own, an unknown function, a file it cannot "
             "load):", "",
             "| engine | reproduces | contradicts | not computed | files failed |",
             "|---|---|---|---|---|"]
    for name in f["engines"]:
        e = t[name]
        lines.append(f"| {PEER_NAMES.get(name, name)} | {count(e['r'])} | {count(e['c'])} | "
                     f"{count(e['n'])} | {e['failed_files']} |")
    best = max(f["engines"], key=lambda n: t[n]["r"])
    lines += ["", f"Target (issue 20): ours reproduces the most: "
                  f"{verdict(best == 'ours')}."]
    return "\n".join(lines) + "\n"
