"""The Checks sheet's values: closure residuals per row, their maxima and verdicts, the
row flags, and the design conditions.

Each residual cell is the template's check tree guarded by the row's status,
``IF(Table!status="ok", residual, "n/a")`` (``guarded``), one tree that the writer
prints and whose values are computed here.  The subtrees several residuals share are
terms (``terms.py``): columns right of the flags, guarded the same way, that the
residuals refer to.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from .. import xlmath as xm
from ..expr import Node, Var, eq, if_
from ..expr.numeric import compile_numpy, compiled_set
from ..pruning import Model
from ..xlerror import ExcelError
from .table import CANNOT_ASSEMBLE, STATUS, STATUS_OK, Table, cached_values
from .terms import Term, common_terms

TOLERANCE = 1e-9   # a residual (relative to its scale) at most this passes
SKIPPED = "n/a"    # a residual's cell where the row is not ok


@lru_cache(maxsize=4096)   # trees are immutable: the same guarded tree for every variant
def guarded(check: Node) -> Node:
    """The residual where the row is 'ok', else a text that MAX and MIN skip.

    Not "": XlsxWriter cannot mark an empty cached string as text, and readers
    then see an empty number where LibreOffice and Excel hold a string."""
    return if_(eq(Var(STATUS), STATUS_OK), check, SKIPPED)


@lru_cache(maxsize=1)
def cannot_assemble_flag() -> Node:
    return if_(eq(Var(STATUS), CANNOT_ASSEMBLE), 1, 0)


@lru_cache(maxsize=1)
def flagged_flag() -> Node:
    """1 where the row assembles but is flagged (toggle, dead centre, not converged ...)."""
    return if_(eq(Var(STATUS), STATUS_OK), 0, if_(eq(Var(STATUS), CANNOT_ASSEMBLE), 0, 1))


def is_flagged(status: str) -> bool:
    return status not in (STATUS_OK, CANNOT_ASSEMBLE)


def plan(model: Model) -> tuple[tuple[Term, ...], tuple[Node, ...]]:
    """The terms and each check's tree over Table columns and terms."""
    return common_terms(tuple(c.expr for c in model.checks))


def _unguarded(table: Table):
    """Each term's and check's value where the row is "ok" (the cells' "ok" branch), and
    the "ok" condition; each check under "\x00check i"."""
    terms, trees = plan(table.model)
    columns = dict(table.columns)
    status = xm.XArray(table.status, np.zeros(table.rows, np.uint8))
    columns[STATUS] = status
    ok = xm.compare("=", status, xm.const(STATUS_OK, table.rows))
    # The residuals read a term in their "ok" branch only, where the cell holds the
    # unguarded value: evaluate them over that (terms first, each seeing those before).
    named = tuple((t.name, t.expr) for t in terms) + tuple(
        (f"\x00check {i}", tree) for i, tree in enumerate(trees))
    return compiled_set(named)(columns, table.params, table.rows), ok


def residuals(table: Table) -> tuple[dict[str, xm.XArray], dict[str, xm.XArray]]:
    """Each check's guarded residual per row, and each term's, as the cells hold them."""
    out, ok = _unguarded(table)
    skipped = xm.const(SKIPPED, table.rows)
    terms, _ = plan(table.model)
    held = {t.name: xm.where(ok, out[t.name], skipped) for t in terms}
    values = {c.name: xm.where(ok, out[f"\x00check {i}"], skipped)
              for i, c in enumerate(table.model.checks)}
    return values, held


def guarded_cells(column: xm.XArray, ok: xm.XArray) -> tuple[list, np.ndarray]:
    """``cached_values(xm.where(ok, column, "n/a"))`` and that column's error codes,
    without the object arrays for a plain numeric column."""
    if column.is_text or column.boolean or np.count_nonzero(ok.err):
        guarded_column = xm.where(ok, column, xm.const(SKIPPED, len(column.val)))
        return cached_values(guarded_column), guarded_column.err
    picks = ok.val != 0
    cells = [v if p else SKIPPED for v, p in zip(column.val.tolist(), picks.tolist())]
    err = np.where(picks, column.err, 0).astype(np.uint8)
    if np.count_nonzero(err):
        for i in np.flatnonzero(err):
            cells[i] = ExcelError.from_code(int(err[i])).value
    return cells, err


