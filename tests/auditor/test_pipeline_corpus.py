"""The audit over the real-world corpus (../shared/corpus/xlsx: 76 workbooks saved by
Excel or LibreOffice that this project did not write).

A ratchet: the counts per class may only improve. The audits are the session's
``corpus_audits`` (tests/corpus_audits.py: two processes, ~30 s; formulas__test.xlsx is
the largest), each file sorted as ``coverage.py`` sorts it. The thresholds are what the
audit reached when this test was written; raise them as the audit improves, never lower
them.
"""

from __future__ import annotations

import pytest

# reached on 2026-11-23 (44 fully audited, 52,919 of 56,808 formula cells recomputed, 12
# files with disagreements, 1 refused); the first two may only move up, the others down
# 19:45: the corpus's functions (distributions, complex, LINEST, VDB, CELL...): 60 fully
# audited, 12 files with disagreements (formulas__test.xlsx among them)
# 19:50: volatile cells by contract, false cycles settled, the LAMBDA family and dynamic
# arrays, a sheet without its part reported (closedxml__tdf111974.xlsm no longer refused):
# 61 fully audited, 56,484 of 57,335 recomputed, nothing refused (helper corpb); 20:10:
# regular expressions, TEXTSPLIT, SORTBY: coverage.py 56,752 of 57,344 (99.0%)
# 22:30: SUBTOTAL/AGGREGATE leave out hidden rows and nested subtotals
# (closedxml__functions-excel-2010.xlsx fully audited; helper corpa3): 63 with POI's;
# MATCH's -1 scan stops past a run equal to the lookup value (pycel__lookup.xlsx): 64;
# TEXT's number formats placeholder by placeholder (pycel__text.xlsx): 65
# 22:35: securities, ODD*, AMOR*, CHAR/CODE in the Mac character set, ASC (helper corpb3):
# coverage.py 66 of 76, 56,831 of 57,344 evaluated; >= 56,800 recomputed here
# 22:58: circular references as Excel evaluates them with iteration off (formulas__circular
# fully audited), CONVERT, XMATCH, criteria arrays, IS* in array formulas (formulas__test:
# 944 -> 219 disagreeing cells; helper corpc3): 6 files with disagreements (4 known, the
# sheetjs stress test's XNPV, formulas__test)
# 2026-11-27 18:10: unions with their areas (AREAS, ISFORMULA, INDEX's area_num), Excel's
# error order in the tests and fits of two arrays, LINEST's #VALUE!: coverage.py 56,894 of
# 57,344; formulas__test.xlsx 100 -> 36 disagreeing cells
# 2026-11-27 (issue 20, 166 files: 90 more from IronCalc, NPOI, ExcelDataReader and the
# Open XML SDK): number formats and the 1904 date system, tables and relative names,
# filters and spill references, named LAMBDAs, the consistency rule, FORMULATEXT/SHEET,
# OLAP caches and external links, criteria and edge values, counts that add up
# (coverage.py: 151 of 166 fully audited, 113,626 of 114,274 evaluated, 29 at the source)
# 2026-11-28 (helper newfns): PERCENTOF, TRIMRANGE, GROUPBY, PIVOTBY, BAHTTEXT: 113,697
MIN_FULLY_AUDITED = 151
MIN_RECOMPUTED_CELLS = 113_690
MIN_EVALUATED_SHARE = 0.99   # issue 20: at least 99% of the corpus's formula cells
MAX_SOURCE_DISAGREEMENTS = 29  # issue 20: at most 50, each explained in the README
MAX_FORMULAS_TEST_DISAGREEING = 11  # Mac Excel 16's test of every function
MAX_REFUSED = 0
# the files allowed to disagree, and why (the README's corpus paragraph says the same):
# the first four hold values no recalculation gives, the last two are where the evaluator
# still differs from Excel
KNOWN_DISAGREEMENTS = {
    "phpspreadsheet__issue.2301.xlsx": "K57: a stale cached 'H' (AO56 is empty: 'M')",
    "sheetjs__LONumbers.xlsx": "LibreOffice 4.1 cached empty strings for numbers",
    "closedxml__named-ranges-global.xlsx": "LibreOffice 3.7 flattened an array formula",
    "closedxml__database.xlsx": "LibreOffice 3.4's database range 'database1' is not in "
                                "the file",
    "formulas__test.xlsx": "11 cells where Mac Excel 16 still differs from the evaluator",
    "sheetjs__formula_stress_test.xlsx": "XNPV B12: Excel's iteration stops at -6.2e-6",
}
# files whose cached values are wrong: the audit must always report them
STALE = {"phpspreadsheet__issue.2301.xlsx", "sheetjs__LONumbers.xlsx",
         "closedxml__named-ranges-global.xlsx", "closedxml__database.xlsx"}


@pytest.fixture(scope="module")
def corpus_results(corpus_audits):
    results = {name: (o.cls, o.formula_cells, o.recomputed, o.detail)
               for name, o in corpus_audits.items()}
    assert len(results) >= 166
    return results


def _names(results, cls):
    return sorted(name for name, r in results.items() if r[0] == cls)


def test_no_crash_and_no_new_refusal(corpus_results):
    assert _names(corpus_results, "crash") == [], {
        n: corpus_results[n][3] for n in _names(corpus_results, "crash")}
    assert len(_names(corpus_results, "refused")) <= MAX_REFUSED, {
        n: corpus_results[n][3] for n in _names(corpus_results, "refused")}


def test_fully_audited_files_and_recomputed_cells_only_grow(corpus_results):
    fully = _names(corpus_results, "fully audited")
    cells = sum(r[1] for r in corpus_results.values())
    recomputed = sum(r[2] for r in corpus_results.values())
    assert len(fully) >= MIN_FULLY_AUDITED, (len(fully), fully)
    assert recomputed >= MIN_RECOMPUTED_CELLS, (recomputed, cells)
    assert recomputed >= MIN_EVALUATED_SHARE * cells, (recomputed, cells)


def test_only_known_files_disagree_and_stale_files_stay_reported(corpus_audits):
    disagreeing = {name for name, o in corpus_audits.items() if o.cls == "disagreements"}
    assert disagreeing <= set(KNOWN_DISAGREEMENTS), {
        n: corpus_audits[n].detail for n in disagreeing - set(KNOWN_DISAGREEMENTS)}
    assert STALE <= disagreeing, STALE - disagreeing
    sources = {name: o.sources for name, o in corpus_audits.items() if o.sources}
    assert sum(sources.values()) <= MAX_SOURCE_DISAGREEMENTS, sources


def test_formulas_test_disagreements_only_shrink(corpus_audits):
    report = corpus_audits["formulas__test.xlsx"].report
    assert report.disagreements <= MAX_FORMULAS_TEST_DISAGREEING, \
        sorted(m.cell for m in report.mismatches if m.root)
