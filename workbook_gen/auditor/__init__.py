"""Audit a workbook: recompute every formula cell from its text and check it.

    report = audit("outputs/sewing_machine.xlsx")
    report.ok, report.cells_checked, report.mismatches, report.reference

Checks, for every formula cell, the recomputed value against the cached one
(Excel semantics; a LibreOffice-saved value explained only by LibreOffice's
known deviations is accepted and counted); for workbooks made by
workbook-gen, every Table column against the independent reference model and
the closure residuals; the structure (names, references, functions, links).
With ``engine="libreoffice"`` the file is also recalculated by LibreOffice.

Every formula cell is counted once (``tally.py``): agree + disagree + not checked + by
contract = formula cells. A cell without a cached value is not checked
(``no_cached_value``); a file saved without calculating (openpyxl, pandas) says so once
and is ``ok`` (exit 0: it contradicts nothing) with "nothing was verified". A
disagreement counts once at its source, an array formula's at its anchor; the cells
that follow from it, including aggregates that agree with their stale precedents but
would show another value if recalculated, are listed with it (``sources.py``). What the
audit's own code warns of is counted in the report, never printed (``caught.py``).
"""

from .pipeline import PHASES, audit
from .report import AuditReport, EngineResult, Mismatch

__all__ = ["audit", "AuditReport", "EngineResult", "Mismatch", "PHASES"]
