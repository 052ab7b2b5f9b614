"""The audit report's verdicts (docs/audit.md, Verdicts): a cell without a cached value is not a
disagreement, an array formula disagrees once, a disagreement counts once at its source with
what follows from it (including a headline "PASS" that recalculation would turn to "FAIL"),
the counts add up, and stdout/stderr hold only the report."""

from __future__ import annotations

import json
import re
import subprocess
import sys
import zipfile
from pathlib import Path
from xml.etree.ElementTree import Element, iterparse

import pytest
import xlsxwriter

from workbook_gen.auditor import audit
from workbook_gen.auditor.report import format_report
from workbook_gen.engines.libreoffice import find_soffice, recalculated_values

CORPUS = Path("/work/shared/corpus/xlsx")
ROOT = Path(__file__).resolve().parents[2]
NS = "{http://schemas.openxmlformats.org/spreadsheetml/2006/main}"
SHEET_PART = re.compile(r"xl/(?:worksheets|macrosheets)/[^/]+\.xml$")


def corpus(name: str) -> Path:
    path = CORPUS / name
    if not path.exists():
        pytest.skip(f"corpus file {name} not present")
    return path


def formula_cells_in_xml(path: Path) -> list[tuple[str, Element]]:
    """(part, <c> element) of every cell that carries an <f>, read off the sheet XML
    (independently of the audit's reader)."""
    out = []
    with zipfile.ZipFile(path) as z:
        for part in z.namelist():
            if not SHEET_PART.match(part):
                continue
            with z.open(part) as fh:
                for _, el in iterparse(fh):
                    if el.tag == NS + "c" and el.find(NS + "f") is not None:
                        out.append((part, el))
    return out


def run_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", "import sys; from workbook_gen.cli import main; "
                           "sys.exit(main())", "audit", *args], capture_output=True, text=True,
                          cwd=ROOT, env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})


def replace_sheet_xml(path: Path, part: str, edit) -> None:
    """Rewrite one part of an xlsx in place: ``edit(text) -> text``."""
    with zipfile.ZipFile(path) as z:
        items = [(i, z.read(i.filename)) for i in z.infolist()]
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        for info, data in items:
            if info.filename == part:
                data = edit(data.decode()).encode()
            z.writestr(info, data)


# -- no cached value -------------------------------------------------------------------

def test_openpyxl_file_without_cached_values_is_not_checked_and_says_so():
    path = corpus("ironcalc__openpyxl_example.xlsx")
    cells = formula_cells_in_xml(path)
    # the file itself: every formula cell without a value (openpyxl writes <v/>)
    assert cells and all(not (c.findtext(NS + "v") or "") and c.get("t") in (None, "n")
                         for _, c in cells)
    report = audit(path)
    assert report.mismatches == [] and report.cells_disagree == 0
    assert report.saved_without_values
    assert report.cells_no_cached_value == report.cells_not_checked == len(cells)
    assert report.cells_agree == 0
    kinds = [f.kind for f in report.findings]
    assert kinds.count("no_cached_value") == 1  # once, not per cell
    # openpyxl stores CONCAT without Excel's _xlfn. prefix: #NAME? when Excel recalculates
    assert [f.message for f in report.findings if f.kind == "unsupported_function"] == [
        f for f in (m.message for m in report.findings) if "_xlfn. prefix" in f]
    text = format_report(report)
    assert "every checked cell agrees" not in text
    assert "nothing was verified" in text and "saved without calculating" in text
    done = run_cli(str(path), "--json")
    assert done.returncode == 0 and done.stderr == ""
    data = json.loads(done.stdout)
    assert data["saved_without_values"] is True and data["cells_no_cached_value"] == len(cells)
    assert data["disagreements"] == 0 and data["mismatches"] == []


def test_absent_value_is_not_an_empty_string(tmp_path):
    """<v/> of a number is absent (not checked); t="str" with <v></v> is the text "": it
    agrees with a formula giving "" and disagrees with one giving a number."""
    path = tmp_path / "absent.xlsx"
    wb = xlsxwriter.Workbook(path)
    ws = wb.add_worksheet("S")
    ws.write_number("A1", 4)
    ws.write_formula("B1", "=A1*2", None, 8)      # agrees
    ws.write_formula("B2", "=A1*3", None, 12)     # its value removed below: absent
    ws.write_formula("B3", '=""', None, "")       # t="str", <v></v>: ""
    ws.write_formula("B4", "=A1+1", None, "")     # t="str", <v></v>: "" against 5
    ws.write_formula("B5", '=""', None, "")       # <v></v> of a number: shows "" as it would
    wb.close()
    replace_sheet_xml(path, "xl/worksheets/sheet1.xml", lambda x: x.replace(
        "<f>A1*3</f><v>12</v>", "<f>A1*3</f><v/>").replace(
        '<c r="B3"><f>', '<c r="B3" t="str"><f>').replace('<c r="B4"><f>', '<c r="B4" t="str"><f>'))
    with zipfile.ZipFile(path) as z:
        xml = z.read("xl/worksheets/sheet1.xml").decode()
    assert '<c r="B3" t="str"><f>""</f><v></v></c>' in xml and "<v/>" in xml
    report = audit(path)
    assert report.not_checked == {"S!B2": report.not_checked["S!B2"]}
    assert report.not_checked["S!B2"].startswith("no cached value")
    assert [m.cell for m in report.mismatches] == ["S!B4"]
    assert (report.cells_agree, report.cells_disagree, report.cells_not_checked) == (3, 1, 1)
    assert not report.saved_without_values
    assert [(f.cell, f.kind) for f in report.findings if f.kind == "no_cached_value"] == [
        ("S!B2", "no_cached_value")]


