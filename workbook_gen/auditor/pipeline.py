"""The audit's pipeline: read, evaluate, compare, the reference model, findings, the
LibreOffice engine; ``audit(path)`` runs it (the package face, ``auditor/__init__.py``,
exports it)."""

from __future__ import annotations

import gc
import time
from itertools import compress, repeat
from operator import contains, itemgetter
from dataclasses import dataclass
from pathlib import Path


from ..cellref import cell_name, column_letters
from ..errors import FormulaSyntaxError, WorkbookGenError, WorkbookReadError
from ..evaluator import evaluate_cells
from ..evaluator.keys import column_groups, pick
from ..evaluator.relnames import relative_names
from ..evaluator.store import FLOAT, type_mask, value_scale
from ..evaluator.volatile import Clock
from ..formula import ast, parse
from ..formula.functions import dialect_of
from ..forked import Forked
import numpy as np

from .caught import caught
from .dialects import against_libreoffice, libreoffice_explains
from .compare import ColumnStats, compare, compare_numbers
from .findings import find as find_findings
from .inputs import AuditInputs, read_inputs
from .mechanics import check_mechanics, noise_trees
from .recomputed import Recomputed
from .report import AuditReport, EngineResult, Mismatch
from .saved import last_saved
from .sources import Stale, arrays_once, rectangles, settle
from .tally import NO_CACHED_VALUE, absent as absent_values, no_cached_findings, tally
from .structure import check_structure



PHASES = ("read", "evaluate", "compare", "reference", "findings", "engine")


def _number_if_bool(v):
    return float(v) if isinstance(v, bool) else v


def _local_evaluation(inputs: AuditInputs, seen: dict | None = None, dialect: str = "excel",
                      saved: Clock | None = None):
    """Cells that read ranges (MAX, MIN, SUM, INDEX, MATCH over a column), recomputed
    from the cached values they read.

    An aggregate sees only its range: the maximum of residuals near 1e-16, or the
    row where a minimum occurs among near-ties, moves with the last bit of every
    cell of the range, which says nothing about the aggregate's own formula.  Each
    range cell is checked against its cached value on its own; the aggregate is
    checked against what it makes of those cached values (or of ``seen``: the
    values another engine computed)."""
    keys = set(compress(inputs.formulas, map(contains, inputs.formulas.values(), repeat(":"))))
    names = inputs.book.defined_names
    read: set[tuple[str, int]] = set()  # the (sheet, column) pairs those formulas read
    # (print areas and titles are names of their sheets too: they matter only where used)
    local_names = {n.upper() for s in inputs.book.sheets for n in s.defined_names}
    relative = None
    everything = False  # 3-D, structured references, sheet-scoped and relative names: all
    for key in keys:
        try:
            node = parse(inputs.formulas[key])
        except FormulaSyntaxError:
            continue
        used = {n.name.upper() for n in ast.walk(node) if isinstance(n, ast.Name)}
        if used and relative is None:  # (names read from the calling cell: relnames)
            relative = relative_names(names)
        if any(isinstance(n, (ast.Sheets3D, ast.StructRef, ast.RefOp)) for n in ast.walk(node)
               ) or used & local_names or used & (relative or set()):
            everything = True
            break
        for sheet, _, c1, _, c2 in rectangles(node, key[0], names):
            read.update((sheet, c) for c in range(c1, c2 + 1))
    given = seen or inputs.cached
    if everything:  # formula and constant cells are apart: the same as below, at C speed
        cached = dict(inputs.constants)
        cached.update(given)
        for k in keys:
            if k in given:
                del cached[k]
    else:
        cached = _in_columns(inputs.constants, read)
        cached.update(_in_columns(given, read, keys))
    if saved is not None:  # volatile cells settle on the values ``given``
        saved = Clock(given, saved.saved, saved.agree, saved.date1904)
    return evaluate_cells({k: inputs.formulas[k] for k in keys}, cached, names,
                          dialect=dialect, book=inputs.book_info(), saved=saved,
                          iterate=inputs.book.iterate, texts=inputs.formulas,
                          array_texts=inputs.arrays, stored=True)


