"""Recompute every formula cell of a workbook: ``evaluate_cells(formulas, constants, names)``.

Each column is cut into runs of formulas equal in R1C1 form (:mod:`grouping`); a run
of two or more rows is compiled once (:mod:`vector`) and evaluated as arrays, any other
formula cell by the scalar reference evaluator (``formula.scalar``). Runs and cells are
ordered by their dependencies (:mod:`graph`); a run that reads its own rows, or takes
part in a cycle of runs, is split into single cells.

Documented choices:
- circular references are followed as Excel follows them with iterative calculation off
  (:mod:`cycles`): a cell on a run-time cycle, and what takes its value, shows 0 (Excel)
  or ``#VALUE!`` (LibreOffice's Err:522 once exported) and is checked against that; each
  cycle is reported with its cells; a cycle of the static references that the values do
  not take is evaluated normally. With iterative calculation on (``iterate``), a run-time
  cycle's component is not checked (Excel's iteration is not modelled);
- every cell that cannot be recomputed, and every cell that reads one (directly or
  through others), is in ``not_checked`` with the reason (:mod:`taint`); given ``saved``,
  such a cell with a cached value holds it for its readers, which are then checked (the
  consistency rule of :mod:`taint`);
- a formula that does not parse gets ``#NAME?`` and its message in ``syntax_errors``;
- an external reference (``[1]Sheet!A1``) reads the values the file caches of the other
  workbook (``book.external``); the cell is in ``external``, and not checked where the
  cache lacks a cell it reads (``fx.Unanswered``, as a cube function the file's OLAP cache
  does not answer); one that does not parse gives ``#REF!``;
- an unsupported function gives ``#NAME?`` where it is evaluated; a volatile function
  (NOW, RAND, OFFSET, INDIRECT, ...) is evaluated and its cells listed in ``volatile``;
  given ``saved`` (the cached values and the file's last save), a cell whose value
  changes at every recalculation (TODAY, NOW, RAND, RANDBETWEEN) is checked against the
  function's contract (:mod:`volatile`, outcome in ``contract``) and keeps its cached
  value, which its dependents read;
- ``dialect`` is the semantics of the engine that saved the file ("excel" or
  "libreoffice": see ``formula.functions.dialect``);
- a reference to a sheet that has no cells reads empty cells.
"""

from __future__ import annotations

import dataclasses
import functools
import logging
import re
import time
from collections.abc import Mapping, Sequence
from operator import itemgetter

import numpy as np

from workbook_gen.errors import FormulaSyntaxError
from workbook_gen.evaluator import calls, cycles, graph, volatile as vol, whatif
from workbook_gen.evaluator.book import BookInfo, resolve, resolve_fixed, without_missing_sheets
from workbook_gen.evaluator.evaluation import Cell, CellMap, Evaluation
from workbook_gen.evaluator.external import ExternalBooks
from workbook_gen.evaluator.relnames import NameInliner
from workbook_gen.evaluator.taint import Taint
from workbook_gen.evaluator.grouping import Grouped, Run, group_formulas
from workbook_gen.evaluator.store import Names, SheetResolver, Store, value_scale
from workbook_gen.evaluator.tasks import (Task, evaluate_task, reads_only_above, rects,
                                          shapes_of, singles)
from workbook_gen.evaluator.vector import NotVectorizable, compile_block
from workbook_gen.formula import ast
from workbook_gen.formula import functions as fx
from workbook_gen.formula.functions.serials import date_system
from workbook_gen.formula.parser import parse
from workbook_gen.formula.scalar import evaluate
from workbook_gen.xlerror import ExcelError

log = logging.getLogger(__name__)

VOLATILE = fx.VOLATILE | {"NOW", "TODAY", "RAND", "RANDBETWEEN", "RANDARRAY", "OFFSET",
                          "INDIRECT"}
# volatile and not reproducible: the cached value is from another moment or another draw
CHANGING = vol.CHANGING
CYCLE_VALUE = ExcelError.REF
SYNTAX_VALUE = ExcelError.NAME
EXTERNAL_VALUE = ExcelError.REF
_EXTERNAL = re.compile(r"\[[^\]]*\][^!]*!")


