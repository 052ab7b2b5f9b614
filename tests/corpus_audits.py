"""One audit of every corpus workbook (../shared/corpus/xlsx), shared by the tests that
read the corpus: the 76 files take ~45 s in one process, so two processes share them,
the largest first.

Each file is sorted as ``coverage.py`` sorts it: fully audited (no disagreement, every
formula cell recomputed), disagreements, partly checked, refused (a one-line error) or
crash (any other exception).
"""

from __future__ import annotations

import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

CORPUS = Path("/work/shared/corpus/xlsx")
# files whose whole report a test reads (the others keep only their counts)
WHOLE_REPORTS = frozenset({"formulas__test.xlsx"})


@dataclass(frozen=True)
class Outcome:
    cls: str            # fully audited | disagreements | partly checked | refused | crash
    formula_cells: int
    recomputed: int
    detail: object      # the first disagreeing cells, or the error's text
    report: object = None  # the AuditReport, for WHOLE_REPORTS only
    sources: int = 0    # disagreements at their source (an array formula's once)
    # every disagreeing cell -> the cell it follows from (itself at a source)
    disagreeing: dict = field(default_factory=dict)
    not_checked: dict = field(default_factory=dict)  # cell -> why it was not recomputed


def corpus_files() -> list[Path]:
    return sorted(p for p in CORPUS.iterdir() if p.suffix.lower() in (".xlsx", ".xlsm"))


def audit_one(path: Path) -> Outcome:
    from workbook_gen import audit
    from workbook_gen.errors import WorkbookGenError
    try:
        report = audit(path)
    except WorkbookGenError as exc:
        return Outcome("refused", 0, 0, str(exc))
    except Exception as exc:  # noqa: BLE001 - a crash is what the corpus test counts
        return Outcome("crash", 0, 0, repr(exc))
    recomputed = report.formula_cells - report.cells_not_checked
    if not report.ok:
        cls = "disagreements"
    elif report.cells_not_checked:
        cls = "partly checked"
    else:
        cls = "fully audited"
    return Outcome(cls, report.formula_cells, recomputed,
                   [m.cell for m in report.mismatches[:3]],
                   report if path.name in WHOLE_REPORTS else None, report.disagreements,
                   _disagreeing(report), dict(report.not_checked))


def _disagreeing(report) -> dict[str, str]:
    """Each disagreeing cell (an array formula's every cell) -> its source's cell."""
    cells: dict[str, str] = {}
    for m in report.mismatches:
        source = m.cell if m.root else (m.sources[0] if m.sources else m.cell)
        for cell in (m.cell, *m.cells):
            cells[cell] = source
    return cells


def _one_process() -> None:
    """The workers already share the cores: an audit forks no reader of its own."""
    os.environ["WORKBOOK_GEN_SERIAL"] = "1"


def audit_corpus(workers: int = 2) -> dict[str, Outcome]:
    """Every corpus file's outcome by file name, audited in ``workers`` fresh processes."""
    files = sorted(corpus_files(), key=lambda p: -p.stat().st_size)
    context = multiprocessing.get_context("spawn")  # no fork of the test process's threads
    with ProcessPoolExecutor(workers, mp_context=context, initializer=_one_process) as pool:
        outcomes = dict(zip((p.name for p in files), pool.map(audit_one, files)))
    return dict(sorted(outcomes.items()))
