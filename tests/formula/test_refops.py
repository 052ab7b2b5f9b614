"""References of foreign workbooks, checked against LibreOffice: whole columns and rows,
3-D references, the intersection and union operators, array constants, tables and
structured references, sheet-scoped names and names defined by a formula.

One workbook of cases is written with openpyxl, recalculated by LibreOffice headless
(the independent engine), and audited: every cell must be recomputed and agree.
"""

from __future__ import annotations

import openpyxl
import pytest
from openpyxl.workbook.defined_name import DefinedName
from openpyxl.worksheet.formula import ArrayFormula
from openpyxl.worksheet.table import Table, TableStyleInfo

from workbook_gen import audit
from workbook_gen.engines.libreoffice import recalculate

CASES = {
    # whole columns and rows, bounded by the used range
    "B1": "=SUM(A:A)",
    "B2": "=SUM($A:$A)*2",
    "B3": "=MAX(Data!2:2)",
    "B4": "=SUM(Data!A:C)",
    # 3-D references over Data, Mid and Last
    "B5": "=SUM(Data:Last!A1)",
    "B6": "=SUM(Data:Last!A1:B2)",
    # intersection and union
    "B7": "=SUM(Data!A1:C3 Data!B2:C4)",
    "B8": "=SUM((Data!A1,Data!B2:B3,Data!C1))",
    "B9": "=Data!A1:C1 Data!B1:B3",
    # array constants
    "B10": "=SUM({1,2;3,4})",
    "B11": "=INDEX({10,20,30},2)",
    "B12": "=MAX({1,-5,3})+MIN({1;-5;3})",
    # tables and structured references (table Sales on sheet Tab)
    "B13": "=SUM(Sales[Amount])",
    "B14": "=MAX(Sales[Price])",
    "B15": "=MAX(Sales[[Price]:[Amount]])",
    # names: a workbook name defined by a formula, a sheet-scoped one, one seen from another sheet
    "B16": "=Twice",
    "B17": "=LocalName",
    "B18": "=Data!LocalName",
    # the newer error literals
    "B19": "=IFERROR(#N/A,7)",
    # arrays outside array formulas, implicit intersection across sheets
    "B20": "=SUMPRODUCT(Data!A1:A3*Data!B1:B3)",
    "B21": "=SUMPRODUCT((Data!A1:C1>1)*Data!A2:C2)",
    # an aggregate over a sheet-scoped name, in a book whose sheets have print titles
    # (names of their sheets too): the aggregates' local evaluation reads what it names
    "B22": "=SUM(LocalName)+SUM(Data!A1:A1)",
}
# array formulas: (range, formula)
ARRAYS = {
    "D1": ("D1:D3", "=Data!A1:A3*Data!C1:C3"),
    "E1": ("E1:G1", "=SIN(Data!A1:C1)+1"),
    "D5": ("D5", "=SUM(IF(Data!A1:C3>4,Data!A1:C3,0))"),
    "D6": ("D6:E7", "={1,2;3,4}*2"),
    "D8": ("D8:D10", "=Data!A1:A2"),   # larger than its value: #N/A below
    "D11": ("D11", "=MAX(ABS(Data!A1:B2-5))"),
}