def _floats_quiet(fn):
    """Run ``fn`` with numpy's floating-point warnings off: an overflow or an invalid
    operation inside a formula is Excel's #NUM! or #DIV/0!, which the functions return
    from the infinite or NaN result, not a fault to print (``ironcalc__MMULT.xlsx``)."""
    @functools.wraps(fn)
    def quiet(*args, **kwargs):
        with np.errstate(all="ignore"):
            return fn(*args, **kwargs)
    return quiet


@_floats_quiet
def evaluate_cells(formulas: Mapping[Cell, str], constants: Mapping[Cell, object],
                   names: Mapping[str, str], *, vectorize: bool = True,
                   uncheckable: Mapping[Cell, str] | None = None,
                   dialect: str = "excel", book: BookInfo | None = None,
                   arrays: Mapping[Cell, tuple[str, tuple[int, int]]] | None = None,
                   saved: vol.Clock | None = None, iterate: bool = False,
                   grouped: Grouped | None = None,
                   texts: Mapping[Cell, str] | None = None,
                   array_texts: Mapping[Cell, tuple[str, tuple[int, int]]] | None = None,
                   tables: Sequence[whatif.DataTable] = (),
                   stored: bool = False) -> Evaluation:
    """Recompute every formula (texts without '=') of a workbook; see the module doc.

    ``uncheckable``: cells among ``constants`` that are formulas the caller could not
    hand over (with the reason): their readers are not checked either. ``book``: sheet
    order, sheet-scoped names and tables (structured references). ``arrays``: array
    formulas, ``{master cell: (text, (last row, last col))}``; the values of every cell
    they fill are in ``values``. ``saved``: check volatile cells by contract (see above).
    ``iterate``: the workbook enables iterative calculation (cells on a circular reference
    are then not checked). ``grouped``: the runs of exactly ``formulas``, grouped
    already (with ``vectorize``). ``texts``, ``array_texts``: the texts of every formula
    and array formula of the workbook, where some are among ``constants`` (their cached
    values taken as they are): SUBTOTAL, ISFORMULA and spill references (ANCHORARRAY)
    still see them as formulas. ``tables``: data tables (:mod:`whatif`), recomputed
    last (what reads their cells reads the values among ``constants``). ``stored``: the
    texts are as a file stores them (a future function without its ``_xlfn.`` prefix is
    then an unknown name in Excel, :mod:`formula.functions.availability`); otherwise as
    a person types them."""
    if dialect not in fx.registry.DIALECTS:
        raise ValueError(f"unknown dialect {dialect!r}")
    book = book or BookInfo()
    with date_system(book.date1904):  # every serial in the workbook's date system
        return _evaluate_cells(formulas, constants, names, vectorize, uncheckable, dialect,
                               book, arrays, saved, iterate, grouped, texts, array_texts,
                               tables, stored)


