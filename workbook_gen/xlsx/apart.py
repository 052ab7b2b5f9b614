"""The biggest worksheets read in a forked child process while this one reads the others.

A worksheet's cells cost per-cell Python work (tens of thousands of cells a second), and
the two big sheets of a large workbook are independent: on a machine with two cores the
child reads about half of the sheet bytes. It sends its cells back as columns (one list
per ``Cell`` field, and the plain cells as the reader keeps them, in columns: cheap to
pickle), from which the parent builds the same sheets as reading them itself would.

The outcome is always that of reading every sheet here in order: whenever anything goes
wrong in either process (a bad part, the cell limit, a dead child), the sheets are emptied
and ``read_apart`` returns False, and the caller reads them all the ordinary way, which
raises the same error for the same first bad sheet.
"""

from __future__ import annotations

from operator import attrgetter

from workbook_gen.forked import Forked, can_fork
from workbook_gen.xlsx.limits import MiB, Package
from workbook_gen.xlsx.model import Cell, Sheet
from workbook_gen.xlsx.sheetdata import read_sheet

MIN_SHARE = 2 * MiB
"""Sheet bytes (as the zip declares them) each process must get for a fork to pay off."""


def split(pkg: Package, sheet_parts: list[tuple[Sheet, str]]) -> list[int]:
    """Indexes of the sheets the child should read; [] to read every sheet here."""
    if len(sheet_parts) < 2 or not can_fork():
        return []
    # with everything in the zip inside the budget of inflated bytes, the order in which
    # the parts are inflated cannot change the outcome
    if pkg.declared_total() > pkg.max_uncompressed - pkg.inflated:
        return []
    sizes = [pkg.declared_size(part) for _, part in sheet_parts]
    theirs, mine, child = 0, 0, []
    for i in sorted(range(len(sizes)), key=lambda i: -sizes[i]):
        if theirs <= mine:
            child.append(i)
            theirs += sizes[i]
        else:
            mine += sizes[i]
    return sorted(child) if min(mine, theirs) >= MIN_SHARE else []


def read_apart(pkg: Package, sheet_parts: list[tuple[Sheet, str]], strings: list[str],
               max_cells: int, ready=lambda sheet: None,
               prepare=lambda sheet: None) -> bool:
    """Fill the sheets' cells, the child reading a share of them; False: nothing read.
    ``ready(sheet)``, ``prepare(sheet)``: see read_workbook (``ready`` with the sheets
    before the child's first while it reads, the others once it is done)."""
    child = split(pkg, sheet_parts)
    if not child:
        return False
    theirs = [sheet_parts[i] for i in child]
    mine = [sp for i, sp in enumerate(sheet_parts) if i not in child]
    inflated = pkg.inflated
    job = Forked(_read_columns, pkg.path, pkg.max_uncompressed, pkg.max_ratio, inflated,
                 [(s.name, s.index, s.state, part) for s, part in theirs], strings, max_cells,
                 prepare)

    def undo() -> None:
        job.cancel()
        _empty(sheet_parts, pkg, inflated)

    count = _guarded(job, undo, _read_mine, pkg, mine, strings, max_cells)
    if count is _FAILED:
        return False
    try:
        for sheet, _ in mine:  # (its own failures, not the file's)
            sheet.prepared = prepare(sheet)
        for sheet, _ in sheet_parts[:child[0]]:
            ready(sheet)
    except BaseException:
        job.cancel()
        raise
    outcome = _guarded(job, undo, job.next)
    if outcome is _FAILED:
        return False
    their_inflated, results = outcome
    count += sum(n for n, *_ in results)
    if count > max_cells:  # read in order, the limit would have stopped it: say where
        job.cancel()
        _empty(sheet_parts, pkg, inflated)
        return False
    pkg.inflated += their_inflated
    for (sheet, _), (_, dimension, shared, hidden, columns, chunks) in zip(theirs, results):
        sheet.adopt(dict(zip(columns[0], map(Cell, *columns))), chunks)
        sheet.dimension, sheet.shared_formulas, sheet.hidden_rows = dimension, shared, hidden

    def prepared() -> None:  # the child's second value: what prepare made of its sheets
        try:
            made = job.next()
        finally:
            job.close()
        for (sheet, _), value in zip(theirs, made):
            sheet.prepared = value

    for sheet, _ in theirs:  # asked for by ready(sheet), or below
        sheet._pending = prepared
    try:
        for sheet, _ in sheet_parts[child[0]:]:
            ready(sheet)
        if theirs[0][0]._pending is not None:
            prepared()
    except BaseException:
        job.cancel()
        raise
    return True


_FAILED = object()


def _guarded(job: Forked, undo, fn, *args):
    """``fn(*args)``; a failure (an Exception) undoes the reading and gives _FAILED, anything
    else (an interrupt) stops the child and goes on."""
    try:
        return fn(*args)
    except Exception:
        undo()
        return _FAILED
    except BaseException:
        job.cancel()
        raise


def _read_mine(pkg: Package, mine: list[tuple[Sheet, str]], strings: list[str],
               max_cells: int) -> int:
    count = 0
    for sheet, part in mine:
        count += read_sheet(pkg, part, sheet, strings, max_cells - count, max_cells)
    return count


def _read_columns(path: str, max_uncompressed: int, max_ratio: float, inflated: int,
                  jobs: list[tuple[str, int, str, str]], strings: list[str], max_cells: int,
                  prepare):
    """In the child: read the sheets, and send (bytes inflated, [(cells read, dimension,
    shared formulas, hidden rows, one list per Cell field of the Cell objects, the plain
    cells' chunks)]); then [what ``prepare`` made of each sheet], made while the parent
    takes the cells."""
    fields = attrgetter(*Cell.__slots__)
    out, count, sheets = [], 0, []
    with Package(path, max_uncompressed=max_uncompressed, max_ratio=max_ratio) as pkg:
        pkg.inflated = inflated
        for name, index, state, part in jobs:
            sheet = Sheet(name, index, state)
            n = read_sheet(pkg, part, sheet, strings, max_cells - count, max_cells)
            count += n
            cells, chunks = sheet.parts()
            columns = [list(c) for c in zip(*map(fields, cells))]
            out.append((n, sheet.dimension, sheet.shared_formulas, sheet.hidden_rows,
                        columns or [[] for _ in Cell.__slots__], chunks))
            sheets.append(sheet)
        inflated = pkg.inflated - inflated
    yield inflated, out
    yield [prepare(sheet) for sheet in sheets]


def _empty(sheet_parts: list[tuple[Sheet, str]], pkg: Package, inflated: int) -> None:
    pkg.inflated = inflated
    for sheet, _ in sheet_parts:
        sheet.cells, sheet.shared_formulas, sheet.dimension, sheet._rows = {}, {}, None, None