def test_libreoffice_stale_empty_strings_stay_disagreements():
    """sheetjs__LONumbers.xlsx: LibreOffice 4.1 saved "" (an inline string) for formulas
    that read numbers; an empty cached string is a value, and a wrong one."""
    path = corpus("sheetjs__LONumbers.xlsx")
    empty = set()
    for part, c in formula_cells_in_xml(path):
        inline = c.find(NS + "is")
        if c.get("t") == "inlineStr" and inline is not None and not "".join(inline.itertext()):
            empty.add("Sheet1!" + c.get("r"))
    assert len(empty) >= 8
    report = audit(path)
    assert report.semantics == "libreoffice" and "LibreOffice" in report.application
    assert empty <= {m.cell for m in report.mismatches}
    assert all(m.cached == "" for m in report.mismatches if m.cell in empty)
    assert report.cells_no_cached_value == 0
    assert "recomputed with libreoffice's semantics" in format_report(report)


# -- array formulas, sources and followers ---------------------------------------------

def _stale_book(path: Path) -> None:
    """Table!B2:B5 = A*2 with B4's cached value stale (0, not 6); Checks!B4 = MAX of them
    and Checks!B2 its "PASS"/"FAIL" verdict, both cached from the stale values; an array
    formula whose area cells were saved as 0."""
    wb = xlsxwriter.Workbook(path)
    t, c = wb.add_worksheet("Table"), wb.add_worksheet("Checks")
    for r, a in enumerate([1, 2, 3, 2], start=1):
        t.write_number(r, 0, a)
        t.write_formula(r, 1, f"=A{r + 1}*2", None, 0 if r == 3 else a * 2)
    c.write_formula("B4", "=MAX(Table!B2:B5)", None, 4)
    c.write_formula("B2", '=IF(B4<=5,"PASS","FAIL")', None, "PASS")
    c.write_formula("C2", "=B4*10", None, 40)
    c.write_array_formula("E1:E3", "{=Table!A2:A4*3}", None, 3)
    wb.close()


def test_array_formula_disagrees_once_at_its_anchor(tmp_path):
    path = tmp_path / "stale.xlsx"
    _stale_book(path)
    report = audit(path)
    arrays = [m for m in report.mismatches if m.area]
    assert len(arrays) == 1
    m = arrays[0]
    assert (m.cell, m.area, m.cells, m.root) == ("Checks!E1", "E1:E3",
                                                 ["Checks!E2", "Checks!E3"], True)
    assert not any(x.cell in ("Checks!E2", "Checks!E3") for x in report.mismatches)


def test_headline_pass_over_a_stale_check_is_listed_with_its_source(tmp_path):
    path = tmp_path / "stale.xlsx"
    _stale_book(path)
    report = audit(path)
    by_cell = {m.cell: m for m in report.mismatches}
    assert {m.cell for m in report.mismatches if m.root} == {"Table!B4", "Checks!E1"}
    assert report.disagreements == 2
    headline = by_cell["Checks!B2"]
    assert (headline.cached, headline.recomputed, headline.root) == ("PASS", "FAIL", False)
    assert headline.sources == ["Table!B4"]
    assert by_cell["Checks!B4"].stale and by_cell["Checks!B4"].sources == ["Table!B4"]
    assert set(by_cell["Table!B4"].followers) == {"Checks!B2", "Checks!B4", "Checks!C2"}
    # 8 formula cells as the file stores them: B2:B5, B4, B2, C2, the array's anchor
    assert report.formula_cells == len(formula_cells_in_xml(path)) == 8
    assert (report.cells_agree, report.cells_disagree) == (3, 5)
    text = format_report(report)
    assert "shows 'PASS', would show 'FAIL', because of Table!B4" in text
    assert "2 disagreements at the source" in text