def _evaluate_cells(formulas, constants, names, vectorize, uncheckable, dialect, book,
                    arrays, saved, iterate, grouped, texts, array_texts,
                    tables, stored) -> Evaluation:
    sheets = set(map(itemgetter(0), formulas)) | set(map(itemgetter(0), constants))
    sheets |= set(book.sheets)
    sheets |= set(book.unreadable)
    store = Store(sheets, book.sheets)
    store.unreadable = {s.lower() for s in book.unreadable}
    store.hidden = {store.sheet(s): rows for s, rows in book.hidden_rows.items()}
    store.filtered = {store.sheet(s): rows for s, rows in book.filtered_rows.items()}
    store.charset, store.olap, store.topics = book.charset, book.olap, book.topics
    store.external = ExternalBooks(book.external)
    store.stored = stored
    store.all_sheets = list(book.all_sheets or book.sheets)
    store.formula_texts, store.array_formulas = texts or formulas, arrays or array_texts or {}
    store.unparsed = uncheckable or {}
    store.put_constants(constants)
    name_table = Names(dict(names), book.local_names,
                       prepare=lambda node: resolve_fixed(node, book))
    inliner = NameInliner(name_table, wrap=dialect == "excel")
    keys = formulas
    if arrays:
        keys = dict.fromkeys(formulas)
        for (sheet, row, col), (_, (r2, c2)) in arrays.items():
            keys.update(dict.fromkeys((sheet, r, c) for r in range(row, r2 + 1)
                                      for c in range(col, c2 + 1)))
            store.note(sheet, r2, c2)
    if tables:
        keys = dict(keys)
        keys.update(dict.fromkeys(c for t in tables for c in t.cells()))
    result = Evaluation(CellMap(keys, store.get), CellMap(keys, store.scale),
                        store=store, bad_names=dict(name_table.errors))
    taint = Taint(None if saved is None else saved.cached,
                  lambda cell, value: store.put(*cell, value, value_scale(value)))
    for cell, reason in (uncheckable or {}).items():
        _source(result, taint, cell, cell, reason)

    clock = time.perf_counter()
    runs, errors = formula_runs(formulas, vectorize, book, grouped, inliner)
    for run in runs:  # store.note of every formula cell (a run's last is its lowest)
        store.note(run.sheet, run.last, run.col)
    for sheet, row, col in errors:
        store.note(sheet, row, col)
    result.runs = runs
    for cell, message in errors.items():
        if _EXTERNAL.search(formulas[cell]):
            result.external.append(cell)
            store.put(*cell, EXTERNAL_VALUE)
            _source(result, taint, cell, cell, "external reference")
        else:
            result.syntax_errors[cell] = message
            store.put(*cell, SYNTAX_VALUE)
            _source(result, taint, cell, cell, f"formula syntax: {message}")
    known = {s.lower() for s in [*book.sheets, *store.all_sheets]} if book.sheets else set()
    tasks = _tasks(runs, vectorize, store, result, known, dialect)
    tasks += _array_tasks(arrays or {}, book, result, taint, store, inliner, known, dialect)
    _report_functions(tasks, result, name_table, dialect, stored)
    taint.flush()

    result.seconds["grouping"] = time.perf_counter() - clock
    clock = time.perf_counter()
    deps = []
    while True:
        shapes = [shapes_of(u, store, name_table) for u in tasks]
        inputs = [rects(u, s) for u, s in zip(tasks, shapes)]
        deps = graph.build([(u.sheet, u.col, u.first, u.area[0] if u.area else u.last)
                            for u in tasks], inputs,
                           [(i, u.sheet, c, u.first, u.area[0]) for i, u in enumerate(tasks)
                            if u.area for c in range(u.col + 1, u.area[1] + 1)])
        components = graph.order(deps)
        cyclic = [c for c in components if graph.is_cycle(c, deps)]
        chains = set()  # a run reading its own rows above (=A1+1 filled down): in order
        for c in cyclic:
            if (len(c) == 1 and tasks[c[0]].sequential
                    and reads_only_above(tasks[c[0]], shapes[c[0]][0])):
                chains.add(c[0])
                deps[c[0]] = [d for d in deps[c[0]] if d != c[0]]
        split = {u for c in cyclic for u in c if u not in chains
                 and (tasks[u].block is not None or tasks[u].sequential)}
        if not split:
            break
        tasks = [s for i, u in enumerate(tasks)
                 for s in (singles(u) if i in split else [u])]

    result.seconds["graph"] = time.perf_counter() - clock
    if saved is not None and result.volatile:  # the moment of the last recalculation
        vol.moments((((u.sheet, u.first, u.col), u.node) for u in tasks
                     if u.first == u.last and u.area in (None, (u.first, u.col))),
                    saved.cached, saved)
    spent = {"vector": 0.0, "scalar": 0.0}
    for component in components:
        if graph.is_cycle(component, deps):
            _cycle([tasks[u] for u in component], [shapes[u] for u in component], taint,
                   result, store, name_table, dialect, iterate)
            taint.flush()
            continue
        for u in component:
            head = (tasks[u].sheet, tasks[u].first, tasks[u].col)
            by_contract = (saved is not None and (tasks[u].area in (None, head[1:])
                                                  or vol.draws_array(tasks[u].node))
                           and saved.cached.get(head) is not None
                           and _changing(result, head))
            if head in result.unsupported and not by_contract:
                if (head in result.unknown and saved is not None
                        and saved.cached.get(head) is ExcelError.NAME):
                    result.avoided.add(head)
                elif (tasks[u].block is None and tasks[u].area is None
                      and calls.guarded(tasks[u].node)
                      and calls.avoids(tasks[u].node, head, store, name_table, dialect)):
                    result.avoided.add(head)  # its branch without them: recomputed
            if taint or shapes[u][1] or head in result.unsupported or head in result.volatile:
                _spread(tasks[u], shapes[u], taint, result, by_contract)
            if by_contract:
                _settle(tasks[u], store, name_table, dialect, saved, result)
                taint.flush()
                continue
            clock = time.perf_counter()
            try:
                evaluate_task(tasks[u], store, name_table, dialect)
            except fx.Unanswered as exc:  # read from a cache the file keeps, which lacks it
                for cell in tasks[u].cells():
                    store.put(*cell, ExcelError.NA)
                    _source(result, taint, cell, cell, str(exc))
            except (ArithmeticError, ValueError, TypeError, IndexError, KeyError,
                    AttributeError, RecursionError) as exc:  # a defect must not lose the file
                log.warning("evaluator failure at %s: %r", _where(tasks[u].cells()[0]), exc)
                for cell in tasks[u].cells():
                    store.put(*cell, ExcelError.VALUE)
                    _source(result, taint, cell, cell,
                            f"evaluator failure: {type(exc).__name__}: {exc}")
            spent["vector" if tasks[u].block is not None else "scalar"] += (
                time.perf_counter() - clock)
            taint.flush()
    result.seconds.update(spent)
    if result.cycles:
        _show_circular(store, cycles.shown(dialect))
    whatif.put_tables(tables, store, name_table, dialect,
                      lambda k: resolve(parse(formulas[k]), book, *k), result.not_checked,
                      lambda cell, why: _source(result, taint, cell, cell, why))
    for u in tasks:
        if u.block is not None:
            result.groups.vector_groups += 1
            result.groups.vector_cells += u.last - u.first + 1
        else:
            result.groups.scalar_cells += u.last - u.first + 1 if u.sequential else 1
    result.external.sort()
    return result


