"""A task of evaluation (a run of R1C1-identical formulas, a single cell or an array
formula): which cells it reads (``shapes_of``, ``rects``) and how it is evaluated
(``evaluate_task``: a compiled block over the run's rows, the scalar evaluator for a cell,
the array evaluator over an array formula's rectangle). :mod:`engine` orders the tasks and
decides what is checked."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from workbook_gen.evaluator import graph
from workbook_gen.evaluator.ops import Const
from workbook_gen.evaluator.store import (Names, NumBlock, ObjBlock, SheetResolver, Store,
                                          value_scale)
from workbook_gen.evaluator.taint import Shape
from workbook_gen.evaluator.vector import Env
from workbook_gen.formula import ast
from workbook_gen.formula import functions as fx
from workbook_gen.formula.scalar import Evaluator, evaluate

# functions that use a reference's position or size, never its cells' values
REFERENCE_ONLY = frozenset({"ROW", "COLUMN", "ROWS", "COLUMNS", "ISREF", "AREAS",
                            "ISFORMULA", "FORMULATEXT", "SHEET", "SHEETS"})


@dataclass
class Task:
    sheet: str
    col: int
    first: int
    last: int
    node: ast.Node
    block: object = None   # compiled vector Block, or None for a single cell
    area: tuple[int, int] | None = None  # an array formula: its last row and column
    # a run that reads its own column only above each row (``=A1+1`` filled down: a
    # chain): evaluated row after row, cell by cell, without a task per cell
    sequential: bool = False

    def cells(self):
        if self.area is not None:
            return [(self.sheet, r, c) for r in range(self.first, self.area[0] + 1)
                    for c in range(self.col, self.area[1] + 1)]
        return [(self.sheet, r, self.col) for r in range(self.first, self.last + 1)]


def reads_only_above(task: Task, shapes: list[Shape]) -> bool:
    """Does every rectangle the run reads in its own column end above the row reading
    it (so that its rows, computed in order, never read one not yet computed)?"""
    return all(s.row2 < task.first for s in shapes
               if s.sheet == task.sheet and s.col1 <= task.col <= s.col2)


def singles(task: Task):
    """A run as single cells, each with its own (shifted) tree, made as they are asked
    for (``list(singles(u))`` for all at once)."""
    return (Task(task.sheet, task.col, r, r, ast.shift(task.node, r - task.first, 0))
            for r in range(task.first, task.last + 1))


def _reads(node: ast.Node):
    """The references and names whose cells a formula reads: not the references given to
    functions that use only their position or size (``ROWS(A1:A9)`` reads no cell)."""
    stack = [node]
    while stack:
        n = stack.pop()
        if isinstance(n, (ast.CellRef, ast.RangeRef, ast.Name, ast.Sheets3D)):
            yield n
        elif isinstance(n, ast.Func) and n.name not in fx.REGISTRY:
            yield ast.Name(n.name)  # a defined name's LAMBDA called by name reads its body
            stack.extend(ast.children(n))
        elif isinstance(n, ast.Func) and n.name in REFERENCE_ONLY:
            stack.extend(a for a in n.args if not isinstance(a, (ast.CellRef, ast.RangeRef)))
        else:
            if isinstance(n, ast.Func) and n.name == "INDIRECT":
                yield from _indirect_reads(n)
            stack.extend(ast.children(n))


def _indirect_reads(call: ast.Func):
    """The reference ``INDIRECT("B1")`` reads when its text is a constant in A1 style:
    the cell it names must be computed before it (``INDIRECT("B1")`` is B1 of the calling
    cell's sheet, the same from every row of a run). A computed text reads what it
    evaluates to, which no graph can know ahead."""
    from workbook_gen.errors import FormulaSyntaxError
    from workbook_gen.formula.parser import parse
    if not call.args or not isinstance(call.args[0], ast.String):
        return
    if len(call.args) > 1 and not (isinstance(call.args[1], ast.Bool) and call.args[1].value):
        return
    try:
        ref = parse(call.args[0].value.strip())
    except FormulaSyntaxError:
        return
    if isinstance(ref, ast.CellRef):
        yield dataclasses.replace(ref, row_abs=True, col_abs=True)
    elif isinstance(ref, ast.RangeRef):
        fixed = [dataclasses.replace(c, row_abs=True, col_abs=True) for c in (ref.first, ref.last)]
        yield dataclasses.replace(ref, first=fixed[0], last=fixed[1])
    elif isinstance(ref, ast.Name):
        yield ref


def shapes_of(task: Task, store: Store, names: Names) -> tuple[list[Shape], list[str]]:
    """The rectangles of cells a task reads at its first row (defined names followed),
    and the names it uses that do not parse (or ``Sheet!``: a sheet it reads is
    unreadable)."""
    out: list[Shape] = []
    bad: list[str] = []
    pending = [(task.node, task.sheet)]
    seen_names: set[tuple] = set()
    while pending:
        node, home = pending.pop()
        for n in _reads(node):
            if isinstance(n, ast.Name):
                key = (n.name.upper(), n.sheet, home)
                if key in seen_names:
                    continue
                seen_names.add(key)
                target = names.node(n.name, n.sheet, home)
                if target is not None:
                    pending.append((target, home if n.sheet is None else store.sheet(n.sheet)))
                elif (label := names.error(n.name, n.sheet, home)) is not None:
                    bad.append(label)
                continue
            if isinstance(n, ast.Sheets3D):
                sheets = store.sheets_between(n.sheet, n.sheet2) or []
                ref = n.ref
            else:
                ref = n
                sheets = [home if n.sheet is None else store.sheet(n.sheet)]
            if isinstance(ref, ast.CellRef):
                first = last = ref
            else:
                first, last = ref.first, ref.last
            if first.row > last.row:
                first, last = last, first
            for sheet in sheets:
                if sheet.lower() in store.unreadable:
                    bad.append(sheet + "!")
                out.append(Shape(sheet, first.row, min(first.col, last.col), last.row,
                                 max(first.col, last.col), not first.row_abs, not last.row_abs))
    return out, bad


def rects(task: Task, shaped: tuple) -> list[graph.Rect]:
    """The rectangles of cells a task reads over all its rows."""
    span = task.last - task.first
    # (row1 <= row2 at the first row; a moving row1 may pass a fixed row2: B1:B$3 filled
    # down to row 9 reads B3:B9)
    return [(s.sheet, s.row1, s.col1,
             max(s.row1 + (span if s.rel1 else 0), s.row2 + (span if s.rel2 else 0)), s.col2)
            for s in shaped[0]]


def evaluate_task(task: Task, store: Store, names: Names, dialect: str = "excel",
                  view=None) -> None:
    """Evaluate a task into ``store``; ``view``: what its formula reads instead of the store
    (the on-demand view of a cycle, :mod:`cycles`; the operand scale still reads the store
    directly, so that it asks for no cell the formula does not read)."""
    scaler = SheetResolver(store, names, task.sheet)
    resolver = scaler if view is None else SheetResolver(view, names, task.sheet)
    cell = (task.sheet, task.first, task.col)
    if task.area is not None:
        from workbook_gen.formula.arrays import beyond, evaluate_array, spread
        rows, cols = task.area[0] - task.first + 1, task.area[1] - task.col + 1
        values = spread(evaluate_array(task.node, resolver, dialect, cell), rows, cols,
                        beyond(task.node, dialect))
        scale = cell_scale(task.node, scaler)
        for i, row in enumerate(values):
            for j, value in enumerate(row):
                store.put(task.sheet, task.first + i, task.col + j, value, scale)
        return
    if task.sequential:  # each row's tree made when its turn comes, then dropped
        for single in singles(task):
            evaluate_task(single, store, names, dialect)
        return
    if task.block is None:
        value = evaluate(task.node, resolver, dialect=dialect, cell=cell)
        store.put(task.sheet, task.first, task.col, value, cell_scale(task.node, scaler))
        return
    reference = Evaluator(resolver, dialect, None, cell)
    reference.ctx.intersect = False  # a part computed once must not depend on the row
    env = Env(task.last - task.first + 1, store.block, reference.arg, dialect)
    try:
        value = task.block.run(env)
    except fx.RowDependent:  # implicit intersection after all: cell by cell
        for single in singles(task):
            evaluate_task(single, store, names, dialect)
        return
    scale = task.block.scale(env)
    if isinstance(value, Const):
        value = ObjBlock([0.0 if value.value is None else value.value] * env.n)
    elif isinstance(value, ObjBlock):
        value = ObjBlock([0.0 if v is None else v for v in value.items])
    elif not isinstance(value, NumBlock):
        raise TypeError(f"unexpected block value {type(value).__name__}")
    store.put_block(task.sheet, task.col, task.first, value, scale)


def cell_scale(node: ast.Node, resolver: SheetResolver) -> float:
    """Largest magnitude among the numbers a formula reads: literals, cells, names."""
    scale = 0.0
    for n in ast.walk(node):
        if isinstance(n, ast.Number):
            scale = max(scale, abs(n.value))
        elif isinstance(n, ast.CellRef):
            scale = max(scale, value_scale(resolver.cell(n.sheet, n.row, n.col)))
        elif isinstance(n, ast.RangeRef):
            r1, r2 = sorted((n.first.row, n.last.row))
            c1, c2 = sorted((n.first.col, n.last.col))
            scale = max(scale, resolver.range_scale(n.sheet, r1, c1, r2, c2))
        elif isinstance(n, ast.Name):
            scale = max(scale, value_scale(resolver.name(n.name, n.sheet)))
    return scale
