"""The audit report: data (``AuditReport``), JSON, and the terminal text."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..xlerror import ExcelError
from .compare import ColumnStats
from .grid import show_value
from .mechanics import REFERENCE_TOLERANCE, MechanicsReport
from .structure import Finding
from .tally import NO_CACHED_VALUE, Tally
from .verdict import causes, verdict_line

MAX_LISTED = 20  # disagreeing cells listed per column in the terminal (--verbose)
WORST = 5  # disagreeing cells shown in the default summary

# reasons of what the file only caches (a cube, another workbook, a data table)
_CACHED_OUTSIDE = ("CUBE", "RTD:", "external reference", "external name", "data table")


@dataclass
class Mismatch:
    cell: str
    formula: str
    cached: object
    recomputed: object
    abs_error: float | None = None
    root: bool = True  # False: a precedent disagrees too, so this may only follow from it
    # an array formula: its area ("D8:D9"; ``cell`` is its anchor), its disagreeing cells,
    # and the cell whose values are shown when it is not the anchor
    area: str | None = None
    cells: list[str] = field(default_factory=list)
    at: str | None = None
    sources: list[str] = field(default_factory=list)    # a follower: what it follows from
    followers: list[str] = field(default_factory=list)  # a source: what follows from it
    # agrees with what it makes of its cached precedents, but a recalculation, in which
    # a source upstream changes, gives ``recomputed``
    stale: bool = False
    key: tuple | None = field(default=None, repr=False, compare=False)


@dataclass
class EngineResult:
    engine: str
    cells: int
    mismatches: list[Mismatch]
    libreoffice_semantics: int  # cells explained only by LibreOffice's known deviations
    seconds: float
    # those cells: ``cached`` holds LibreOffice's value, ``recomputed`` ours (Excel's)
    differences: list[Mismatch] = field(default_factory=list)


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
    # formula cells that could not be recomputed, or read one: cell -> reason
    not_checked: dict[str, str] = field(default_factory=dict)
    macros: str | None = None  # the VBA project's part: macros the audit does not check
    # whose semantics recomputed the cells ("excel" or "libreoffice"), from the application
    # that saved the file (docProps/app.xml)
    semantics: str = "excel"
    application: str | None = None
    # cells calling TODAY/NOW/RAND/RANDBETWEEN, checked against the function's contract
    # (not recomputed: the value changes at every recalculation): cell -> how
    by_contract: dict[str, str] = field(default_factory=dict)
    counts: Tally | None = None  # the formula cells by verdict (tally.py)
    # no formula cell holds a cached value (openpyxl, pandas): nothing could be verified
    saved_without_values: bool = False
    # what the audit's own code warned of while it ran (caught.py): message -> times
    warnings: dict[str, int] = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        """True unless a cell disagrees (with its cached value, the reference model or
        the other engine): findings and cells not checked never fail an audit.

        A file saved without calculating (``saved_without_values``: openpyxl, pandas) is
        ok too, and exits 0: it contradicts nothing, as a file whose every cell calls an
        unsupported function. The report says that nothing was verified instead of
        "every checked cell agrees", and ``--engine libreoffice`` can verify it."""
        return (not self.mismatches
                and (self.mechanics is None or self.mechanics.ok)
                and (self.engine is None or not self.engine.mismatches))

    @property
    def cells_disagree(self) -> int:
        """Formula cells whose cached value differs from a recalculation, at the source or
        following from one (an array formula's area at its anchor)."""
        return self.counts.disagree if self.counts else len(self.mismatches)

    @property
    def disagreements(self) -> int:
        """Disagreements counted once at their source."""
        return sum(1 for m in self.mismatches if m.root)

    @property
    def cells_agree(self) -> int:
        return (self.counts.agree if self.counts else
                self.cells_checked - len(self.mismatches) - len(self.by_contract))

    @property
    def cells_not_checked(self) -> int:
        return len(self.not_checked)

    @property
    def cells_no_cached_value(self) -> int:
        return sum(1 for r in self.not_checked.values() if r == NO_CACHED_VALUE)

    def not_checked_reasons(self) -> list[tuple[str, int]]:
        """(reason, cells) most frequent first; dependents grouped by what they read."""
        counts: dict[str, int] = {}
        for reason in self.not_checked.values():
            if reason.startswith("depends on"):
                key = "depend on a cell not checked"
            elif reason.startswith(_CACHED_OUTSIDE):  # "what: why: which cells"
                key = ": ".join(reason.split(": ")[:2])
            elif reason.startswith(("formula syntax", "circular reference", "defined name")):
                key = reason.split(" at position")[0].split(" (")[0].split(" '")[0]
                key = key if len(key) < 70 else key[:67] + "..."
            else:
                key = reason
            counts[key] = counts.get(key, 0) + 1
        return sorted(counts.items(), key=lambda kv: (-kv[1], kv[0]))

    @property
    def reference(self) -> dict[str, float]:
        if self.mechanics is None:
            return {}
        return {q.name: q.max_error for q in self.mechanics.quantities}

    def to_json(self) -> dict:
        out = {
            "ok": self.ok,
            "failed": [c.json() for c in causes(self)],  # what failed: cells, reference, ...
            "file": self.path,
            "formula_cells": self.formula_cells,
            "cells_checked": self.cells_checked,
            "cells_agree": self.cells_agree,
            "cells_disagree": self.cells_disagree,
            "cells_not_checked": self.cells_not_checked,
            "cells_no_cached_value": self.cells_no_cached_value,
            "saved_without_values": self.saved_without_values,
            "disagreements": self.disagreements,
            "not_checked": [{"cell": c, "reason": r} for c, r in self.not_checked.items()],
            "cells_by_contract": len(self.by_contract),
            "by_contract": [{"cell": c, "check": m} for c, m in self.by_contract.items()],
            "mismatches": [_mismatch_json(m) for m in self.mismatches],
            "max_abs_error": self.max_abs_error,
            "max_rel_error": self.max_rel_error,
            "reference": self.reference,
            "findings": [{"cell": f.cell, "kind": f.kind, "message": f.message}
                         for f in self.findings],
            "macros": self.macros,
            "semantics": self.semantics,
            "application": self.application,
            "libreoffice_semantics": self.libreoffice_semantics,
            "warnings": [{"message": k, "count": n} for k, n in self.warnings.items()],
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
                             "libreoffice_differences": [
                                 {"cell": m.cell, "formula": "=" + m.formula,
                                  "libreoffice": _plain(m.cached), "excel": _plain(m.recomputed)}
                                 for m in self.engine.differences],
                             "seconds": self.engine.seconds}
        return out


def _plain(value: object) -> object:
    if isinstance(value, ExcelError):
        return value.value
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    return value


def _mismatch_json(m: Mismatch) -> dict:
    out = {"cell": m.cell, "formula": "=" + m.formula, "cached": _plain(m.cached),
           "recomputed": _plain(m.recomputed), "root": m.root}
    if m.area:
        out.update(area=m.area, cells=m.cells, at=m.at or m.cell)
    if m.sources:
        out["sources"] = m.sources
    if m.followers:
        out["followers"] = m.followers
    if m.stale:
        out["stale"] = True
    return out


def _worst(report: AuditReport) -> list:
    """Disagreeing cells, sources first, then by the size of the difference."""
    def size(m):
        return m.abs_error if m.abs_error is not None and math.isfinite(m.abs_error) else math.inf
    return sorted(report.mismatches, key=lambda m: (not m.root, -size(m)))


def _names(cells: list[str], shown: int = 5) -> str:
    more = len(cells) - shown
    return ", ".join(cells[:shown]) + (f" (+{more})" if more > 0 else "")


def _disagreements(report: AuditReport, verbose: bool) -> list[str]:
    """Each disagreement at its source with what follows from it; then the cells that
    would show another value if recalculated (stale headlines first)."""
    worst = _worst(report)
    if not worst:
        return []
    sources = [m for m in worst if m.root]
    follow = sorted((m for m in worst if not m.root), key=lambda m: not m.stale)
    limit = MAX_LISTED * 5 if verbose else WORST
    lines = [f"  {len(sources)} disagreement{'s' * (len(sources) != 1)} at the source "
             f"(cached against recomputed; no precedent disagrees)"
             + (f", {report.cells_disagree} formula cells in all with those that follow "
                "from them" if follow or report.cells_disagree != len(sources) else "")
             + ("; the worst:" if not verbose and len(sources) > WORST else ":")]
    for m in sources[:limit]:
        first, _, last = (m.area or "").partition(":")
        where = (f" (array {m.area}, {len(m.cells)} of its cells disagree)"
                 if m.area and first != last else "")
        at = f"at {m.at}: " if m.at else ""
        lines.append(f"    {m.cell}{where}: ={m.formula}")
        lines.append(f"      {at}cached {show_value(m.cached)}, "
                     f"recomputed {show_value(m.recomputed)}"
                     + (f"; {len(m.followers)} cell{'s' * (len(m.followers) > 1)} "
                        f"follow{'s' * (len(m.followers) == 1)} from it: "
                        f"{_names(m.followers)}" if m.followers else ""))
    if follow:
        one = len(follow) == 1
        lines.append(f"  {len(follow)} cell{'s' * (not one)} would show another value if "
                     f"recalculated ({'it follows' if one else 'they follow'} from a "
                     "disagreement)"
                     + ("; the first:" if not verbose and len(follow) > WORST else ":"))
        for m in follow[:limit]:
            why = f", because of {_names(m.sources, 3)}" if m.sources else ""
            lines.append(f"    {m.cell}: ={_cut(m.formula)}")
            lines.append(f"      shows {show_value(m.cached)}, "
                         f"would show {show_value(m.recomputed)}{why}")
    return lines


def format_report(report: AuditReport, verbose: bool = False) -> str:
    """A few lines (counts, reasons, the worst cells, the verdict); ``verbose``: every
    column, every disagreeing cell, every cell not checked and every finding."""
    n_contract = report.counts.by_contract if report.counts else len(report.by_contract)
    contract = f", {n_contract} by contract" if n_contract else ""
    lines = [f"audit of {report.path}",
             f"  {report.formula_cells} formula cells: {report.cells_checked} checked "
             f"({report.cells_agree} agree, {report.cells_disagree} disagree{contract}), "
             f"{report.cells_not_checked} not checked; {report.seconds:.2f} s"]
    if report.saved_without_values:
        lines.append("  no cached values: the file was saved without calculating"
                     + (f" (by {report.application})" if report.application else "")
                     + "; its formulas were recomputed, but there is nothing to compare with")
    if report.semantics != "excel":
        lines.append(f"  recomputed with {report.semantics}'s semantics: the file was saved by "
                     f"{report.application}")
    elif report.application and not report.application.lower().startswith("microsoft"):
        lines.append(f"  recomputed with Excel's semantics: the file was saved by "
                     f"{report.application}, whose own are not modelled")
    reasons = report.not_checked_reasons()
    if reasons and not report.saved_without_values:
        shown = reasons if verbose else reasons[:3]
        lines.append("  not checked: " + "; ".join(f"{n} {r}" for r, n in shown)
                     + ("; ..." if len(shown) < len(reasons) else ""))
    if report.by_contract:
        lines.append(f"  {len(report.by_contract)} of the checked cells call TODAY, NOW, RAND, "
                     "RANDBETWEEN or RANDARRAY (volatile): checked against the function's "
                     "contract, not recomputed; their dependents are recomputed from their "
                     "cached values")
    if report.libreoffice_semantics:
        lines.append(f"  {report.libreoffice_semantics} cells hold LibreOffice's answer where "
                     f"Excel's differs (e.g. SQRT(-1) is #VALUE! there): accepted")
    lines += _disagreements(report, verbose)
    if verbose:
        lines += _columns(report)
        if report.not_checked:
            lines += ["", "  not checked:"]
            lines += [f"    {cell}: {reason}" for cell, reason in report.not_checked.items()]
        if report.by_contract:
            lines += ["", "  checked against the contract of a volatile function:"]
            lines += [f"    {cell}: {how}" for cell, how in report.by_contract.items()]
    findings = [f for f in report.findings if not (report.saved_without_values
                                                   and f.kind == "no_cached_value")]
    if findings:  # (a file saved without values is said so above, once)
        kinds: dict[str, int] = {}
        for f in findings:
            kinds[f.kind] = kinds.get(f.kind, 0) + 1
        lines.append("  findings: " + ", ".join(f"{k} {n}" for k, n in sorted(kinds.items())))
        for f in findings[:None if verbose else 3]:
            lines.append(f"    {f.kind}: {f.cell}: {f.message}")
    if report.macros:
        lines.append(f"  macros: the file holds a VBA project ({report.macros}); "
                     "the audit does not check macros")
    if report.mechanics is not None:
        lines += _mechanics_lines(report.mechanics) if verbose else _mechanics_line(report.mechanics)
    if report.engine is not None:
        e = report.engine
        lines += [f"  {e.engine}: {e.cells} cells recalculated in {e.seconds:.1f} s, "
                  f"{len(e.mismatches)} disagree with the recomputed values"]
        for m in e.mismatches[:MAX_LISTED if verbose else WORST]:
            lines.append(f"    {m.cell}: ={_cut(m.formula)}: {e.engine} "
                         f"{_cut(show_value(m.cached))}, ours {_cut(show_value(m.recomputed))}")
        if e.differences:
            lines.append(f"  {len(e.differences)} cells differ where LibreOffice's own semantics "
                         "differ from Excel's (its difference, not the file's; not failed):")
            for m in e.differences[:MAX_LISTED if verbose else 3]:
                lines.append(f"    {m.cell}: ={_cut(m.formula)}: LibreOffice "
                             f"{_cut(show_value(m.cached))}, "
                             f"Excel {_cut(show_value(m.recomputed))}")
    if report.warnings:
        lines.append(f"  the audit warned {sum(report.warnings.values())} times (its own "
                     "problem, not the file's): " + "; ".join(
                         f"{k} (x{n})" for k, n in list(report.warnings.items())[:3]))
    lines.append(verdict_line(report, verbose))
    return "\n".join(lines)


def _cut(text: str, width: int = 80) -> str:
    return text if len(text) <= width else text[:width - 3] + "..."


def _columns(report: AuditReport) -> list[str]:
    lines = ["", f"  {'sheet':<12}{'column':<8}{'cells':>8}{'worst error':>14}  {'at':<10}disagree"]
    for c in report.columns:
        lines.append(f"  {c.sheet:<12}{c.column:<8}{c.cells:>8}{c.worst_error:>14.2e}  "
                     f"{c.worst_cell:<10}{c.mismatches}")
    return lines


def _mechanics_line(m: MechanicsReport) -> list[str]:
    bad = [q.name for q in m.quantities if not q.ok]
    worst = max((q.max_error for q in m.quantities), default=0.0)
    line = (f"  reference model of {m.mechanism}: {len(m.quantities)} quantities, max error "
            f"{worst:.2e}")
    return [line + (f"; FAIL: {', '.join(bad)}" if bad else "")]


def _mechanics_lines(m: MechanicsReport) -> list[str]:
    lines = ["", f"  against the independent reference model of {m.mechanism} "
                 f"(tolerance {REFERENCE_TOLERANCE:g} of each column's magnitude or row's "
                 f"rounding noise; rows flagged singular not compared):"]
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
            lines.append(f"    {name:<22}{show_value(value)}")
    if m.paper_table:
        lines.append("  lever angular acceleration alpha_5 against the model, per 10 deg "
                     "(the paper's Table 2; it found 0.707% at 310 deg against CAD):")
        lines.append(f"    {'theta_1':>8}{'workbook':>18}{'reference':>18}{'error %':>11}")
        for angle, ours, ref, error in m.paper_table:
            lines.append(f"    {angle:>8g}{ours:>18.10f}{ref:>18.10f}{error:>11.2e}")
    return lines