def formula_runs(formulas, vectorize: bool, book: BookInfo,
                 grouped: Grouped | None = None, inliner: NameInliner | None = None
                 ) -> tuple[list[Run], dict]:
    """The runs evaluate_cells evaluates (its ``runs``), and the syntax errors; names that
    depend on the calling cell written into the formulas (``inliner``)."""
    if grouped is not None and vectorize:
        grouped.check(len(formulas))
        runs, errors = list(grouped.runs), dict(grouped.errors)
    else:
        runs, errors = _runs(formulas, vectorize)
    if inliner is not None and inliner.active:
        runs = [r for run in runs for r in inliner.inline_run(run)]
    if book.tables:
        runs = [dataclasses.replace(r, node=resolve(r.node, book, r.sheet, r.first, r.col))
                for r in runs]
    return runs, errors


def _runs(formulas, vectorize: bool) -> tuple[list[Run], dict]:
    """Runs of R1C1-identical formulas; without ``vectorize`` every cell parsed alone."""
    if vectorize:
        return group_formulas(formulas)
    runs, errors = [], {}
    for (sheet, row, col), text in formulas.items():
        try:
            runs.append(Run(sheet, col, row, row, parse(text)))
        except FormulaSyntaxError as exc:
            errors[(sheet, row, col)] = str(exc)
    return runs, errors


def _external(node: ast.Node) -> bool:
    return any(isinstance(n, (ast.CellRef, ast.RangeRef, ast.Name))
               and "]" in (n.sheet or "") for n in ast.walk(node))


