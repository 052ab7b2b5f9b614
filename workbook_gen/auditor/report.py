"""The audit report: data (``AuditReport``), JSON, and the terminal text."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..xlerror import ExcelError
from .compare import ColumnStats
from .mechanics import REFERENCE_TOLERANCE, MechanicsReport
from .structure import Finding

MAX_LISTED = 20  # disagreeing cells listed per column in the terminal


@dataclass
class Mismatch:
    cell: str
    formula: str
    cached: object
    recomputed: object
    abs_error: float | None = None
    root: bool = True  # False: a precedent disagrees too, so this may only follow from it


@dataclass
class EngineResult:
    engine: str
    cells: int
    mismatches: list[Mismatch]
    libreoffice_semantics: int  # cells explained only by LibreOffice's known deviations
    seconds: float


@dataclass
class AuditReport:
    path: str
    formula_cells: int
    cells_checked: int
    mismatches: list[Mismatch]
    columns: list[ColumnStats]
    max_abs_error: float
    max_rel_error: float
    findings: list[Finding]
    mechanics: MechanicsReport | None
    libreoffice_semantics: int
    vector_cells: int
    seconds: float
    engine: EngineResult | None = None
    timings: dict[str, float] = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return (not self.mismatches
                and not any(f.blocking for f in self.findings)
                and (self.mechanics is None or self.mechanics.ok)
                and (self.engine is None or not self.engine.mismatches))

    @property
    def reference(self) -> dict[str, float]:
        if self.mechanics is None:
            return {}
        return {q.name: q.max_error for q in self.mechanics.quantities}

    def to_json(self) -> dict:
        out = {
            "ok": self.ok,
            "file": self.path,
            "formula_cells": self.formula_cells,
            "cells_checked": self.cells_checked,
            "mismatches": [_mismatch_json(m) for m in self.mismatches],
            "max_abs_error": self.max_abs_error,
            "max_rel_error": self.max_rel_error,
            "reference": self.reference,
            "findings": [f.__dict__ for f in self.findings],
            "libreoffice_semantics": self.libreoffice_semantics,
            "vectorized_cells": self.vector_cells,
            "seconds": self.seconds,
            "timings": self.timings,
        }
        if self.mechanics is not None:
            m = self.mechanics
            out["mechanism"] = m.mechanism
            out["reference_tolerance"] = REFERENCE_TOLERANCE
            out["reference_problems"] = {q.name: q.wrong_rows for q in m.quantities if q.wrong_rows}
            out["residuals"] = {k: _plain(v) for k, v in m.residuals.items()}
            out["residual_tolerance"] = m.tolerance
            out["flagged_rows"] = dict(m.flagged)
            out["paper_table"] = [dict(zip(("input", "workbook", "reference", "error_percent"), r))
                                  for r in m.paper_table]
        if self.engine is not None:
            out["engine"] = {"name": self.engine.engine, "cells": self.engine.cells,
                             "mismatches": [_mismatch_json(m) for m in self.engine.mismatches],
                             "libreoffice_semantics": self.engine.libreoffice_semantics,
                             "seconds": self.engine.seconds}
        return out


def _plain(value: object) -> object:
    if isinstance(value, ExcelError):
        return value.value
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    return value


def _mismatch_json(m: Mismatch) -> dict:
    return {"cell": m.cell, "formula": "=" + m.formula, "cached": _plain(m.cached),
            "recomputed": _plain(m.recomputed), "root": m.root}


def _show(value: object) -> str:
    if isinstance(value, float):
        return f"{value:.15g}"
    if isinstance(value, ExcelError):
        return value.value
    return repr(value)


def format_report(report: AuditReport) -> str:
    lines = [f"audit of {report.path}",
             f"  {report.formula_cells} formula cells, {report.cells_checked} checked "
             f"({report.vector_cells} as vectorised columns), {report.seconds:.2f} s"]
    lines.append("")
    lines.append(f"  {'sheet':<12}{'column':<8}{'cells':>8}{'worst error':>14}  {'at':<10}disagree")
    for c in report.columns:
        lines.append(f"  {c.sheet:<12}{c.column:<8}{c.cells:>8}{c.worst_error:>14.2e}  "
                     f"{c.worst_cell:<10}{c.mismatches}")
    if report.mismatches:
        roots = [m for m in report.mismatches if m.root]
        lines += ["", f"  {len(report.mismatches)} cells disagree (cached against recomputed), "
                      f"{len(roots)} at their source (no precedent disagrees):"]
        ordered = roots + [m for m in report.mismatches if not m.root]
        for m in ordered[:MAX_LISTED * 5]:
            lines.append(f"    {m.cell}: ={m.formula}{'' if m.root else '  (follows)'}")
            lines.append(f"      cached {_show(m.cached)}, recomputed {_show(m.recomputed)}")
    if report.libreoffice_semantics:
        lines.append(f"  {report.libreoffice_semantics} cells hold LibreOffice's answer where "
                     f"Excel's differs (e.g. SQRT(-1) is #VALUE! there): accepted")
    if report.findings:
        lines += ["", "  structure:"]
        for f in report.findings[:200]:
            mark = "" if f.blocking else " (reported)"
            lines.append(f"    {f.kind}{mark}: {f.where}: {f.detail}")
    if report.mechanics is not None:
        lines += _mechanics_lines(report.mechanics)
    if report.engine is not None:
        e = report.engine
        lines += ["", f"  {e.engine}: {e.cells} cells recalculated in {e.seconds:.1f} s, "
                      f"{len(e.mismatches)} disagree with the recomputed values"]
        for m in e.mismatches[:MAX_LISTED]:
            lines.append(f"    {m.cell}: ={m.formula}: {e.engine} {_show(m.cached)}, "
                         f"ours {_show(m.recomputed)}")
    lines += ["", "  OK: every cell agrees" if report.ok else "  FAILED: see above"]
    return "\n".join(lines)


def _mechanics_lines(m: MechanicsReport) -> list[str]:
    lines = ["", f"  against the independent reference model of {m.mechanism} "
                 f"(tolerance {REFERENCE_TOLERANCE:g} of each column's magnitude):"]
    for q in m.quantities:
        where = f" at {q.worst_row_input:g}" if q.worst_row_input is not None else ""
        lines.append(f"    {q.name:<10}{q.rows:>7} rows  max error {q.max_error:.2e}{where}"
                     f"{'' if q.ok else '  FAIL'}")
        lines += [f"      {w}" for w in q.wrong_rows[:MAX_LISTED]]
    flagged = ", ".join(f"{text} {n}" for text, n in sorted(m.flagged.items()))
    lines.append(f"  rows flagged singular: {sum(m.flagged.values())}"
                 + (f" ({flagged}; rates there are singular or unconverged)" if flagged else ""))
    if m.residuals:
        lines.append(f"  closure residuals (Checks sheet, tolerance {m.tolerance:g}):")
        for name, value in m.residuals.items():
            lines.append(f"    {name:<22}{_show(value)}")
    if m.paper_table:
        lines.append("  lever angular acceleration alpha_5 against the model, per 10 deg "
                     "(the paper's Table 2; it found 0.707% at 310 deg against CAD):")
        lines.append(f"    {'theta_1':>8}{'workbook':>18}{'reference':>18}{'error %':>11}")
        for angle, ours, ref, error in m.paper_table:
            lines.append(f"    {angle:>8g}{ours:>18.10f}{ref:>18.10f}{error:>11.2e}")
    return lines
