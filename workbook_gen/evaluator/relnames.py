"""Defined names whose value depends on the cell that uses them, written into that cell's
formula.

A name's relative references are relative to the cell that uses it: the file stores them
as seen from A1 (``Sheet1!$H1`` read from I12 is ``Sheet1!$H12``; ``Sheet1!A1048576``,
one row above, read from row 5 is row 4), wrapping at the sheet's edges as Excel does
(rows modulo 1,048,576, columns modulo 16,384; LibreOffice does not wrap: #REF!, its
dialect). A structured reference that names no
table, or says ``[#This Row]`` / ``@``, is likewise resolved from the calling cell.

Such a name is replaced in the formula's tree by its definition, moved to the calling
cell (and the names it uses, the same way): the tree then reads what Excel reads, and the
dependency graph, the vectorised and the cell-by-cell evaluators need nothing more.
Names whose value is the same from every cell are left as names.
"""

from __future__ import annotations

import dataclasses

from workbook_gen.errors import FormulaSyntaxError
from workbook_gen.formula import ast
from workbook_gen.formula.parser import parse_name
from workbook_gen.xlerror import ExcelError

MAX_DEPTH = 16  # names through names


def cell_dependent(node: ast.Node) -> bool:
    """Does the tree read something relative to the cell evaluating it (a relative
    reference, a structured reference left to the calling cell)?"""
    for n in ast.walk(node):
        if isinstance(n, ast.Sheets3D):
            n = n.ref
        if isinstance(n, ast.CellRef) and not (n.row_abs and n.col_abs):
            return True
        if isinstance(n, ast.RangeRef) and not all(
                c.row_abs and c.col_abs for c in (n.first, n.last)):
            return True
        if isinstance(n, ast.StructRef):
            return True
    return False


def calling_cell_struct(node: ast.StructRef) -> bool:
    """A structured reference resolved from the calling cell: no table named
    (``[@x]``, ``[Col]``), or this row (``[#This Row]``, ``@``)."""
    spec = node.spec.lower()
    return not node.table or "@" in spec or "#this row" in spec


def _moved(ref: ast.CellRef, drow: int, dcol: int, wrap: bool) -> ast.CellRef | None:
    row = ref.row if ref.row_abs else ref.row + drow
    col = ref.col if ref.col_abs else ref.col + dcol
    if wrap:
        row, col = (row - 1) % ast.MAX_ROW + 1, (col - 1) % ast.MAX_COL + 1
    elif not (1 <= row <= ast.MAX_ROW and 1 <= col <= ast.MAX_COL):
        return None
    return dataclasses.replace(ref, row=row, col=col)


def at_cell(node: ast.Node, row: int, col: int, sheet: str | None, wrap: bool = True
            ) -> ast.Node:
    """A name's tree (as seen from A1) seen from cell (row, col); unqualified references
    put on ``sheet`` (None: the calling sheet). ``wrap``: a reference moved past the
    sheet's edge comes back at the other edge (Excel); else it is #REF! (LibreOffice)."""
    def move(ref):
        # (whole columns and rows have absolute rows, columns: they stay whole)
        ends = [_moved(c, row - 1, col - 1, wrap)
                for c in ((ref,) if isinstance(ref, ast.CellRef) else (ref.first, ref.last))]
        if None in ends:
            return ast.ErrorLit(ExcelError.REF)
        if isinstance(ref, ast.CellRef):
            return ends[0] if sheet is None or ref.sheet else dataclasses.replace(
                ends[0], sheet=sheet)
        return ast.RangeRef(ref.sheet or sheet, ends[0], ends[1], ref.whole)
    return ast.map_refs(node, move)


