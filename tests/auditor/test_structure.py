"""auditor/structure.py: findings about a workbook's structure.

Cases written with openpyxl: a name Excel refuses (R1C1 reads as a cell reference: "Names
cannot be the same as a cell reference, such as Z$100 or R1C1",
https://support.microsoft.com/en-us/office/names-in-formulas-fc2935f9-115d-4bef-a370-3aa8bb4c91f1),
a name that does not parse, a missing sheet and name, a function Excel lacks (#NAME?),
a volatile function (NOW, RAND: https://learn.microsoft.com/en-us/office/client-developer/excel/excel-recalculation),
two cells referring to each other. Each expected finding is named by hand."""

from __future__ import annotations

from types import SimpleNamespace

import openpyxl
import pytest
from openpyxl.workbook.defined_name import DefinedName

from workbook_gen import audit
from workbook_gen.auditor.inputs import read_inputs
from workbook_gen.auditor.structure import Finding, check_structure
from workbook_gen.cellref import cell_name
from workbook_gen.xlsx.model import ExternalLink


@pytest.fixture(scope="module")
def path(tmp_path_factory):
    book = openpyxl.Workbook()
    ws = book.active
    ws.title = "S"
    ws["A1"] = 1
    ws["B1"] = "=Nope!A1"
    ws["B2"] = "=zz*2"
    ws["B3"] = "=FOOBAR(1)"
    ws["B4"] = "=NOW()"
    ws["B5"] = "=RAND()+RAND()"
    ws["B6"] = "=RAND()"
    ws["B7"] = "=ok+A1"
    ws["C1"] = "=C2+1"
    ws["C2"] = "=C1+1"
    book.defined_names["R1C1"] = DefinedName("R1C1", attr_text="S!$A$1")
    book.defined_names["bad"] = DefinedName("bad", attr_text="S!$A$1+(")
    book.defined_names["ok"] = DefinedName("ok", attr_text="S!$A$1")
    out = tmp_path_factory.mktemp("structure") / "structure.xlsx"
    book.save(out)
    return out


def test_the_audit_finds_each_planted_structure(path):
    findings = audit(path).findings
    found = {(f.kind, f.cell) for f in findings if f.kind != "no_cached_value"}
    assert found == {
        ("illegal_name", "R1C1"),
        ("defined_name_syntax", "BAD"),
        ("circular_reference", "S!C1"),
        ("unsupported_function", "S!B3"),
        ("volatile_function", "S!B4"),      # NOW
        ("volatile_function", "S!B5"),      # RAND, first of two cells
        ("unresolved_reference", "S!B1"),   # no sheet Nope
        ("unresolved_reference", "S!B2"),   # no name zz
    }
    messages = {(f.kind, f.cell): f.message for f in findings}
    assert messages["volatile_function", "S!B5"] == "2 cells call RAND, a volatile function"
    assert messages["unresolved_reference", "S!B1"] == "no sheet named 'Nope'"
    assert messages["unresolved_reference", "S!B2"] == "no defined name 'zz'"
    assert "R1C1 reference" in messages["illegal_name", "R1C1"]


def _evaluation(**fields):
    base = dict(bad_names={}, cycles=[], unsupported={}, unknown={}, volatile={}, runs=[])
    return SimpleNamespace(**{**base, **fields})


def test_cycles_links_and_functions_by_hand(path):
    inputs = read_inputs(path)
    cycle = [("S", r, 9) for r in range(1, 11)]
    inputs.book.external_links.append(ExternalLink(1, "xl/externalLinks/externalLink1.xml",
                                                   "other.xlsx"))
    try:
        found = check_structure(inputs, _evaluation(
            cycles=[cycle], unsupported={("S", 3, 2): ["FOO"], ("S", 2, 2): ["FOO", "BAR"]},
            unknown={}), cell_name)
    finally:
        inputs.book.external_links.pop()
    by_kind = {}
    for f in found:
        by_kind.setdefault(f.kind, []).append(f)
    [cyc] = by_kind["circular_reference"]
    assert cyc.cell == "S!I1" and cyc.message.startswith("10 cells refer to each other: S!I1 -> ")
    assert "(and 2 more)" in cyc.message and "show 0" in cyc.message
    assert by_kind["external_link"] == [Finding("xl/externalLinks/externalLink1.xml",
                                                "external_link", "the workbook links to other.xlsx")]
    unsupported = [(f.cell, f.message.split(",")[0]) for f in by_kind["unsupported_function"]]
    assert unsupported == [("S!B2", "1 cells call BAR"), ("S!B2", "2 cells call FOO")]
    assert by_kind["illegal_name"] == [Finding("R1C1", "illegal_name",
                                               "it reads as an R1C1 reference")]
    inputs.book.iterate = True
    [cyc] = check_structure(inputs, _evaluation(cycles=[cycle[:2]]), cell_name)[1:]
    assert cyc.message == ("2 cells refer to each other: S!I1 -> S!I2; they and what reads "
                           "them are not checked (iterative calculation is on)")