def _cube(node: ast.Node) -> bool:
    """Does the formula call a function the file's OLAP cache answers?"""
    return any(isinstance(n, ast.Func) and n.name in fx.CACHED_OUTSIDE for n in ast.walk(node))


def _tasks(runs: list[Run], vectorize: bool, store: Store, result: Evaluation,
           sheets=(), dialect: str = "excel") -> list[Task]:
    """``sheets``: the workbook's (lower case), a reference to another is an error."""
    tasks = []
    for run in runs:
        outside = _external(run.node)
        if outside:
            result.external.extend((run.sheet, r, run.col) for r in range(run.first, run.last + 1))
        task = Task(run.sheet, run.col, run.first, run.last,
                    without_missing_sheets(run.node, sheets, dialect))
        if run.last > run.first and (vol.calls(run.node) or calls.guarded(run.node)
                                     or (store.stored and calls.bare_future(run.node))
                                     or outside or _cube(run.node)):
            # (a volatile contract, a branch that may avoid an unsupported call, a future
            # function without its prefix, a cell an outside cache may not answer: cell
            # by cell)
            tasks.extend(singles(task))
            continue
        if vectorize and run.last > run.first:
            try:
                task.block = compile_block(task.node, run.sheet, run.col, run.first,
                                           run.last, store.sheet)
            except NotVectorizable as exc:
                log.debug("cell by cell: %s!%s%s..: %s", run.sheet, run.col, run.first, exc)
        # a run not vectorised is evaluated row after row as one task (a task per cell,
        # each with its tree, would cost ~1.5 KB a cell); split if in a cycle
        task.sequential = task.block is None and run.last > run.first
        tasks.append(task)
    return tasks


def _array_tasks(arrays, book: BookInfo, result: Evaluation, taint: Taint,
                 store: Store, inliner: NameInliner | None = None, sheets=(),
                 dialect: str = "excel") -> list[Task]:
    """One task per array formula, filling its rectangle."""
    tasks = []
    for (sheet, row, col), (text, area) in arrays.items():
        try:
            node = parse(text)
            if inliner is not None:
                node = inliner.inline(node, sheet, row, col)
            node = resolve(node, book, sheet, row, col)
        except FormulaSyntaxError as exc:
            for r in range(row, area[0] + 1):
                for c in range(col, area[1] + 1):
                    store.put(sheet, r, c, SYNTAX_VALUE)
                    _source(result, taint, (sheet, r, c), (sheet, row, col),
                            f"formula syntax: {exc}")
            continue
        result.runs.append(Run(sheet, col, row, row, node))
        tasks.append(Task(sheet, col, row, row, without_missing_sheets(node, sheets, dialect),
                          area=area))
    return tasks


def _report_functions(tasks: list[Task], result: Evaluation, names: Names,
                      dialect: str, stored: bool) -> None:
    for u in tasks:
        called = {n.name for n in ast.walk(u.node) if isinstance(n, ast.Func)}
        if not called:
            continue
        bad = sorted(calls.unsupported(u.node, names, u.sheet, dialect, stored))
        volatile = sorted(called & VOLATILE)
        if not bad and not volatile:
            continue
        unknown = calls.unknown_reason(u.node, bad, dialect, stored)
        for cell in u.cells():
            if bad:
                result.unsupported[cell] = bad
            if unknown:
                result.unknown[cell] = unknown
            if volatile:
                result.volatile[cell] = volatile


def _where(cell: Cell) -> str:
    from workbook_gen.formula.printer import column_letters, quote_sheet
    return f"{quote_sheet(cell[0])}!{column_letters(cell[2])}{cell[1]}"


def _source(result: Evaluation, taint: Taint, cell: Cell, origin: Cell, reason: str,
            hold: bool = True) -> None:
    """``cell`` cannot be recomputed (``origin`` is the cell the reason is about); with
    ``hold``, its cached value stands for it (the consistency rule of :mod:`taint`)."""
    if cell not in result.not_checked:
        result.not_checked[cell] = reason
        if hold:
            taint.mark(cell, origin)
        else:
            taint.add(cell[0], cell[2], cell[1], cell[1], origin)


