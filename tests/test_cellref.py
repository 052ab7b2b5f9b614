"""workbook_gen.cellref, the one place of A1 conversions, against openpyxl's utilities."""

from __future__ import annotations

import pytest
from openpyxl.utils.cell import (column_index_from_string, coordinate_from_string,
                                 get_column_letter, quote_sheetname)

from workbook_gen.cellref import a1, cell_name, column_letters, column_number, row_col

COLUMNS = [1, 2, 25, 26, 27, 52, 53, 701, 702, 703, 18278, 16383, 16384]


@pytest.mark.parametrize("col", COLUMNS)
def test_column_letters_and_numbers(col):
    letters = get_column_letter(col)
    assert column_letters(col) == letters
    assert column_number(letters) == column_index_from_string(letters) == col
    assert column_number(letters.lower()) == col


@pytest.mark.parametrize("row", [1, 9, 10, 1048576])
@pytest.mark.parametrize("col", [1, 27, 16384])
def test_cells(row, col):
    text = a1(row, col)
    assert coordinate_from_string(text) == (get_column_letter(col), row)
    assert row_col(text) == row_col(f"${column_letters(col)}${row}") == (row, col)


@pytest.mark.parametrize("sheet", ["Table", "My sheet", "it's", "Sheet_2", "Données"])
def test_cell_name_quotes_the_sheet_as_excel_does(sheet):
    name = cell_name((sheet, 3, 2))
    assert name.endswith("!B3")
    # openpyxl quotes every name that is not plain word characters
    assert name[:-3] == (sheet if sheet.replace("_", "").isalnum() else quote_sheetname(sheet))


@pytest.mark.parametrize("text", ["", "B", "3", "B3C", "AAAA1", "B-3"])
def test_row_col_refuses_what_is_not_a_cell(text):
    with pytest.raises(ValueError):
        row_col(text)


def test_every_column_as_xlsxwriters_utilities_name_it():
    """The writers took XlsxWriter's utilities (0-based) before cellref (1-based): every
    column of a sheet, relative and absolute, and cells at the first, a middle and the
    last row, give the same text."""
    from xlsxwriter.utility import xl_cell_to_rowcol, xl_col_to_name, xl_rowcol_to_cell

    for col in range(16384):
        letters = xl_col_to_name(col)
        assert column_letters(col + 1) == letters, col
        assert column_letters(col + 1, True) == xl_col_to_name(col, True) == "$" + letters
        assert column_number(letters) == col + 1
        for row in (0, 99, 1048575):
            assert a1(row + 1, col + 1) == xl_rowcol_to_cell(row, col), (row, col)
            assert a1(row + 1, col + 1, True) == xl_rowcol_to_cell(row, col, True, True)
            assert row_col(a1(row + 1, col + 1, True)) == tuple(
                x + 1 for x in xl_cell_to_rowcol(xl_rowcol_to_cell(row, col)))
