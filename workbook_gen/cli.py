"""The command line: ``workbook-gen list | generate | audit | tradeoff | batch``.

User errors print one line to stderr and exit 2; no tracebacks.
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import sys
from typing import Sequence

from .errors import SceneError, WorkbookGenError
from .terminate import EXIT_CODE, Terminated
from .version import VERSION

# a reader that closes the pipe early (`| head`): exit quietly with the status a Unix tool
# killed by SIGPIPE has in the shell (128 + 13)
EXIT_BROKEN_PIPE = 128 + signal.SIGPIPE


def _value(text: str) -> int | float | bool | str:
    """A --set value as TOML would read it: integer, number, true/false, else text."""
    text = text.strip()
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    if text in ("true", "false"):
        return text == "true"
    return text.strip('"')


def _overrides(scene: str, items: Sequence[str]) -> dict[str, object]:
    """--set NAME=VALUE items: parameters (numbers) or options (``branch=crossed``)."""
    values = {}
    for item in items:
        name, sep, text = item.partition("=")
        if not sep or not name.strip() or not text.strip():
            raise SceneError(f"{scene}: --set {item!r}: expected NAME=VALUE (a parameter "
                             f"with a number, or an option: branch=crossed)")
        values[name.strip()] = _value(text)
    return values


def _cells(text: str) -> int:
    """--max-cells N: a whole number >= 1 (1200000, 1_200_000 or 1.2e6)."""
    try:
        value = float(text.replace("_", "").replace(",", ""))
    except ValueError:
        value = 0.0
    if not (1 <= value < 1e15 and value == int(value)):
        raise argparse.ArgumentTypeError(f"{text!r}: give a whole number of cells >= 1")
    return int(value)


def _warn(scene) -> None:
    for warning in scene.warnings:
        print(f"workbook-gen: warning: {warning}", file=sys.stderr)


def _list(args: argparse.Namespace) -> int:
    from .mechanisms.listing import listing
    sys.stdout.write(listing())
    return 0


def _generate(args: argparse.Namespace) -> int:
    from .scene import load_scene
    scene = load_scene(args.scene, overrides=_overrides(args.scene, args.set), step=args.step,
                       start=args.start, stop=args.stop, name=args.name)
    _warn(scene)
    from .workbook import write_workbook  # after the scene: a bad one need not pay for it
    from .progress import Progress
    with Progress(2 * scene.sweep.rows, desc=f"{scene.name}.xlsx", step="row",
                  delay=1.0) as bar:
        path = write_workbook(scene, args.out, force=args.force, progress=bar.update)
    print(path)
    return 0


def _audit(args: argparse.Namespace) -> int:
    from pathlib import Path
    if len(args.paths) > 1 or Path(args.paths[0]).is_dir():
        return _audit_many(args)
    if not Path(args.paths[0]).exists():
        from .auditor.many import expand
        expand(args.paths)  # the one-line refusal (a pattern that matched nothing says so)
    from .auditor import audit
    from .auditor.report import format_report
    if args.annotate:
        from .auditor.annotate import check_target
        check_target(args.paths[0], args.annotate, force=args.force)  # before the work
    from .auditor import PHASES
    from .progress import Progress
    phases = len(PHASES) - (0 if args.engine else 1)
    with Progress(total=phases, desc="audit", step="phase", delay=1.0) as bar:
        report = audit(args.paths[0], engine=args.engine, progress=bar,
                       max_cells=args.max_cells)
    if args.json:
        print(json.dumps(report.to_json(), allow_nan=False))
    else:
        print(format_report(report, verbose=args.verbose))
    if args.annotate:
        from .auditor.annotate import annotate
        done = annotate(args.paths[0], report, args.annotate, force=args.force)
        print(f"annotated copy: {done}", file=sys.stderr if args.json else sys.stdout)
    return 0 if report.ok else 1


def _audit_many(args: argparse.Namespace) -> int:
    """Several files or folders: one line (or one JSON object) per file, then a total."""
    from .auditor.many import audit_many, expand, total_line
    from .errors import WorkbookReadError
    from .progress import Progress
    if args.annotate:
        raise WorkbookReadError("--annotate takes a single workbook, not several or a folder")
    if args.jobs is not None and args.jobs < 1:
        raise WorkbookReadError(f"--jobs {args.jobs}: give a number of processes >= 1")
    count = len(expand(args.paths))
    results, worst = [], 0
    with Progress(total=count, desc="audit", step="file") as bar:
        for result in audit_many(args.paths, jobs=args.jobs, engine=args.engine,
                                 progress=bar, max_cells=args.max_cells):
            results.append(result)
            worst = max(worst, result.code)
            text = (json.dumps(result.json(), allow_nan=False) if args.json
                    else result.line())
            bar.write(text)
    if not args.json:
        print(total_line(results))
    return worst


def _tradeoff(args: argparse.Namespace) -> int:
    from .scene import load_scene
    from .progress import Progress
    from .tradeoff import format_table, measure, progress_steps, write_tradeoff_workbook
    scene = load_scene(args.scene)
    if args.out:
        from .files import refuse_existing
        from .tradeoff.book import output_path
        refuse_existing(output_path(scene, args.out), args.force)  # before minutes of work
    with Progress(progress_steps(scene), desc="tradeoff", step="run") as bar:
        result = measure(scene, progress=bar)
    if args.json:
        print(json.dumps(result.to_json(), indent=2, allow_nan=False))
    else:
        print(format_table(result))
    if args.out:
        path = write_tradeoff_workbook(result, args.out, force=args.force)
        print(path, file=sys.stderr if args.json else sys.stdout)
    return 0


def _batch(args: argparse.Namespace) -> int:
    import logging
    from pathlib import Path
    from .batching.api import run_batch
    from .terminate import sigterm_raises
    said = logging.StreamHandler(sys.stderr)  # the wait for Dask workers, as it happens
    said.setFormatter(logging.Formatter("workbook-gen: %(message)s"))
    said.setLevel(logging.WARNING)
    logger = logging.getLogger("workbook_gen.batching")
    logger.addHandler(said)
    try:
        with sigterm_raises():
            done = run_batch(args.scene, args.vary, args.design, args.out, args.jobs,
                              summary_only=args.summary_only,
                              sets=_overrides(args.scene, args.set), step=args.step,
                              samples=args.samples, seed=args.seed, audit=args.audit,
                              force=args.force, scheduler=args.scheduler,
                              progress=False if args.quiet else None, timeout=args.timeout)
    finally:
        logger.removeHandler(said)
    failed, kept = done.failed, done.kept
    for name in kept:
        print(f"workbook-gen: kept {Path(done.folder) / name}: it differs from "
              f"what this batch wrote (edited since?), so it was not regenerated; --force "
              f"replaces it", file=sys.stderr)
    if not args.quiet:
        print(f"{done.folder}: {done.count} variants, {done.count - failed} ok"
              + (f", {failed} not ok (see summary.csv)" if failed else "")
              + (f", {len(kept)} file{'s' if len(kept) > 1 else ''} kept as edited"
                 if kept else ""))
    return 1 if failed or kept else 0


def parser() -> argparse.ArgumentParser:
    top = argparse.ArgumentParser(
        prog="workbook-gen",
        description="Planar linkage kinematics as live-formula workbooks, and their audit.")
    top.add_argument("--version", action="version", version=f"workbook-gen {VERSION}")
    sub = top.add_subparsers(dest="command", required=True)

    p = sub.add_parser("list", help="templates, their parameters, inputs and outputs")
    p.set_defaults(run=_list)

    p = sub.add_parser("generate", help="write DIR/<name>.xlsx from a scene file")
    p.add_argument("scene", metavar="SCENE", help="a scene file (TOML), e.g. "
                                                  "templates/sewing_machine.toml")
    p.add_argument("--out", default="outputs", metavar="DIR",
                   help="output folder (default: outputs)")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="override a parameter (l_BC=105) or an option (branch=crossed); "
                        "repeatable")
    p.add_argument("--step", type=float, metavar="X", help="override the sweep step")
    p.add_argument("--start", type=float, metavar="X", help="override the sweep start")
    p.add_argument("--stop", type=float, metavar="X", help="override the sweep stop")
    p.add_argument("--name", metavar="STEM", help="output file stem instead of the scene's "
                                                  "name (a variant beside its baseline)")
    p.add_argument("--force", action="store_true", help="overwrite an existing file")
    p.set_defaults(run=_generate)

    p = sub.add_parser("audit", help="recompute and check every formula cell of a workbook")
    p.add_argument("paths", nargs="+", metavar="PATH",
                   help="workbooks, or folders to search for *.xlsx and *.xlsm")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object per file, one per line (JSON Lines)")
    p.add_argument("--jobs", type=int, metavar="N",
                   help="audit several files in N worker processes (default: all cores)")
    p.add_argument("--annotate", metavar="OUT.xlsx",
                   help="write a copy with every disagreement and finding highlighted and "
                        "explained in a cell comment (formulas and cached values untouched)")
    p.add_argument("--force", action="store_true", help="overwrite the --annotate file")
    p.add_argument("--engine", choices=["libreoffice"],
                   help="also recalculate the file in LibreOffice headless and compare")
    p.add_argument("--verbose", action="store_true",
                   help="list every column, disagreeing cell, cell not checked and finding")
    p.add_argument("--max-cells", type=_cells, metavar="N",
                   help="read workbooks of up to N cells (default 1,200,000; about 1 KB "
                        "of memory a cell)")
    p.set_defaults(run=_audit)

    p = sub.add_parser("tradeoff", help="speed against accuracy on a scene: step, method, "
                                        "derivatives, precision")
    p.add_argument("scene", metavar="SCENE", help="a scene file (TOML)")
    p.add_argument("--json", action="store_true", help='print {"rows": [...]} as JSON')
    p.add_argument("--out", metavar="DIR",
                   help="also write DIR/<name>_tradeoff.xlsx (table and charts)")
    p.add_argument("--force", action="store_true", help="overwrite an existing workbook")
    p.set_defaults(run=_tradeoff)

    p = sub.add_parser("batch", help="design variants: one workbook per variant and a summary")
    p.add_argument("scene", metavar="SCENE", help="a scene file (TOML)")
    p.add_argument("--vary", action="append", default=[], metavar="NAME=SPEC",
                   help="START:STOP:STEP (grid), V1,V2,... (list: numbers, or an option's "
                        "values, branch=open,crossed), normal:MEAN:SD or uniform:LO:HI (with "
                        "--samples); repeatable: full factorial, last fastest")
    p.add_argument("--design", metavar="FILE", help="CSV (',' or ';') or xlsx: a header of "
                                                    "parameter and option names (and "
                                                    "'variant'), one row per variant")
    p.add_argument("--samples", type=int, metavar="N", help="random variants to draw")
    p.add_argument("--seed", type=int, metavar="S", help="seed of the draw (numpy default_rng)")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="override a parameter or an option for every variant (repeatable)")
    p.add_argument("--step", type=float, metavar="X", help="override the sweep step")
    p.add_argument("--out", default="outputs", metavar="DIR",
                   help="writes DIR/<name>-batch/ (default: outputs)")
    p.add_argument("--jobs", type=int, metavar="N", help="worker processes (default: all cores)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run on a Dask cluster, e.g. tcp://host:8786")
    p.add_argument("--timeout", type=float, metavar="S",
                   help="with --scheduler: give up (exit 2) if no Dask worker has connected "
                        "after S seconds (default: wait)")
    p.add_argument("--summary-only", action="store_true",
                   help="only the summaries, all variants evaluated at once")
    p.add_argument("--audit", action="store_true", help="audit each workbook where it is made")
    p.add_argument("--force", action="store_true",
                   help="replace a batch folder made by another command, and files "
                        "edited since the batch wrote them")
    p.add_argument("--quiet", action="store_true", help="no progress bar, no closing line")
    p.set_defaults(run=_batch)
    return top


def _os_error(exc: OSError) -> str:
    """An OSError the commands did not foresee (a folder made read-only mid-run, a full
    disk), as one line: the path(s) and the system's reason."""
    paths = " -> ".join(str(p) for p in (exc.filename, exc.filename2) if p is not None)
    return f"{paths}: {exc.strerror or exc}" if paths else str(exc.strerror or exc)


def _silence_output() -> None:
    """After a broken pipe: point stdout and stderr at /dev/null, so that Python's
    flush at exit does not complain about the reader that went away."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    for stream in (sys.stdout, sys.stderr):
        try:
            os.dup2(devnull, stream.fileno())
        except (OSError, ValueError):
            pass
    os.close(devnull)


def main(argv: Sequence[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        code = args.run(args)
        sys.stdout.flush()  # a closed pipe is noticed here, not at the interpreter's exit
        return code
    except WorkbookGenError as exc:
        print(f"workbook-gen: error: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # `audit --verbose | head`: the reader has what it wanted
        _silence_output()
        return EXIT_BROKEN_PIPE
    except OSError as exc:
        print(f"workbook-gen: error: {_os_error(exc)}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("workbook-gen: interrupted", file=sys.stderr)
        return 130
    except Terminated:
        print("workbook-gen: terminated (SIGTERM)", file=sys.stderr)
        return EXIT_CODE


if __name__ == "__main__":
    sys.exit(main())
