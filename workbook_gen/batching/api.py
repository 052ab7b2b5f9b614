"""``batch()``: design variants of a scene, one workbook each and a summary.

Everything a user can get wrong (the scene, --set, --vary, --design, the output
folder) is checked before anything is written.  Then the variants still to make go
to a runner; this process writes each workbook as it arrives (atomically) and notes
it in the folder's journal; the summaries are written last.
"""

from __future__ import annotations

import contextlib
import functools
import gc
import hashlib
import json
import logging
import math
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Mapping, Sequence, Union

from .. import terminate
from ..errors import SceneError
from ..mechanisms import get_template
from ..scene import Scene, parse_scene, read_scene_text
from ..files import write_bytes_atomically
from ..pruning import select
from ..version import VERSION
from . import runners
from .folder import Folder, Resumed, digest
from .job import JobSpec, run_chunk
from .rows import ROW_COUNTS
from .summary import SummaryWriter
from .summary_only import SummaryJob, block_size, summary_rows
from .table import Table
from .specs import shown
from .variants import Design, Variant, flag, from_design, from_specs

log = logging.getLogger(__name__)
_FIRST_BLOCK = 32   # variants in the first --summary-only block


def _read(scene: str | Path | Scene) -> tuple[str, str, dict, float | None]:
    """(text, source, --set, --step) of a scene path or a loaded Scene."""
    if isinstance(scene, Scene):
        given = getattr(scene, "cli", None) or {}
        sets = dict(given.get("overrides", {})) if given else {
            k: float(v) for k, _, v in (o.partition("=") for o in scene.overrides)}
        return scene.text, scene.source, sets, scene.sweep.step
    return read_scene_text(scene), str(scene), {}, None


def _design(base: Scene, vary, design, sets, samples, seed, cli: bool) -> Design:
    names = [p.name for p in base.template.parameters]
    options = get_template(base.mechanism).options
    if design is not None:
        if vary:
            raise SceneError(f"{flag('design', cli)} and {flag('vary', cli)}: give one of them "
                             f"(put every varied parameter in the design file)")
        if samples is not None or seed is not None:
            raise SceneError(f"{flag('samples', cli)} and {flag('seed', cli)} go with a random "
                             f"{flag('vary', cli)}, not {flag('design', cli)}")
        return from_design(design, names, list(sets), options, cli)
    return from_specs(vary if vary is not None else (), names, list(sets), samples, seed,
                      options, cli)


def _option_models(base: Scene, plan: Design, text: str, source: str, sets, step) -> list:
    """The models of the option combinations the variants ask for, other than the
    scene's own (a combination the scene refuses has none: its variants are refused)."""
    if not plan.options:
        return []
    seen, models = set(), []
    for variant in plan.variants:
        key = tuple((n, v) for n, v in variant.values if n in plan.options)
        if key in seen:
            continue
        seen.add(key)
        try:
            scene = parse_scene(text, source, {**sets, **dict(key)} or None, step)
        except SceneError:
            continue
        models.append(select(scene.template, scene.outputs))
    return models


def variants_json(variants: Sequence[Variant]) -> str:
    """``json.dumps([[label, [[name, repr(value)], ...]], ...])`` of the variants (the
    folder's key: same text), written directly: a float's repr needs no escaping, a
    label of ASCII letters and digits none either (others go through json). A grid's
    values repeat: each (name, value) pair's text is made once."""
    return "".join(_json_pieces(variants))


def variants_digest(variants: Sequence[Variant]) -> str:
    """``digest(variants_json(variants).encode())``, the text hashed as it is made (a
    million variants' text is ~50 MB)."""
    hasher = hashlib.sha256()
    pieces: list[str] = []
    for piece in _json_pieces(variants):
        pieces.append(piece)
        if len(pieces) >= 4096:
            hasher.update("".join(pieces).encode())
            pieces = []
    hasher.update("".join(pieces).encode())
    return hasher.hexdigest()


def _json_pieces(variants: Sequence[Variant]):
    pairs: dict[tuple[str, float], str] = {}
    yield "["
    for n, v in enumerate(variants):
        label = v.label
        label = f'"{label}"' if label.isascii() and label.isalnum() else json.dumps(label)
        cells = []
        for pair in v.values:
            text = pairs.get(pair)
            if text is None:
                text = f'[{json.dumps(pair[0])}, "{pair[1]!r}"]'
                if pair[1]:  # 0.0 and -0.0 are equal keys, and their texts differ
                    pairs[pair] = text
            cells.append(text)
        yield f"{', ' if n else ''}[{label}, [{', '.join(cells)}]]"
    yield "]"


