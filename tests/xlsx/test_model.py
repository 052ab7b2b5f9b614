"""xlsx/model.py: what the reader returns. A workbook written by openpyxl (constants of
each kind, formulas, a shared formula written as Excel writes one, sheet-scoped names) is
read by read_workbook and every cell compared with openpyxl reading the same file back;
the plain cells the scanner keeps as columns (chunks) read the same through every view
(cells, row, row_cells, column, parts) as Cell objects made one by one."""

from __future__ import annotations

import zipfile

import openpyxl
import pytest

from workbook_gen.xlerror import ExcelError
from workbook_gen.xlsx import read_workbook
from workbook_gen.xlsx.model import Cell, Sheet, Workbook


@pytest.fixture(scope="module")
def book_path(tmp_path_factory):
    path = tmp_path_factory.mktemp("model") / "book.xlsx"
    wb = openpyxl.Workbook()
    ws = wb.active
    ws.title = "Data"
    ws["A1"], ws["B1"], ws["C1"], ws["D1"] = 1.5, "text", True, "=A1*2"
    ws["A2"], ws["B2"] = -3, "=SUM(A1:A2)"
    ws["E5"] = "#N/A"
    other = wb.create_sheet("Other Sheet")
    other["A1"] = "=Data!A1+1"
    wb.defined_names["Rate"] = openpyxl.workbook.defined_name.DefinedName(
        "Rate", attr_text="Data!$A$1")
    other.defined_names["Local"] = openpyxl.workbook.defined_name.DefinedName(
        "Local", attr_text="'Other Sheet'!$A$1")
    wb.save(path)
    # a shared formula as Excel writes one: B3:B5 =A3*10, the master in B3
    with zipfile.ZipFile(path) as z:
        parts = {n: z.read(n) for n in z.namelist()}
    sheet = parts["xl/worksheets/sheet1.xml"].decode()
    rows = ('<row r="3"><c r="B3"><f t="shared" ref="B3:B5" si="0">A3*10</f><v>0</v></c></row>'
            '<row r="4"><c r="B4"><f t="shared" si="0"/><v>0</v></c></row>'
            '<row r="5"><c r="B5"><f t="shared" si="0"/><v>0</v></c>'
            '<c r="E5" t="e"><v>#N/A</v></c></row>')
    start = sheet.index('<row r="5"')
    end = sheet.index("</row>", start) + len("</row>")
    sheet = sheet[:start] + rows + sheet[end:]
    parts["xl/worksheets/sheet1.xml"] = sheet.encode()
    with zipfile.ZipFile(path, "w") as z:
        for name, data in parts.items():
            z.writestr(name, data)
    return path


def _openpyxl_cells(path):
    out = {}
    for ws in openpyxl.load_workbook(path).worksheets:
        for row in ws.iter_rows():
            for c in row:
                if c.value is not None:
                    out[(ws.title, c.coordinate)] = c.value
    return out


def test_every_cell_as_openpyxl_reads_it(book_path):
    book = read_workbook(book_path)
    theirs = _openpyxl_cells(book_path)
    ours = {}
    for sheet in book.sheets:
        for ref, cell in sheet.cells.items():
            if cell.formula is not None:
                ours[(sheet.name, ref)] = "=" + cell.formula
            elif cell.formula_type == "shared":
                ours[(sheet.name, ref)] = "="  # a follower: openpyxl shifts the master's text
            else:
                ours[(sheet.name, ref)] = cell.value
    for key, value in theirs.items():
        mine = ours[key]
        if isinstance(value, str) and value.startswith("=") and mine == "=":
            continue
        if isinstance(mine, ExcelError):
            mine = mine.value
        assert mine == value or (isinstance(value, (int, float)) and float(value) == mine), key
    assert set(ours) == set(theirs)


def test_shared_formulas_and_names(book_path):
    book = read_workbook(book_path)
    data = book["data"]  # sheets are found regardless of case, as in Excel
    assert data.formula_source("B4") == ("A3*10", "B3")
    assert data.formula_source(data["$b$3"]) == ("A3*10", "B3")
    assert data.formula_source("A1") is None
    assert data["B4"].has_formula and not data["B4"].is_array
    assert book.resolve_name("rate") == "Data!$A$1"
    assert book.resolve_name("LOCAL", "Other Sheet") == "'Other Sheet'!$A$1"
    assert book.resolve_name("Local") is None  # not seen from the workbook
    assert book.sheet_names == ["Data", "Other Sheet"]
    with pytest.raises(KeyError):
        book.sheet("missing")
    assert (data.max_row, data.max_col) == (5, 5)
    assert [c.ref for c in data.formula_cells()] == ["D1", "B2", "B3", "B4", "B5"]
    assert book.n_cells == sum(len(s.cells) for s in book.sheets) == 11


def _chunked():
    sheet = Sheet("S", 0)
    sheet.cells = {"B1": Cell("B1", 1, 2, "x")}
    rows, cols, values, formulas = sheet.chunk()
    for r, c, v, f in [(1, 1, 1.0, None), (2, 3, 2.0, "A1*2"), (2, 1, True, None),
                       (3, 2, None, "B1&1")]:
        rows.append(r), cols.append(c), values.append(v), formulas.append(f)
    return sheet


def test_chunks_read_as_cells():
    lazy = _chunked()
    assert [c.ref for c in lazy.row_cells(2)] == ["A2", "C2"]
    assert lazy.max_row == 3 and lazy.max_col == 3
    cells, chunks = lazy.parts()
    assert [c.ref for c in cells] == ["B1"] and len(chunks[0][0]) == 4
    eager = _chunked()
    made = eager.cells  # every chunk made Cell objects
    assert eager.chunks == []
    assert list(made) == ["B1", "A1", "C2", "A2", "B3"]
    assert made["C2"] == Cell("C2", 2, 3, 2.0, "A1*2", "normal")
    assert made["A2"].formula_type is None and made["B3"].has_formula
    assert [c.ref for c in eager.row(2)] == ["A2", "C2"]
    assert [c.ref for c in eager.column(1)] == ["A1", "A2"]
    assert [(c.ref, c.value) for c in lazy.row_cells(2)] == \
        [(c.ref, c.value) for c in eager.row(2)]


def test_a_repeated_ref_keeps_the_last_as_cells_does():
    sheet = Sheet("S", 0)
    rows, cols, values, formulas = sheet.chunk()
    for r, c, v in [(1, 1, 1.0), (1, 1, 2.0), (2, 1, 3.0)]:
        rows.append(r), cols.append(c), values.append(v), formulas.append(None)
    cells, chunks = sheet.parts()
    assert chunks == [] and [(c.ref, c.value) for c in cells] == [("A1", 2.0), ("A2", 3.0)]


def test_an_empty_workbook():
    book = Workbook("x.xlsx", [], {}, [], [])
    assert book.n_cells == 0 and book.sheet_names == [] and book.resolve_name("a") is None