def _changing(result: Evaluation, cell: Cell) -> list[str]:
    return [f for f in result.volatile.get(cell, ()) if f in CHANGING]


def _task_reason(task: Task, result: Evaluation, bad_names: list[str],
                 by_contract: bool = False) -> str | None:
    """Why a task cannot be recomputed at all, or None."""
    cell = (task.sheet, task.first, task.col)
    if cell in result.unsupported and cell not in result.avoided:
        if cell in result.unknown:
            return result.unknown[cell]
        return "unsupported function " + ", ".join(result.unsupported[cell])
    changing = _changing(result, cell)
    if changing and not by_contract:
        return (f"volatile function {', '.join(changing)}: its value changes at every "
                "recalculation")
    if bad_names:
        name = bad_names[0]
        if name.endswith("!"):  # (names hold no "!")
            return f"reads sheet {name[:-1]!r}, which the file lists without its part"
        return f"defined name {name} does not parse: {result.bad_names.get(name, '')}"
    return None


def _spread(task: Task, shaped: tuple, taint: Taint, result: Evaluation,
            by_contract: bool = False) -> None:
    """Mark the task's cells that cannot be recomputed or read a cell that cannot."""
    shapes, bad_names = shaped
    reason = _task_reason(task, result, bad_names, by_contract)
    if reason is not None:
        for cell in task.cells():
            _source(result, taint, cell, cell, reason)
        return
    n = task.last - task.first + 1
    # a chain (a run reading its own column above each row): every later row may read
    # a row that cannot be recomputed
    chain = task.sequential and any(s.sheet == task.sheet and s.col1 <= task.col <= s.col2
                                    for s in shapes)
    for shape in shapes:
        for lo, hi, origin in taint.hits(shape, n):
            why = result.not_checked.get(origin, "")
            if chain:
                hi = n - 1
            cells = (task.cells() if task.area else
                     [(task.sheet, task.first + i, task.col) for i in range(lo, hi + 1)])
            for cell in cells:
                if cell not in result.not_checked:
                    result.not_checked[cell] = f"depends on {_where(origin)}: {why}"
                    taint.mark(cell, origin)


def _cycle(members: list[Task], shaped: list, taint: Taint, result: Evaluation,
           store: Store, names: Names, dialect: str, iterate: bool) -> None:
    """A cyclic component of the reference graph, evaluated as Excel does with iteration
    off (:mod:`cycles`): the cells on a run-time cycle are reported and hold
    ``cycles.CIRCULAR`` (0 once shown), like what reads them; the other cells are
    computed. With iterative calculation on (not modelled), a run-time cycle makes the
    whole component not checked; so does a component too large or a failure."""
    cells = sorted(c for m in members for c in m.cells())
    found = None
    if len(cells) <= cycles.MAX_CELLS:
        try:
            simple = not any(m.area is not None or vol.calls(m.node) for m in members)
            if simple and cycles.settle(members, Task.cells, lambda c: store.get(*c),
                                        lambda c, v: store.put(*c, v),
                                        lambda task: _fresh(store) or evaluate_task(
                                            task, store, names, dialect)):
                found = []
            else:
                found = cycles.run(members, Task.cells, store, lambda task, view: evaluate_task(
                    task, store, names, dialect, view=view))
        except fx.Unanswered as exc:  # what the file does not cache: the component too
            log.info("not checked in a cycle at %s: %s", _where(cells[0]), exc)
        except (ArithmeticError, ValueError, TypeError, IndexError, KeyError,
                AttributeError, RecursionError) as exc:
            log.warning("evaluator failure in a cycle at %s: %r", _where(cells[0]), exc)
        _fresh(store)  # rectangles read while the values moved
    if found is None or (iterate and found):
        result.cycles.extend(found or [cells])
        where = _where(cells[0]) + (f" and {len(cells) - 1} more" if len(cells) > 1 else "")
        why = ("with iterative calculation on (not modelled)" if found else
               "too large or not evaluated" if len(cells) > cycles.MAX_CELLS else "")
        for cell in cells:
            store.put(*cell, CYCLE_VALUE)
            # (not held: Excel's cached values around a cycle are not mutually consistent)
            _source(result, taint, cell, cell, f"circular reference ({where}) {why}".strip(),
                    hold=False)
        return
    result.cycles.extend(found)
    for task, shape in zip(members, shaped):
        head = (task.sheet, task.first, task.col)
        if taint or shape[1] or head in result.unsupported or head in result.volatile:
            _spread(task, shape, taint, result)
    spoiled = next((c for c in cells if c in result.not_checked), None)
    if spoiled is not None:  # what reads what inside the component is not known: all of it
        why = result.not_checked[spoiled]
        for cell in cells:
            if cell not in result.not_checked:
                result.not_checked[cell] = f"depends on {_where(spoiled)}: {why}"
                taint.add(cell[0], cell[2], cell[1], cell[1], spoiled)


