"""auditor/sources.py: a disagreement counted once, at its source, with what follows.

The chain is planted with XlsxWriter: B1 =A1*3 cached 7 (wrong, 6), C1 =B1+1 cached 8 and
D1 =C1*2 cached 16 are right for the cached B1 but show 7 and 14 once recalculated
(they follow from B1); E1 =A1 cached 5 is wrong on its own. The expected sources and
followers are derived by hand from the cells written."""

from __future__ import annotations

import pytest
import xlsxwriter

from workbook_gen import audit
from workbook_gen.auditor.inputs import read_inputs
from workbook_gen.auditor.report import Mismatch
from workbook_gen.auditor.sources import Stale, arrays_once, rectangles, settle
from workbook_gen.cellref import cell_name
from workbook_gen.formula import parse

from planted import planted_book


@pytest.fixture(scope="module")
def chain(tmp_path_factory):
    path = tmp_path_factory.mktemp("sources") / "chain.xlsx"
    book = xlsxwriter.Workbook(str(path))
    s = book.add_worksheet("S")
    s.write_number("A1", 2)
    s.write_formula("B1", "=A1*3", None, 7)
    s.write_formula("C1", "=B1+1", None, 8)
    s.write_formula("D1", "=C1*2", None, 16)
    s.write_formula("E1", "=A1", None, 5)
    s.write_formula("F1", "=A1*10", None, 20)
    book.close()
    return path


def test_rectangles_a_formula_reads():
    found = list(rectangles(parse("SUM(C3:A1)+T!B2+k"), "S", {"K": "S!$D$5:$E$6"}))
    assert found == [("S", 1, 1, 3, 3), ("T", 2, 2, 2, 2), ("S", 5, 4, 6, 5)]
    # a name's relative reference reads from the cell that uses it (defined at A1, as
    # Excel's Name Manager does: "=S!A1" used in C2 is C2)
    assert list(rectangles(parse("r*2"), "S", {"r": "S!A1"}, at=(2, 3))) == [
        ("S", 2, 3, 2, 3)]
    assert list(rectangles(parse("nothere+1"), "S", {})) == []


def test_the_audit_names_the_source_and_its_followers(chain):
    report = audit(chain)
    by_cell = {m.cell: m for m in report.mismatches}
    assert sorted(by_cell) == ["S!B1", "S!C1", "S!D1", "S!E1"]
    assert by_cell["S!B1"].root and by_cell["S!B1"].followers == ["S!C1", "S!D1"]
    assert by_cell["S!E1"].root and by_cell["S!E1"].followers == []
    for follower in ("S!C1", "S!D1"):
        assert not by_cell[follower].root and by_cell[follower].sources == ["S!B1"]
    assert (by_cell["S!D1"].cached, by_cell["S!D1"].recomputed) == (16, 14)
    assert report.counts.disagreements == 2 and report.counts.disagree == 4


def _m(key, cached=1, recomputed=2):
    return Mismatch(cell_name(key), "x", cached, recomputed, key=key)


def test_an_array_disagrees_once_at_its_anchor(tmp_path):
    inputs = read_inputs(planted_book(tmp_path / "p.xlsx"))  # C1:C2 {=A1:A2*2}
    c1, c2, b3 = ("S", 1, 3), ("S", 2, 3), ("S", 3, 2)
    out = arrays_once(inputs, [_m(b3), _m(c2, 6, 7), _m(c1, 4, 5)], cell_name)
    assert [m.cell for m in out] == ["S!B3", "S!C1"]
    grouped = out[1]
    assert grouped.area == "C1:C2" and grouped.cells == ["S!C2", "S!C1"]
    assert grouped.at == "S!C2" and (grouped.cached, grouped.recomputed) == (6, 7)
    assert grouped.key == c1


def test_settle_by_hand(chain):
    inputs = read_inputs(chain)
    b1, c1, d1, e1, f1 = (("S", 1, c) for c in (2, 3, 4, 5, 6))
    out = settle(inputs, [_m(b1), _m(d1), _m(e1)], {}, cell_name)
    by = {m.cell: m for m in out}
    # D1 reads C1, which agrees: D1 is a source of its own here
    assert by["S!D1"].root and by["S!B1"].followers == []
    out = settle(inputs, [_m(b1), _m(c1), _m(d1)], {}, cell_name)
    assert [m.sources for m in out] == [[], ["S!B1"], ["S!B1"]]
    # a stale aggregate is listed when something upstream disagrees, not otherwise
    stale = {f1: Stale("A1*10", 20, 20.000001)}
    assert [m.cell for m in settle(inputs, [_m(b1), _m(e1)], stale, cell_name)] == \
        ["S!B1", "S!E1"]  # F1 reads A1 only: nothing upstream disagrees
    stale = {d1: Stale("C1*2", 16, 14)}
    out = settle(inputs, [_m(b1), _m(c1)], stale, cell_name)
    assert out[-1].cell == "S!D1" and out[-1].stale and out[-1].sources == ["S!B1"]