@pytest.fixture(scope="module")
def saved(libreoffice, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("refs")
    book = openpyxl.Workbook()
    main = book.active
    main.title = "Main"
    data = book.create_sheet("Data")
    book.create_sheet("Mid")["A1"] = 100
    book.create_sheet("Last")["A1"] = 1000
    book["Mid"]["B2"] = 7
    tab = book.create_sheet("Tab")
    for r, row in enumerate([[1, 2, 3], [4, 5, 6], [7, 8, 9]], start=1):
        for c, v in enumerate(row, start=1):
            data.cell(r, c, v)
    for r, v in enumerate([0.5, 1.5, 2.5, 3.5], start=1):
        main.cell(r, 1, v)
    tab.append(["Item", "Price", "Amount"])
    for item, price, amount in [("a", 2.5, 3), ("b", 4.0, 1), ("c", 1.25, 8)]:
        tab.append([item, price, amount])
    table = Table(displayName="Sales", ref="A1:C4")
    table.tableStyleInfo = TableStyleInfo(name="TableStyleMedium9")
    tab.add_table(table)
    for row in range(2, 5):  # a row-wise structured reference in a table's own column
        tab.cell(row, 4, f"=Sales[[#This Row],[Price]]*Sales[[#This Row],[Amount]]")
    tab["D1"] = "Total"
    book.defined_names["Twice"] = DefinedName("Twice", attr_text="Data!$A$1*2+SUM(Data!$B:$B)")
    main.defined_names["LocalName"] = DefinedName("LocalName", attr_text="Data!$C$3")
    data.defined_names["LocalName"] = DefinedName("LocalName", attr_text="Data!$A$2")
    data.print_title_rows = "1:1"
    for ref, formula in CASES.items():
        main[ref] = formula
    for ref, (area, formula) in ARRAYS.items():
        main[ref] = ArrayFormula(area, formula)
    src = tmp / "refs.xlsx"
    book.save(src)
    return recalculate(src, tmp / "lo")


def test_libreoffice_computed_what_the_cases_mean(saved):
    """The cases are about what they say: spot-check LibreOffice's values by hand."""
    values = openpyxl.load_workbook(saved, data_only=True)["Main"]
    assert values["B1"].value == 8.0            # 0.5+1.5+2.5+3.5
    assert values["B5"].value == 1 + 100 + 1000
    assert values["B7"].value == 5 + 6 + 8 + 9
    assert values["B8"].value == 1 + 5 + 8 + 3
    assert values["B10"].value == 10
    assert values["B13"].value == 12
    assert values["B17"].value == 9 and values["B18"].value == 4
    assert values["B22"].value == 9 + 1
    assert values["B20"].value == 1 * 2 + 4 * 5 + 7 * 8
    assert [values[f"D{r}"].value for r in (1, 2, 3)] == [3, 24, 63]
    assert values["D5"].value == 5 + 6 + 7 + 8 + 9
    assert values["D10"].value == "#N/A"


def test_every_reference_case_is_recomputed_and_agrees(saved):
    report = audit(saved)
    assert report.not_checked == {}, report.not_checked
    assert report.ok, [(m.cell, m.formula, m.cached, m.recomputed) for m in report.mismatches]
    # each cell an array formula fills is compared; the file stores the formula once, and
    # it counts once among the formula cells checked
    filled = 3 + 3 + 1 + 4 + 3 + 1
    assert report.formula_cells == len(CASES) + 3 + len(ARRAYS)
    assert report.cells_checked == report.formula_cells
    assert sum(c.cells for c in report.columns) == len(CASES) + 3 + filled


def test_aggregate_over_a_sheet_scoped_name_among_print_titles(tmp_path):
    """The aggregates' local evaluation reads only the columns their formulas name, unless
    a formula uses a sheet-scoped name; print titles (names of their sheets too) must not
    hide one that is used. Cached values by hand: 9 + 1 and 1 + 2."""
    import xlsxwriter
    path = tmp_path / "local.xlsx"
    book = xlsxwriter.Workbook(str(path))
    main, data = book.add_worksheet("Main"), book.add_worksheet("Data")
    for r, row in enumerate([[1, 2, 3], [4, 5, 6], [7, 8, 9]]):
        data.write_row(r, 0, row)
    data.repeat_rows(0)  # Data!_xlnm.Print_Titles
    book.define_name("Main!LocalName", "=Data!$C$3")
    main.write_formula("A1", "=SUM(LocalName)+SUM(Data!A1:A1)", None, 10)
    main.write_formula("A2", "=SUM(Data!A1:B1)", None, 3)
    book.close()
    report = audit(path)
    assert report.ok and report.cells_checked == 2, report.mismatches


def test_a_defined_name_of_several_areas_is_their_union(tmp_path):
    """A defined name may join areas with a top-level comma (Excel writes the print titles
    `Table!$A:$A,Table!$1:$1` so, and any multi-area name): the union operator, not a
    syntax error.  SUM over it adds both areas; no finding."""
    import xlsxwriter
    from workbook_gen import audit
    path = tmp_path / "union.xlsx"
    book = xlsxwriter.Workbook(path)
    sheet = book.add_worksheet("Data")
    sheet.write_column(0, 0, [1.0, 2.0, 4.0])
    sheet.write_column(0, 2, [8.0, 16.0])
    book.define_name("Both", "=Data!$A$1:$A$3,Data!$C$1:$C$2")
    sheet.write_formula("E1", "=SUM(Both)", None, 31.0)
    sheet.write_formula("E2", "=SUM(Both)+1", None, 30.0)   # wrong on purpose
    sheet.repeat_rows(0)
    sheet.repeat_columns(0)
    book.close()
    report = audit(path)
    assert [m.cell for m in report.mismatches] == ["Data!E2"]
    assert not [f for f in report.findings if f.kind == "defined_name_syntax"]