def _fresh(store: Store) -> None:
    store.forget_rects()


def _show_circular(store: Store, shown) -> None:
    """Cells on or fed by a circular reference, as the saving engine shows them."""
    code = ExcelError.CIRC.code
    for (sheet, col), column in list(store.cols.items()):
        for row in np.nonzero(column.err == code)[0].tolist():
            store.put(sheet, row, col, shown, float(column.scale[row]))
    store.forget_rects()


def _settle_area(task: Task, store: Store, names: Names, dialect: str, clock: vol.Clock,
                 result: Evaluation) -> None:
    """An array formula that is just RANDARRAY: each cell's cached value checked against
    the call's contract (vol.check_array), and kept for the dependents to read."""
    cell = (task.sheet, task.first, task.col)
    rows = [[clock.cached.get((task.sheet, r, c)) for c in range(task.col, task.area[1] + 1)]
            for r in range(task.first, task.area[0] + 1)]
    resolver = SheetResolver(store, names, task.sheet)
    try:
        outcomes = vol.check_array(task.node, rows, lambda tree: evaluate(
            tree, resolver, dialect=dialect, cell=cell))
    except (ArithmeticError, ValueError, TypeError, IndexError, KeyError,
            AttributeError, RecursionError) as exc:
        outcomes = None
        failure = vol.Outcome("unknown", f"evaluator failure: {type(exc).__name__}: {exc}")
    for i, r in enumerate(range(task.first, task.area[0] + 1)):
        for j, c in enumerate(range(task.col, task.area[1] + 1)):
            key = (task.sheet, r, c)
            if key not in result.not_checked:
                outcome = failure if outcomes is None else outcomes[i][j]
                if outcome.status == "unknown":
                    result.not_checked[key] = outcome.message
                else:
                    result.contract[key] = outcome
            store.put(*key, rows[i][j], value_scale(rows[i][j]))


def _settle(task: Task, store: Store, names: Names, dialect: str, clock: vol.Clock,
            result: Evaluation) -> None:
    """A single cell calling TODAY/NOW/RAND/RANDBETWEEN: its cached value checked against
    the function's contract, and kept for its dependents to read."""
    cell = (task.sheet, task.first, task.col)
    if task.area not in (None, (task.first, task.col)):  # an area of draws (RANDARRAY)
        _settle_area(task, store, names, dialect, clock, result)
        return
    cached = clock.cached[cell]
    if cell not in result.not_checked:  # not already a reader of a cell not checked
        resolver = SheetResolver(store, names, task.sheet)
        try:
            outcome = vol.check(task.node, cached, lambda tree: evaluate(
                tree, resolver, dialect=dialect, cell=cell), clock)
        except fx.Unanswered as exc:
            outcome = vol.Outcome("unknown", str(exc))
        except (ArithmeticError, ValueError, TypeError, IndexError, KeyError,
                AttributeError, RecursionError) as exc:
            outcome = vol.Outcome("unknown", f"evaluator failure: {type(exc).__name__}: {exc}")
        if outcome.status == "unknown":  # not checked; its readers still read its value
            result.not_checked[cell] = outcome.message
        else:
            result.contract[cell] = outcome
    store.put(*cell, cached, value_scale(cached))