def _vary_words(vary) -> list[str]:
    """``vary`` as the command line would spell it (the About sheet's command)."""
    if not isinstance(vary, Mapping):
        return list(vary or ())
    words = []
    for name, value in vary.items():
        if not isinstance(value, str):
            items = value.tolist() if hasattr(value, "tolist") else value
            items = list(items) if isinstance(items, (list, tuple, range)) else [items]
            value = ",".join(str(shown(v)) for v in items)
        words.append(f"{name}={value}")
    return words


def _command(source, vary, design, sets, step, samples, seed, summary_only, audit) -> str:
    parts = ["workbook-gen batch", source]
    parts += [f"--vary {v}" for v in _vary_words(vary)]
    parts += [f"--design {design}"] if design is not None else []
    parts += [f"--samples {samples}"] if samples is not None else []
    parts += [f"--seed {seed}"] if seed is not None else []
    parts += [f"--set {k}={v}" for k, v in sets.items()]
    parts += [f"--step {step:g}"] if step is not None else []
    parts += ["--summary-only"] if summary_only else []
    parts += ["--audit"] if audit else []
    return " ".join(parts)


def _progress(total: int, initial: int, enabled: bool | None):
    if enabled is None:
        enabled = sys.stderr.isatty()
    if not enabled:
        return None
    from tqdm import tqdm
    return tqdm(total=total, initial=initial, unit="variant", file=sys.stderr,
                dynamic_ncols=True, smoothing=0.1)


# What ``vary`` takes: {name: values} or the command line's "NAME=SPEC" texts.
Vary = Union[Mapping[str, Union[str, float, bool, Sequence[Union[float, str, bool]], range]],
             Sequence[str], None]


def batch(scene: str | Path | Scene, vary: Vary = None,
          design: str | Path | None = None, out: str | Path = "outputs",
          jobs: int | None = None, client=None, summary_only: bool = False, *,
          sets: Mapping[str, object] | None = None, step: float | None = None,
          samples: int | None = None, seed: int | None = None, audit: bool = False,
          force: bool = False, scheduler: str | None = None,
          progress: bool | None = None, timeout: float | None = None):
    """Make ``out/<name>-batch/<name>-0001.xlsx`` ... and ``summary.csv``/``summary.xlsx``;
    return the summary as a pandas DataFrame: its columns the summary's names without
    the units the files' headers carry (``y_C_max``; ``frame.attrs["units"]``:
    ``{"y_C_max": "mm", ...}``), ``frame.attrs["folder"]``: the folder,
    ``frame.attrs["failed"]``: how many variants are not ``ok``, ``frame.attrs["kept"]``:
    the files a rerun kept because they differ from what the batch wrote, edited since
    (``force`` replaces them).

    ``vary``: a mapping from a parameter or option name to its values, varied as a full
    factorial in the mapping's order (the last fastest).  Values are a list, tuple,
    range or numpy array of numbers (``{"l_AB": [30, 32]}``, ``{"l_BC": range(95, 106)}``)
    or of an option's values (``{"branch": ["open", "crossed"], "balance": [True,
    False]}``), or a text as after ``--vary NAME=`` on the command line: a grid
    ``"95:105:0.5"`` (start to stop inclusive), a list ``"30,32,34"``/``"open,crossed"``,
    or a distribution ``"normal:32:0.05"`` / ``"uniform:31.9:32.1"`` (every varied name
    random, with ``samples`` and ``seed``).  A list of the command line's ``"NAME=SPEC"``
    texts is taken too.  ``design``: a CSV (``,`` or ``;`` separated; with ``;`` a
    decimal comma is read) or xlsx table, one variant per row, columns named for
    parameters and options.  ``sets``: parameters or options for every variant.
    ``jobs``: local worker processes (default: all cores); ``client`` (a Dask
    ``Client``) or ``scheduler`` (its address) runs the variants on a Dask cluster; with
    no worker connected it logs a warning after a few seconds and waits, at most
    ``timeout`` seconds (None: no limit).  ``summary_only``: the summary without the workbooks, evaluated over all variants at
    once.  Raises SceneError (bad input, the message naming the argument) before
    writing anything."""
    return run_batch(scene, vary, design, out, jobs, client, summary_only, sets=sets,
                     step=step, samples=samples, seed=seed, audit=audit, force=force,
                     scheduler=scheduler, progress=progress, timeout=timeout, cli=False).frame()


@dataclass(frozen=True)
class Finished:
    """A finished batch: its folder, its number of variants, those not ok (or failing
    their audit), and its table (``frame``: the summary as a DataFrame)."""

    folder: Path
    count: int
    failed: int
    table: Table
    kept: tuple[str, ...] = ()  # the files a rerun kept: they differ from what it wrote

    def frame(self):
        """The summary as a DataFrame: from the table, or from summary.parquet when the
        table kept no rows (--summary-only; a figure that holds texts as in the Parquet
        file)."""
        if self.table.keep:
            frame = self.table.frame()
        else:
            frame = _parquet_frame(self.folder / "summary.parquet", self.table)
        frame.attrs["folder"] = str(self.folder)
        frame.attrs["failed"] = self.failed
        frame.attrs["kept"] = list(self.kept)
        return frame


