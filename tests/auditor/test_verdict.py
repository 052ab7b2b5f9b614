"""auditor/verdict.py: row runs written as "rows 13-15, 20" (against itertools.groupby),
and the causes of a failed audit named: the disagreeing source cell of SheetJS's stress
test (Excel's XNPV iteration, listed in tests/test_fixture_workbooks.py), and none for a
file that passes."""

from __future__ import annotations

import itertools
import random

import pytest

from corpus_audits import CORPUS
from workbook_gen import audit
from workbook_gen.auditor.verdict import causes, row_ranges, verdict_line


def runs(rows: list[int]) -> list[str]:
    out = []
    for _, group in itertools.groupby(enumerate(sorted(set(rows))), lambda p: p[1] - p[0]):
        run = [r for _, r in group]
        out.append(f"{run[0]}-{run[-1]}" if len(run) > 1 else f"{run[0]}")
    return out


@pytest.mark.parametrize("seed", range(30))
def test_row_ranges_as_groupby(seed):
    rng = random.Random(seed)
    rows = [rng.randint(2, 60) for _ in range(rng.randint(1, 25))]
    shown = rng.randint(1, 6)
    want = runs(rows)
    text = ("rows " if len(rows) > 1 else "row ") + ", ".join(want[:shown])
    if len(want) > shown:
        text += f" (+{len(want) - shown} more)"
    assert row_ranges(rows, shown) == text


def test_a_failed_audit_names_its_source_cell():
    report = audit(CORPUS / "sheetjs__formula_stress_test.xlsx")
    assert not report.ok
    (cause,) = causes(report)
    assert cause.kind == "cells" and cause.message == \
        "1 cell disagrees at the source: Finance!B12"
    assert verdict_line(report, False) == \
        "  FAILED: 1 cell disagrees at the source: Finance!B12 (see above; --verbose lists all)"


def test_a_passing_audit_has_no_cause():
    report = audit(CORPUS / "pycel__stats.xlsx")
    assert report.ok and causes(report) == []
    assert verdict_line(report, True).startswith("  OK: every checked cell agrees")
