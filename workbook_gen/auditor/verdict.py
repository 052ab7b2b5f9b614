"""What failed an audit, named: the cells that disagree, the reference model (which
quantities, at which rows), the Checks (which closure residuals), the other engine.

    causes(report)  -> [Cause("reference", "reference model: theta_4 differs at rows
                       13-15, max error 2.0e+00"), ...]

The terminal's verdict, the JSON's ``failed`` and the one-line-per-file mode all say
these, so a FAILED never reads "cells disagree" over 0 disagreeing cells.
"""

from __future__ import annotations

from dataclasses import dataclass

SHOWN = 3  # quantities, residuals or cells named in one cause before "(+N more)"

# the kinds, in the order they are told, with how a file count reads in a total
KINDS = {
    "cells": "with cells that disagree",
    "reference": "failing the reference model",
    "checks": "failing their Checks",
    "engine": "disagreeing with LibreOffice",
}


@dataclass(frozen=True)
class Cause:
    kind: str      # one of KINDS
    message: str   # one line, what and where

    def json(self) -> dict:
        return {"kind": self.kind, "message": self.message}


def row_ranges(rows: list[int], shown: int = 4) -> str:
    """[13, 14, 15, 20] -> "rows 13-15, 20"; more than ``shown`` runs end "(+N more)"."""
    runs: list[list[int]] = []
    for row in sorted(set(rows)):
        if runs and row == runs[-1][1] + 1:
            runs[-1][1] = row
        else:
            runs.append([row, row])
    text = ", ".join(f"{a}-{b}" if b > a else f"{a}" for a, b in runs[:shown])
    more = len(runs) - shown
    word = "rows" if len(rows) > 1 else "row"
    return f"{word} {text}" + (f" (+{more} more)" if more > 0 else "")


def _more(items: list[str], shown: int = SHOWN) -> str:
    rest = len(items) - shown
    return ", ".join(items[:shown]) + (f" (+{rest} more)" if rest > 0 else "")


def causes(report) -> list[Cause]:
    """Every reason ``report.ok`` is False (empty when it is True)."""
    out = []
    sources = [m for m in report.mismatches if m.root]
    if report.mismatches:
        n = len(sources) or len(report.mismatches)
        where = _more([m.cell for m in (sources or report.mismatches)])
        out.append(Cause("cells", f"{n} cell{'s' * (n != 1)} disagree"
                                  f"{'s' * (n == 1)} at the source: {where}"
                         if sources else f"{n} cells disagree: {where}"))
    mechanics = report.mechanics
    if mechanics is not None:
        bad = [q for q in mechanics.quantities if not q.ok]
        if bad:
            parts = [f"{q.name} differs at {row_ranges(q.bad_rows)}"
                     + (f", max error {q.max_error:.1e}" if q.rows else "")
                     for q in bad]
            out.append(Cause("reference", "reference model: " + _more(parts)))
        if mechanics.tolerance is not None:
            over = [f"{name} {_value(r)}" for name, r in mechanics.residuals.items()
                    if not (isinstance(r, float) and r <= mechanics.tolerance)]
            if over:
                out.append(Cause("checks", f"Checks: closure residual{'s' * (len(over) > 1)} "
                                           f"{_more(over)} over the tolerance "
                                           f"{mechanics.tolerance:g}"))
    engine = report.engine
    if engine is not None and engine.mismatches:
        n = len(engine.mismatches)
        out.append(Cause("engine", f"{engine.engine}: {n} cell{'s' * (n != 1)} recalculate"
                                   f"{'s' * (n == 1)} to another value: "
                                   + _more([m.cell for m in engine.mismatches])))
    return out


def _value(value) -> str:
    if isinstance(value, float):
        return f"{value:.1e}"
    return getattr(value, "value", None) or repr(value)


def verdict_line(report, verbose: bool) -> str:
    """The last line of the terminal report."""
    if report.ok and report.saved_without_values:
        return ("  OK: nothing disagrees, but nothing was verified: the file holds no cached "
                "values (--engine libreoffice compares with LibreOffice's recalculation)")
    if report.ok and report.formula_cells and not report.cells_checked:
        return (f"  OK: nothing disagrees, but nothing was verified: none of the "
                f"{report.formula_cells} formula cells could be checked")
    if report.ok:
        return "  OK: every checked cell agrees" + (
            f" ({report.cells_not_checked} not checked)" if report.cells_not_checked else "")
    return ("  FAILED: " + "; ".join(c.message for c in causes(report))
            + (" (see above" + ("" if verbose else "; --verbose lists all") + ")"))