class NameInliner:
    """Writes the calling-cell-dependent names of ``names`` (a :class:`store.Names`) into
    formulas; ``active`` is False when the workbook has none (nothing to do). ``wrap``:
    Excel's wrapping at the sheet's edges (LibreOffice's dialect: #REF! there instead)."""

    def __init__(self, names, wrap: bool = True):
        self.names, self.wrap = names, wrap
        self._dependent: dict[tuple, bool] = {}
        self.active = any(cell_dependent(n) for n in names.nodes.values()) or any(
            cell_dependent(n) for scope in names.local.values() for n in scope.values())

    def _depends(self, node: ast.Node, home: str, depth: int = 0) -> bool:
        if cell_dependent(node):
            return True
        if depth >= MAX_DEPTH:
            return False
        for n in ast.walk(node):
            if isinstance(n, ast.Name) and self._target(n, home, depth + 1) is not None:
                return True
        return False

    def _target(self, n: ast.Name, home: str, depth: int = 0):
        """The tree of name ``n`` used on sheet ``home`` if it depends on the calling
        cell, else None."""
        if n.name.lower().startswith("_xlpm."):  # a LAMBDA's or LET's own name
            return None
        key = (n.name.upper(), (n.sheet or "").lower(), home.lower())
        target = self.names.node(n.name, n.sheet, home)
        if target is None:
            return None
        if key not in self._dependent:
            self._dependent[key] = False  # (a name through itself: not dependent)
            self._dependent[key] = self._depends(target, n.sheet or home, depth)
        return target if self._dependent[key] else None

    def inline(self, node: ast.Node, sheet: str, row: int, col: int, depth: int = 0
               ) -> ast.Node:
        """``node`` (a formula of cell (sheet, row, col)) with the calling-cell-dependent
        names written in."""
        if not self.active or depth >= MAX_DEPTH or not any(
                isinstance(n, ast.Name) and self._target(n, sheet) is not None
                for n in ast.walk(node)):
            return node

        def fix(n):
            target = self._target(n, sheet)
            if target is None:
                return n
            home = n.sheet
            return self.inline(at_cell(target, row, col, home, self.wrap), home or sheet,
                               row, col, depth + 1)
        return map_nodes(node, ast.Name, fix)


    def inline_run(self, run) -> list:
        """A run (:class:`grouping.Run`) with its calling-cell-dependent names written in:
        one run still if the names read the same way down it (no wrap at the sheet's
        edge, no reference moved off it), else cell by cell."""
        first = self.inline(run.node, run.sheet, run.first, run.col)
        if first is run.node or run.last == run.first:
            return [dataclasses.replace(run, node=first)]
        span = run.last - run.first
        last = self.inline(ast.shift(run.node, span, 0), run.sheet, run.last, run.col)
        if ast.shift(first, span, 0) == last and _refs_off(last) == _refs_off(first):
            return [dataclasses.replace(run, node=first)]
        return [dataclasses.replace(run, first=r, last=r, node=self.inline(
            ast.shift(run.node, r - run.first, 0), run.sheet, r, run.col))
            for r in range(run.first, run.last + 1)]


def _refs_off(node: ast.Node) -> int:
    """#REF! literals in a tree (a reference moved off the sheet becomes one)."""
    return sum(1 for n in ast.walk(node) if isinstance(n, ast.ErrorLit)
               and n.error is ExcelError.REF)


def relative_names(names: dict[str, str]) -> set[str]:
    """The workbook's names (upper case; name -> definition text) whose value depends on
    the calling cell, directly or through another such name."""
    trees = {}
    for name, text in names.items():
        try:
            trees[name.upper()] = parse_name(text)
        except FormulaSyntaxError:
            continue
    found = {n for n, tree in trees.items() if cell_dependent(tree)}
    while True:
        more = {n for n, tree in trees.items() if n not in found and any(
            isinstance(m, ast.Name) and m.name.upper() in found for m in ast.walk(tree))}
        if not more:
            return found
        found |= more


def map_nodes(node: ast.Node, kind, fn) -> ast.Node:
    """A copy of ``node`` where every node of type ``kind`` is replaced by ``fn(node)``."""
    if isinstance(node, kind):
        return fn(node)
    if isinstance(node, ast.Func):
        return dataclasses.replace(node, args=tuple(map_nodes(a, kind, fn) for a in node.args))
    if isinstance(node, (ast.Unary, ast.Percent)):
        return dataclasses.replace(node, operand=map_nodes(node.operand, kind, fn))
    if isinstance(node, ast.Binary):
        spine = []  # left spine, iterated: long operator chains must not recurse
        while isinstance(node, ast.Binary):
            spine.append(node)
            node = node.left
        result = map_nodes(node, kind, fn)
        for step in reversed(spine):
            result = ast.Binary(step.op, result, map_nodes(step.right, kind, fn))
        return result
    if isinstance(node, ast.Paren):
        return ast.Paren(map_nodes(node.inner, kind, fn))
    if isinstance(node, ast.RefOp):
        return ast.RefOp(node.op, map_nodes(node.left, kind, fn),
                         map_nodes(node.right, kind, fn))
    return node