def _parquet_frame(path: Path, table: Table):
    import pandas as pd
    frame = pd.read_parquet(path)
    frame.columns = table.columns    # the names without the headers' units
    frame["variant"] = frame["variant"].astype(str)
    for name in ROW_COUNTS:
        if name in frame:
            frame[name] = frame[name].astype("Int64")
    frame.attrs["units"] = dict(table.units)
    return frame


def run_batch(scene, vary=None, design=None, out="outputs", jobs=None, client=None,
              summary_only=False, *, sets=None, step=None, samples=None, seed=None,
              audit=False, force=False, scheduler=None, progress=None, timeout=None,
              cli=True):
    """``batch()`` without making the DataFrame (the command line: a million variants'
    summary need not be read back), its messages naming the command line's flags when
    ``cli``."""
    with _no_cycle_collection():
        return _batch(scene, vary, design, out, jobs, client, summary_only, sets, step,
                      samples, seed, audit, force, scheduler, progress, timeout, cli)


@contextlib.contextmanager
def _no_cycle_collection():
    """The cycle collector off while a batch runs: it makes no reference cycles worth
    collecting, but holds ~10^5 variants and 10^7 summary cells whose allocation made
    the collector walk them all again and again (~10% of the command's time)."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def _batch(scene, vary, design, out, jobs, client, summary_only, sets, step, samples, seed,
           audit, force, scheduler, progress, timeout, cli):
    text, source, given_sets, given_step = _read(scene)
    sets = {**given_sets, **dict(sets or {})}
    step = step if step is not None else given_step
    if summary_only and audit:
        raise SceneError("--audit checks workbooks; --summary-only makes none" if cli else
                         "audit checks workbooks; summary_only makes none")
    if jobs is not None and jobs < 1:
        raise SceneError(f"{flag('jobs', cli)} must be >= 1, got {jobs}")
    if jobs is not None and (client is not None or scheduler is not None):
        raise SceneError(f"{flag('jobs', cli)} and {flag('scheduler', cli)}"
                         f"{'' if cli else ' (or client)'}: give one (the cluster's workers "
                         f"do the work)")
    if timeout is not None and (client is None and scheduler is None):
        raise SceneError(f"{flag('timeout', cli)} goes with {flag('scheduler', cli)}"
                         f"{'' if cli else ' (or client)'} (how long to wait for a Dask "
                         f"worker)")
    if timeout is not None and not timeout > 0:
        raise SceneError(f"{flag('timeout', cli)} must be > 0 seconds, got {timeout:g}")
    base = parse_scene(text, source, sets or None, step)
    plan = _design(base, vary, design, sets, samples, seed, cli)
    folder_path = Path(out) / f"{base.name}-batch"
    width = max(4, len(str(len(plan))))
    spec = JobSpec(text, source, tuple(sets.items()), step, str(folder_path), base.name,
                   width, audit)
    identity = {"version": VERSION, "scene": source, "text": text, "sets": sorted(
        (k, repr(v)) for k, v in sets.items()), "step": step, "summary_only": summary_only,
        "audit": audit, "names": list(plan.names), "count": len(plan),
        "variants": variants_digest(plan.variants)}
    folder = Folder(folder_path, base.name, identity)
    resume = folder.check(force)
    own = runners.connect(scheduler, timeout) if scheduler is not None and client is None else None
    command = _command(source, vary, design, sets, step, samples, seed, summary_only, audit)
    writer = None
    kept: list[str] = []
    try:
        if client is not None or own is not None:
            runners.wait_for_workers(own if client is None else client, timeout)
        folder_path.mkdir(parents=True, exist_ok=True)
        with folder.locked():
            folder.start(resume, command)
            models = _option_models(base, plan, text, source, sets, step) or [
                select(base.template, base.outputs)]
            defaults = {**base.parameters, **{o.name: base.options.get(o.name, o.default)
                                              for o in get_template(base.mechanism).options}}
            table = Table(plan, models[0], defaults, others=models[1:],
                          keep=not summary_only)
            writer = SummaryWriter(table, folder_path / "summary.csv",
                                   folder_path / "summary.xlsx")
            runner = runners.pick(jobs, client or own)
            if summary_only:
                _summaries_only(spec, plan, table, runner, progress, writer)
            else:
                kept += _workbooks(spec, plan, table, runner, folder, resume, progress)
            terminate.check()
            writer.finish(_about(command, source, plan, table, summary_only, base.name,
                                 width, text),
                          place=functools.partial(_place, folder, kept))
    except BaseException:
        if writer is not None:
            writer.abort()
        raise
    finally:
        if own is not None:
            own.close()
    return Finished(folder_path, len(plan), table.failed_count(), table, tuple(kept))


def _place(folder: Folder, kept: list[str], temporary: Path, target: Path) -> None:
    if not folder.place_summary(temporary, target):
        log.info("%s differs from what this batch wrote: kept", target)
        kept.append(target.name)


def _about(command, source, plan, table, summary_only, name, width, text):
    return [("command", command), ("scene file", source),
            ("generator", f"workbook-gen {VERSION}"),
            ("variants", f"{len(plan)} ({plan.kind}); varied: {', '.join(plan.names)}"),
            ("statuses", _counts(table)), ("workbooks", "none (--summary-only)" if summary_only
                                           else f"{name}-{'0' * (width - 1)}1.xlsx ..."),
            ("scene as given", text)]


def _counts(table: Table) -> str:
    statuses, fails = table.tally()
    return (f"ok {statuses['ok']}, partial {statuses['partial']}, refused "
            f"{statuses['refused']}" + (f", audit failed {fails}" if fails else ""))


def _summaries_only(spec: JobSpec, plan: Design, table: Table, runner, progress,
                    writer: SummaryWriter) -> None:
    bar = _progress(len(plan), 0, progress)
    try:
        # A small first block: a local pool runs it in this process to warm the caches
        # its forked workers inherit, before they start (a block's numbers do not depend
        # on how the variants are cut into blocks).
        size = block_size(spec)
        first = min(size, _FIRST_BLOCK, len(plan.variants))
        parts = ([plan.variants[:first]] if first else []) + runners.chunks(
            plan.variants[first:], size)
        job = SummaryJob(spec, plan.names, tuple(table.values), frozenset(table.figures),
                         plan.options, table.text_options,
                         tuple((n, table.defaults_shown[n]) for n in plan.names))
        with contextlib.closing(runner.run(summary_rows, job, parts)) as run:
            for part, (block, text) in run:
                table.put_block(part, block)
                if text is not None:  # formatted by the worker: written as soon as in order
                    writer.add(part[0].index, len(part), text, part, block)
                elif not table.keep:
                    raise RuntimeError("a block of variants not consecutive: the summary "
                                       "keeps no rows to write it from")
                if bar is not None:
                    bar.update(len(part))
                terminate.check()
    finally:
        if bar is not None:
            bar.close()


def workbook_chunks(todo: Sequence[Variant], jobs: int) -> list[Sequence[Variant]]:
    """The variants cut into the chunks a runner is given: the first alone (a local pool
    runs it in this process to warm the caches its forked workers inherit: one variant
    is enough, and the other cores wait meanwhile), then chunks of up to 8 variants (a
    quarter of each worker's share at most), the last two such chunks per worker cut
    into chunks of at most 2 variants so that the workers finish together."""
    if not todo:
        return []
    first, rest = todo[:1], todo[1:]
    size = max(1, min(8, math.ceil(len(rest) / (4 * jobs))))
    tail = min(len(rest), 2 * jobs * size)
    bulk, last = rest[:len(rest) - tail], rest[len(rest) - tail:]
    return [first] + runners.chunks(bulk, size) + runners.chunks(last, min(size, 2))


def _workbooks(spec: JobSpec, plan: Design, table: Table, runner, folder: Folder,
               resume: bool, progress) -> list[str]:
    """Make the workbooks still to make; the names of those kept because they differ
    from what the batch wrote (a rerun never destroys work)."""
    found = folder.finished() if resume else Resumed()
    for variant in plan.variants:
        if variant.index in found.rows:
            table.put(variant, found.rows[variant.index])
    kept = list(found.edited.values())
    todo = [v for v in plan.variants if v.index not in found.rows]
    log.info("%d variants, %d complete, %d to make", len(plan), len(found.rows), len(todo))
    bar = _progress(len(plan), len(found.rows), progress)
    journal = folder.journal()
    jobs = getattr(runner, "jobs", 1)
    by_index = {v.index: v for v in todo}
    try:
        with contextlib.closing(runner.run(run_chunk, spec, workbook_chunks(todo, jobs))) as run:
            for _, outcomes in run:
                for outcome in outcomes:
                    if outcome.data is not None:
                        name = outcome.row["file"]
                        if not (resume and (folder.path / name).exists()):
                            write_bytes_atomically(folder.path / name, outcome.data, force=True)
                        elif folder.differs(name, outcome.data):
                            kept.append(name)  # not the batch's: the journal says what is
                    journal.add(outcome.index, outcome.data, outcome.row)
                    table.put(by_index[outcome.index], outcome.row)
                if bar is not None:
                    bar.update(len(outcomes))
                terminate.check()
    finally:
        journal.close()
        if bar is not None:
            bar.close()
    return sorted(kept)  # numbered names of one width: in variant order