def max_abs(cells: list, err: np.ndarray) -> float | str:
    """What MAX(MAX(r),-MIN(r)) gives: the first error of the range if any (Excel's
    MAX propagates it), else the largest magnitude; texts are skipped, none left is 0."""
    if np.count_nonzero(err):
        return ExcelError.from_code(int(err[np.flatnonzero(err)[0]])).value
    numbers = [abs(v) for v in cells if not isinstance(v, str)]
    return max(numbers, default=0.0)


def verdict(maximum: float | str) -> str:
    """What IF(max<=check_tol,"PASS","FAIL") gives (an error passes through)."""
    if isinstance(maximum, str):
        return maximum
    return "PASS" if maximum <= TOLERANCE else "FAIL"


@dataclass(frozen=True)
class CheckValues:
    """What the Checks sheet's cells cache, by check name (and term name)."""

    terms: tuple[Term, ...]
    trees: tuple[Node, ...]            # each check's tree over Table columns and terms
    cells: dict[str, list]             # each residual's cells, row by row
    maxima: dict[str, float | str]     # max |r| of each residual
    verdicts: dict[str, str]           # PASS, FAIL or an error text
    overall: str | None                # "all checks" (None: no checks)
    term_cells: dict[str, list]        # each term's cells, row by row
    cannot_assemble: list[int]         # 1 where the row cannot be assembled
    flagged: list[int]                 # 1 where the row assembles but is flagged


def check_values(table: Table) -> CheckValues:
    out, ok = _unguarded(table)
    terms, trees = plan(table.model)
    checks = table.model.checks
    found = {c.name: guarded_cells(out[f"\x00check {i}"], ok) for i, c in enumerate(checks)}
    maxima = {name: max_abs(*cells) for name, cells in found.items()}
    overall = None
    if checks:
        errors = [m for m in maxima.values() if isinstance(m, str)]
        overall = errors[0] if errors else verdict(max(maxima.values()))
    texts = table.status.tolist()
    return CheckValues(
        terms, trees, {name: cells for name, (cells, _) in found.items()}, maxima,
        {name: verdict(m) for name, m in maxima.items()}, overall,
        {t.name: guarded_cells(out[t.name], ok)[0] for t in terms},
        [1 if t == CANNOT_ASSEMBLE else 0 for t in texts],
        [1 if is_flagged(t) else 0 for t in texts])


@dataclass(frozen=True)
class ConditionValue:
    """A design condition's cells: its residual, scale, |residual|/scale and verdict."""

    value: object
    scale: object
    relative: object
    verdict: str   # PASS or FAIL


def _value(tree, params):
    return cached_values(compile_numpy(tree)({}, params, 1))[0]


@dataclass(frozen=True)
class Conditions:
    items: tuple[ConditionValue, ...]   # the template's conditions, in order
    overall: str                        # "all conditions": PASS or FAIL


def condition_values(table: Table) -> Conditions:
    """The template's balancing conditions from the parameters."""
    out = []
    for item in table.model.conditions:
        value, scale = _value(item.expr, table.params), _value(item.scale, table.params)
        relative = ((0.0 if scale == 0 else abs(value) / scale)
                    if isinstance(value, float) and isinstance(scale, float) else value)
        good = isinstance(relative, float) and relative <= TOLERANCE
        out.append(ConditionValue(value, scale, relative, "PASS" if good else "FAIL"))
    return Conditions(tuple(out), "PASS" if all(c.verdict == "PASS" for c in out) else "FAIL")
