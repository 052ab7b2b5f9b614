"""Structured references: every column-name spelling, special items, column spans, this
row, in names; filters left out by SUBTOTAL.

References: Microsoft's "Using structured references with Excel tables" (its examples of
the grammar, stage table below); Excel's cached values in ironcalc__tables.xlsx (tables
with columns named "the two ", "[Not me]", "#Shame", "Hi, 'This", totals rows, a table
without headers, filtered tables and sheets); a workbook of such names recalculated by
LibreOffice headless.
"""

from __future__ import annotations

from pathlib import Path

import openpyxl
import pytest
import xlsxwriter

from workbook_gen import audit
from workbook_gen.engines.libreoffice import recalculate
from workbook_gen.evaluator.book import _parse_spec

CORPUS = Path("/work/shared/corpus/xlsx")
TABLES = CORPUS / "ironcalc__tables.xlsx"

# spec -> (special items, column names): Microsoft's examples, and the escapes it lists
SPECS = [
    ("[Sales Amount]", set(), ["Sales Amount"]),
    ("[[#Totals],[Sales Amount]]", {"#totals"}, ["Sales Amount"]),
    ("[[#Headers],[Region]:[Commission Amount]]", {"#headers"}, ["Region", "Commission Amount"]),
    ("[[#Data],[#Totals],[Sales Amount]]", {"#data", "#totals"}, ["Sales Amount"]),
    ("[[#This Row], [Commission Amount]]", {"#this row"}, ["Commission Amount"]),
    ("[@Commission Amount]", {"#this row"}, ["Commission Amount"]),
    ("[@[Sales Amount]:[Commission Amount]]", {"#this row"},
     ["Sales Amount", "Commission Amount"]),
    ("[@]", {"#this row"}, []),
    ("[#All]", {"#all"}, []),
    ("[]", set(), []),
    ("['#OfItems]", set(), ["#OfItems"]),            # ' escapes # [ ] ' @
    ("[[the two ]]", set(), ["the two "]),           # spaces inside brackets are the name's
    ("['[Not me']]", set(), ["[Not me]"]),
    ("[Totals '[']^&*@'#$,,<>]", set(), ["Totals []^&*@#$,,<>"]),
    ("[[#This Row],[Hi, ''This]:['[Not me']]]", {"#this row"}, ["Hi, 'This", "[Not me]"]),
]


@pytest.mark.parametrize("spec, specials, columns", SPECS)
def test_spec_grammar(spec, specials, columns):
    assert _parse_spec(spec) == (specials, columns)


@pytest.mark.parametrize("spec", ["[[a]", "[[a]x]", "[[a]:[#Data]]"])
def test_malformed_spec_is_no_reference(spec):
    assert _parse_spec(spec) is None


def _cached(path, sheet, ref):
    return openpyxl.load_workbook(path, data_only=True)[sheet][ref].value


@pytest.fixture(scope="module")
def tables_report():
    return audit(TABLES)


def test_excel_tables_file_recomputes_every_structured_reference(tables_report):
    """Every formula cell of the Excel-saved file is recomputed and agrees with what Excel
    cached (SHEET of tables, names and sheet names among them)."""
    report = tables_report
    assert report.ok, [(m.cell, m.formula, m.cached, m.recomputed) for m in report.mismatches]
    assert report.not_checked == {}
    assert report.cells_checked == report.formula_cells == 212


@pytest.mark.parametrize("sheet, ref", [
    ("Hidden", "H5"),   # SUM(Table3[[#Totals],[the two ]])
    ("Hidden", "I5"),   # SUM(Table3[[#Totals],[the two ]:[last]])
    ("Hidden", "B8"),   # SUM(Table3[[the two ]])
    ("Hidden", "B7"),   # SUBTOTAL(109,B2:B6): the hidden row and the nested totals left out
    ("Escape", "D6"),   # SUBTOTAL(103,Table9['[Not me']])
    ("Escape", "E6"),   # SUM(Table9[Totals '[']^&*@'#$,,<>])
    ("filters", "B8"),  # SUBTOTAL(9,B3:B6) over rows a table's filter hid
    ("Functions Filters", "D54"),  # SUBTOTAL(3,Table16[[#All],[Units]])
])
def test_excel_cached_value_is_checked(tables_report, sheet, ref):
    report = tables_report
    name = f"'{sheet}'!{ref}" if " " in sheet else f"{sheet}!{ref}"
    assert name not in report.not_checked
    assert _cached(TABLES, sheet, ref) is not None
    assert all(m.cell != name for m in report.mismatches)


HEADERS = ["Item", " lead", "trail ", "[Not me]", "#Shame", "It's", "a@b"]
ROWS = [["a", 1, 10, 100, 1000, 2, 3], ["b", 2, 20, 200, 2000, 4, 5],
        ["c", 3, 30, 300, 3000, 6, 7]]
SUMS = {"M1": "=SUM(T[[ lead]])", "M2": "=SUM(T[trail ])", "M3": "=SUM(T['[Not me']])",
        "M4": "=SUM(T['#Shame])", "M5": "=SUM(T[It''s])", "M6": "=SUM(T[[ lead]:[trail ]])",
        "M7": "=SUM(T[[#Data],[#Totals],[trail ]])", "M8": "=SUM(T[a'@b])",
        "M9": "=SUM(T)"}  # a bare table name: its data


ARRAYS = {"O1": ("O1", "{=SUM(T[ lead]*T[trail ])}"),
          "P2": ("P2:P4", "{=T['[Not me']]+T[[ lead]]}")}


@pytest.fixture(scope="module")
def recalculated(libreoffice, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("structured")
    wb = xlsxwriter.Workbook(str(tmp / "t.xlsx"))
    ws = wb.add_worksheet("Data")
    ws.add_table("A1:G5", {"name": "T", "columns": [{"header": h} for h in HEADERS],
                           "data": ROWS, "total_row": True})
    wb.define_name("RowLead", "=T[[#This Row],[ lead]]*2")  # this row, in a name
    for r in range(2, 5):
        ws.write_formula(f"I{r}", "=T[[#This Row],[ lead]]+T[[#This Row],[trail ]]")
        ws.write_formula(f"J{r}", "=RowLead")
    for ref, formula in SUMS.items():
        ws.write_formula(ref, formula)
    for ref, (area, formula) in ARRAYS.items():  # structured references in array formulas
        ws.write_array_formula(area, formula)
    wb.close()
    return recalculate(tmp / "t.xlsx", tmp / "lo")


def test_libreoffice_computed_what_the_cases_mean(recalculated):
    ws = openpyxl.load_workbook(recalculated, data_only=True)["Data"]
    assert [ws[f"I{r}"].value for r in range(2, 5)] == [11, 22, 33]
    assert [ws[f"J{r}"].value for r in range(2, 5)] == [2, 4, 6]
    assert [ws[ref].value for ref in SUMS] == [6, 60, 600, 6000, 12, 66, 60, 15, 6693]
    assert ws["O1"].value == 1 * 10 + 2 * 20 + 3 * 30
    assert [ws[f"P{r}"].value for r in range(2, 5)] == [101, 202, 303]


def test_column_spellings_and_this_row_in_names_agree_with_libreoffice(recalculated):
    report = audit(recalculated)
    assert report.not_checked == {}
    assert report.ok, [(m.cell, m.formula, m.cached, m.recomputed) for m in report.mismatches]
    assert report.cells_checked == 6 + len(SUMS) + len(ARRAYS)  # (an array counts once)