def _in_columns(cells: dict, columns: set[tuple[str, int]], leave=()) -> dict:
    """The items of ``cells`` {(sheet, row, col): value} in ``columns`` (sheet, col), but
    for the keys in ``leave`` (C loops: a few hundred thousand cells, a few columns)."""
    out = dict(compress(cells.items(), map(columns.__contains__, map(_SHEET_COL, cells))))
    for key in leave:
        out.pop(key, None)
    return out


_SHEET_COL = itemgetter(0, 2)


def audit(path: str | Path, *, engine: str | None = None, vectorize: bool = True,
          progress=None, max_cells: int | None = None) -> AuditReport:
    """Recompute and check every formula cell of the workbook at ``path``.

    ``progress(label)`` is called as each of the PHASES ends (the last only with
    ``engine``). ``max_cells``: read a workbook of more cells than the reader's default
    ceiling (``xlsx.limits.MAX_CELLS``, 1.2 million), at about 0.8 KB and 44 us a cell."""
    if max_cells is not None and (isinstance(max_cells, bool) or not isinstance(max_cells, int)
                                  or max_cells < 1):
        raise WorkbookGenError(f"max_cells {max_cells!r}: give a whole number of cells >= 1")
    # The collector would rescan the ~2 million objects read off a large workbook each
    # time the heap grows by a quarter (0.3-0.5 s at 200k cells); they hold no cycles
    # worth collecting before the audit ends (as the reader, which pauses it too).
    paused = gc.isenabled()
    gc.disable()
    try:
        with caught() as said:
            report = _audit(path, engine, vectorize, progress, max_cells)
        report.warnings = said
        return report
    finally:
        if paused:
            gc.enable()


def _audit(path, engine, vectorize, progress, max_cells=None) -> AuditReport:
    step = progress or (lambda label: None)
    started = time.perf_counter()
    timings: dict[str, float] = {}
    inputs = read_inputs(path, group=vectorize, max_cells=max_cells)
    timings["read"] = time.perf_counter() - started
    step("read")
    t = time.perf_counter()
    semantics = dialect_of(inputs.book.application)  # the engine that saved the file
    clock = Clock(inputs.cached, last_saved(path), _agree, inputs.book.date1904)
    # the aggregates' local evaluation needs nothing of the full evaluation: on the
    # other core
    aside = Forked(_beside_evaluation, inputs, semantics, clock)
    try:
        evaluation = evaluate_cells(inputs.formulas, inputs.constants, inputs.book.defined_names,
                                    vectorize=vectorize, uncheckable=inputs.uncheckable(),
                                    dialect=semantics, book=inputs.book_info(),
                                    arrays=inputs.arrays, saved=clock,
                                    iterate=inputs.book.iterate, grouped=inputs.grouped,
                                    tables=inputs.data_tables, stored=True)
    except WorkbookReadError as exc:  # the evaluator's refusal (cost), named by file
        aside.cancel()
        raise WorkbookReadError(f"{path}: {exc}") from None
    except BaseException:
        aside.cancel()
        raise
    timings["evaluate_all"] = time.perf_counter() - t

    local = aside.result()
    timings["evaluate_all"] = time.perf_counter() - t
    # "parse": cutting the columns into runs equal in R1C1 form (the formula text analysis);
    # "evaluate": ordering, vectorised and cell-by-cell evaluation (both passes)
    phases = [evaluation.seconds, local.seconds]
    timings["parse"] = inputs.grouping_seconds + sum(p.get("grouping", 0.0) for p in phases)
    timings["evaluate"] = sum(p.get(k, 0.0) for p in phases for k in ("graph", "vector", "scalar"))
    step("evaluate")

    value_of = Recomputed(evaluation, inputs.constants)

    # the reference model's check and the findings on the other core while this one
    # compares (their times their own, spent alongside); is_formula would make the
    # Table's Cell objects for its input columns
    trees = noise_trees(inputs.book, evaluation.runs,
                        lambda k: k in inputs.formulas or k in inputs.broken
                        or k in inputs.array_master)
    aside = Forked(_beside_compare, inputs, evaluation.runs, value_of,
                   evaluation.column_values, trees)
    try:
        absent = absent_values(inputs.cached)
        without = bool(absent) and len(absent) == len(inputs.cached)  # none has a value
        if absent:  # an empty cell where the formula gives "" shows what it would show
            values = evaluation.values
            absent = [k for k in absent if k not in values or k in evaluation.not_checked
                      or values[k] not in (None, "")]
        mismatches, columns, counts, skipped, explained, max_abs, max_rel = _compare(
            inputs, evaluation, local, semantics, value_of, timings, absent)
        step("compare")
        findings = check_structure(inputs, evaluation, cell_name)
        findings += no_cached_findings(inputs, absent, cell_name)
        (mechanics, timings["reference"]), (seen, timings["findings"]) = aside.result()
        findings += seen
    except BaseException:
        aside.cancel()
        raise
    step("reference")
    step("findings")
    engine_result = (_engine(path, engine, inputs, value_of, evaluation.operands_scale,
                             evaluation.not_checked) if engine else None)
    if engine:
        step("engine")
    not_checked = {cell_name(k): reason for k, reason in sorted(skipped.items())
                   if inputs.is_formula(k)}
    return AuditReport(
        path=str(path), formula_cells=inputs.formula_count, cells_checked=counts.checked,
        mismatches=mismatches, not_checked=not_checked, columns=[columns[k] for k in sorted(columns)],
        max_abs_error=max_abs, max_rel_error=max_rel, findings=findings, mechanics=mechanics,
        libreoffice_semantics=explained, vector_cells=evaluation.groups.vector_cells,
        seconds=time.perf_counter() - started, engine=engine_result, timings=timings,
        macros=inputs.book.vba_project, semantics=semantics,
        by_contract={cell_name(k): o.message for k, o in sorted(evaluation.contract.items())
                     if o.status != "disagrees"},
        application=inputs.book.application, counts=counts,
        saved_without_values=without)


