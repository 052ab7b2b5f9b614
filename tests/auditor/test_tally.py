"""auditor/tally.py: every formula cell counted once by verdict. The cells and the
disagreement are planted with XlsxWriter (tests/planted.py); the expected counts are
derived by hand from the cells written."""

from __future__ import annotations

import openpyxl
import pytest

from workbook_gen import audit
from workbook_gen.auditor.inputs import read_inputs
from workbook_gen.auditor.tally import Tally, absent, no_cached_findings, tally
from workbook_gen.cellref import cell_name

from planted import planted_book

B1, B2, B3, D1, TB1 = ("S", 1, 2), ("S", 2, 2), ("S", 3, 2), ("S", 1, 4), ("T", 1, 2)
C1, C2 = ("S", 1, 3), ("S", 2, 3)   # an array formula's anchor and its second cell
COMPARED = [B1, B2, B3, D1, TB1, C1, C2]


@pytest.fixture(scope="module")
def planted(tmp_path_factory):
    return planted_book(tmp_path_factory.mktemp("tally") / "planted.xlsx")


@pytest.fixture(scope="module")
def inputs(planted):
    return read_inputs(planted)


def test_absent_is_none_not_empty_text():
    cached = {("S", 1, 1): None, ("S", 1, 2): "", ("S", 1, 3): 0, ("S", 1, 4): False,
              ("S", 1, 5): None}
    assert absent(cached) == [("S", 1, 1), ("S", 1, 5)]


def test_a_cell_of_an_array_counts_with_its_anchor(inputs):
    t = tally(inputs, COMPARED, {B3, C2}, set(), set(), 2)
    # six formula cells (five plain, the array once): B3 and the array disagree
    assert t == Tally(agree=4, disagree=2, not_checked=0, by_contract=0, disagreements=2)
    assert t.checked == 6 == inputs.formula_count
    assert tally(inputs, COMPARED, {C1, C2}, set(), set(), 1).disagree == 1


def test_not_checked_and_by_contract_take_cells_from_agree(inputs):
    t = tally(inputs, COMPARED, {B3}, {D1}, {B1}, 1)
    assert (t.agree, t.disagree, t.not_checked, t.by_contract) == (3, 1, 1, 1)
    assert t.checked == 5
    # a cell that breaks its contract disagrees; one not checked is neither
    t = tally(inputs, COMPARED, {B1, D1}, {D1}, {B1}, 1)
    assert (t.agree, t.disagree, t.not_checked, t.by_contract) == (4, 1, 1, 0)
    # a constant named among the not checked is not a formula cell: not counted
    assert tally(inputs, COMPARED, set(), {("S", 1, 1)}, set(), 0).not_checked == 0


def test_the_audit_counts_the_planted_disagreement(planted):
    report = audit(planted)
    c = report.counts
    assert (c.agree, c.disagree, c.not_checked, c.by_contract) == (5, 1, 0, 0)
    assert c.agree + c.disagree + c.not_checked + c.by_contract == report.formula_cells == 6
    assert [(m.cell, m.cached, m.recomputed) for m in report.mismatches] == [("S!B3", 99, 5)]


def test_no_cached_value_one_finding_per_cell(inputs):
    inputs.cached[B2], saved = None, inputs.cached[B2]
    try:
        found = no_cached_findings(inputs, absent(inputs.cached), cell_name)
    finally:
        inputs.cached[B2] = saved
    assert [(f.cell, f.kind) for f in found] == [("S!B2", "no_cached_value")]
    assert no_cached_findings(inputs, absent(inputs.cached), cell_name) == []


def test_a_file_saved_without_calculating_gives_one_finding(tmp_path):
    book = openpyxl.Workbook()  # openpyxl writes formulas without values
    ws = book.active
    ws.title = "W"
    ws["A1"], ws["B1"], ws["B2"], ws["B3"] = 1.5, "=A1*2", "=B1+1", "=SUM(B1:B2)"
    book.save(tmp_path / "nocalc.xlsx")
    inputs = read_inputs(tmp_path / "nocalc.xlsx")
    found = no_cached_findings(inputs, absent(inputs.cached), cell_name)
    assert len(found) == 1 and found[0].cell == "W!B1" and found[0].kind == "no_cached_value"
    assert "none of the 3 formula cells" in found[0].message