@pytest.mark.skipif(find_soffice() is None, reason="LibreOffice is not installed")
def test_recalculation_shows_what_the_report_says_it_would(tmp_path):
    """LibreOffice recalculating the file shows, in every follower, the value the report
    says it would show."""
    path = tmp_path / "stale.xlsx"
    _stale_book(path)
    report = audit(path)
    theirs = recalculated_values(path)
    followers = [m for m in report.mismatches if not m.root]
    assert len(followers) == 3
    for m in followers:
        sheet, ref = m.cell.split("!")
        assert theirs[sheet][ref] == m.recomputed, m.cell


def test_a_label_reading_a_stale_cell_is_listed_with_it():
    """phpspreadsheet__issue.2301.xlsx: K57's cached "H" is stale (AO56 is empty, so the
    formula gives "M"); AN56 picks its label from K57 and shows the "H" one. AN56 agrees
    with the stale K57, but a recalculation shows its "M" label: a follower of K57."""
    path = corpus("phpspreadsheet__issue.2301.xlsx")
    cells = {c.get("r"): c for _, c in formula_cells_in_xml(path)}
    label = cells["AN56"]
    m_label = re.search(r'K57="M","([^"]*)"', label.findtext(NS + "f")).group(1)
    report = audit(path)
    by_cell = {m.cell.split("!")[1]: m for m in report.mismatches}
    assert by_cell["K57"].root and by_cell["K57"].cached == cells["K57"].findtext(NS + "v")
    follower = by_cell["AN56"]
    assert not follower.root and follower.sources == ["'HS1-XYZ'!K57"]
    assert follower.cached == label.findtext(NS + "v") != m_label
    assert follower.recomputed == m_label
    assert report.disagreements == 1


# -- counts add up ---------------------------------------------------------------------

COUNTED = [  # arrays, cycles, data tables, volatile contracts, not checked, LibreOffice
    "formulas__circular.xlsx", "openxmlsdk__00D4EE78301DA16F3BF92631CA9B68E6.xlsx",
    "closedxml__DataTableFormula-Excel-Input.xlsx", "ironcalc__MMULT.xlsx",
    "ironcalc__openpyxl_example.xlsx", "sheetjs__LONumbers.xlsx", "ironcalc__invoice.xlsx",
    "ironcalc__weekly_timesheet.xlsx", "ironcalc__yearly_calendar.xlsx",
    "edr__Test_Encoding_Formula_Date_1520.xlsx", "closedxml__named-ranges-global.xlsx",
    "sheetjs__formula_stress_test.xlsx", "poi__stress002.xlsx", "phpspreadsheet__issue.2301.xlsx",
    "phpspreadsheet__CellMatcher.xlsx", "openxmlsdk__Spreadsheet.xlsx",
]


@pytest.mark.parametrize("name", COUNTED)
def test_formula_cells_are_agree_disagree_not_checked_or_by_contract(name):
    path = corpus(name)
    report = audit(path)
    in_file = len(formula_cells_in_xml(path))
    assert report.formula_cells == in_file
    assert (report.cells_agree + report.cells_disagree + report.cells_not_checked
            + len(report.by_contract)) == in_file
    assert report.cells_checked == report.cells_agree + report.cells_disagree + len(
        report.by_contract)
    listed = {m.cell for m in report.mismatches} | {c for m in report.mismatches for c in m.cells}
    assert not listed & set(report.not_checked)   # a cycle's cells: checked or not, not both
    assert not set(report.by_contract) & set(report.not_checked)
    assert report.disagreements == sum(1 for m in report.mismatches if m.root)
    assert report.warnings == {}
    data = report.to_json()
    assert (data["cells_agree"] + data["cells_disagree"] + data["cells_not_checked"]
            + data["cells_by_contract"]) == data["formula_cells"]


# -- nothing but the report ------------------------------------------------------------

def test_overflow_in_mmult_prints_no_warning():
    path = corpus("ironcalc__MMULT.xlsx")
    done = run_cli(str(path), "--json")
    assert done.returncode in (0, 1) and done.stderr == ""
    assert json.loads(done.stdout)["warnings"] == []


def test_a_warning_of_the_audit_is_counted_in_the_report_not_printed(tmp_path):
    """An error value the reader does not know (kept as text) is logged by the reader:
    counted in the report's ``warnings``, nothing on stderr."""
    path = tmp_path / "odd.xlsx"
    wb = xlsxwriter.Workbook(path)
    wb.add_worksheet("S").write_formula("A1", "=1+1", None, 2)
    wb.close()
    replace_sheet_xml(path, "xl/worksheets/sheet1.xml", lambda x: x.replace(
        "</sheetData>", '<row r="3"><c r="A3" t="e"><v>#WHAT?</v></c></row></sheetData>'))
    report = audit(path)
    assert any("#WHAT?" in k for k in report.warnings)
    done = run_cli(str(path))
    assert done.stderr == "" and "the audit warned" in done.stdout