def _timed(fn, *args):
    """``(fn(*args), seconds it took)``."""
    t = time.perf_counter()
    return fn(*args), time.perf_counter() - t


@dataclass
class _Local:
    """What the audit uses of the aggregates' local evaluation (compact, to pickle)."""

    values: dict
    operands_scale: dict
    seconds: dict


def _beside_evaluation(inputs: AuditInputs, dialect: str, clock: Clock):
    """The aggregates' local evaluation (it needs nothing of the full evaluation),
    compact to pickle."""
    local = _local_evaluation(inputs, dialect=dialect, saved=clock)
    return _Local(dict(local.values), dict(local.operands_scale), local.seconds)


def _beside_compare(inputs: AuditInputs, runs, value_of, column_of, trees):
    """((the reference check, seconds), (the findings, seconds)), while the cells are
    compared."""
    return (_timed(check_mechanics, inputs.book, value_of, column_of, trees),
            _timed(find_findings, inputs, runs, cell_name))


def _compare(inputs: AuditInputs, evaluation, local, semantics: str, value_of, timings,
             absent: list):
    """Cached against recomputed, every checked formula cell but those ``absent`` (no
    cached value) and those checked by contract: (mismatches, column statistics, the
    tally, cells LibreOffice's semantics explain, max abs and rel error of the agreeing
    cells)."""
    values, skipped = evaluation.values, evaluation.not_checked
    t = time.perf_counter()
    columns: dict[tuple[str, int], ColumnStats] = {}
    mismatches, explained = [], 0
    max_abs = max_rel = 0.0
    # the cells to check, by column; those whose cached value is a number that the
    # evaluator computed as a whole column are compared as arrays (``fast``)
    evaluated, aggregates = values.keyset, set(local.values)
    keys, cached_values = list(inputs.cached), list(inputs.cached.values())
    aside = set(absent).union(evaluation.contract) if absent or evaluation.contract else ()
    if skipped or aside or not all(map(evaluated.__contains__, keys)):
        keep = [k not in skipped and k not in aside and k in evaluated for k in keys]
        keys, cached_values = list(compress(keys, keep)), list(compress(cached_values, keep))
    groups, all_rows = column_groups(keys)
    fast_all = type_mask(cached_values, FLOAT)
    if aggregates:
        fast_all &= ~np.fromiter(map(aggregates.__contains__, keys), bool, len(keys))
    done = np.zeros(len(keys), bool)
    for sheet, col, idx in groups:
        stats = columns[(sheet, col)] = ColumnStats(sheet, column_letters(col))
        fast = idx[fast_all[idx]]
        if len(fast):
            cached = np.array(pick(cached_values, fast), float)
            plain, recomputed, scale = evaluation.numbers(sheet, col, all_rows[fast])
            if not plain.all():
                fast, cached = fast[plain], cached[plain]
                recomputed, scale = recomputed[plain], scale[plain]
            done[fast] = True
            agree, diff, rel = compare_numbers(cached, recomputed, scale)
            stats.add_many(lambda i: inputs.ref(keys[fast[i]]), agree, rel)
            if agree.any():
                max_abs = max(max_abs, float(diff[agree].max()))
                max_rel = max(max_rel, float(rel[agree].max()))
            for i in np.flatnonzero(~agree):
                k = keys[fast[i]]
                mismatches.append(Mismatch(cell_name(k), inputs.text_of(k), inputs.cached[k],
                                           float(recomputed[i]), float(diff[i]), key=k))
        for key in pick(keys, idx[~done[idx]]):
            cached = inputs.cached[key]
            source = local if key in local.values else evaluation
            recomputed = source.values[key]
            if semantics == "libreoffice":  # no boolean type there: TRUE is stored as 1
                cached, recomputed = _number_if_bool(cached), _number_if_bool(recomputed)
            verdict = compare(cached, recomputed, source.operands_scale.get(key, 0.0))
            if not verdict.agree and libreoffice_explains(inputs, key, value_of, cached):
                explained += 1
                continue
            stats.add(inputs.ref(key), verdict)
            if not verdict.agree:
                mismatches.append(Mismatch(cell_name(key), inputs.text_of(key), cached,
                                           recomputed, verdict.abs_error, key=key))
            else:
                max_abs = max(max_abs, verdict.abs_error)
                max_rel = max(max_rel, verdict.rel_error)
    # volatile cells hold their cached value (their dependents read it): the check was
    # against the function's contract, and a value outside it is a disagreement
    contract_ok = []
    for key, outcome in evaluation.contract.items():
        if outcome.status == "disagrees":
            mismatches.append(Mismatch(cell_name(key), inputs.text_of(key), inputs.cached[key],
                                       outcome.contract, key=key))
        else:
            contract_ok.append(key)
    # aggregates that agree with their cached range, whose full recalculation differs
    stale = {}
    for k in local.values:
        cached = inputs.cached[k]
        if k in skipped or cached is None:
            continue
        if not compare(cached, values[k], evaluation.operands_scale[k]).agree:
            stale[k] = Stale(inputs.text_of(k), cached, values[k])
    disagreeing = [m.key for m in mismatches]
    mismatches = settle(inputs, arrays_once(inputs, mismatches, cell_name), stale, cell_name)
    disagreeing += [m.key for m in mismatches if m.stale]
    not_checked = dict(skipped)
    not_checked.update(inputs.opaque)
    not_checked.update(dict.fromkeys(absent, NO_CACHED_VALUE))
    counts = tally(inputs, keys, disagreeing, not_checked, contract_ok,
                   sum(1 for m in mismatches if m.root))
    timings["compare"] = time.perf_counter() - t
    return mismatches, columns, counts, not_checked, explained, max_abs, max_rel


def _agree(cached, value) -> bool:
    return compare(cached, value, value_scale(cached)).agree


def _engine(path, engine: str, inputs: AuditInputs, value_of, scales,
            scales_skip=()) -> EngineResult:
    if engine != "libreoffice":
        raise WorkbookGenError(f"unknown engine {engine!r} (known: libreoffice)")
    from ..engines.libreoffice import recalculated_values
    started = time.perf_counter()
    theirs = recalculated_values(path)
    seen = {k: theirs.get(k[0], {}).get(inputs.ref(k)) for k in inputs.formulas}
    local = _local_evaluation(inputs, seen, dialect="libreoffice",
                              saved=Clock({}, last_saved(path), _agree))
    return against_libreoffice(inputs, theirs, local, value_of, scales, scales_skip, started,
                               cell_name)
