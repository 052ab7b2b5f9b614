"""batching/designfile.py: a design table is read as a spreadsheet wrote it: CSV with
``,`` or ``;`` (Excel in a decimal-comma locale writes ``;`` and ``32,5``), UTF-8 with or
without a byte-order mark or Windows-1252, and an xlsx file's first sheet as openpyxl
reads it; anything else is one SceneError naming the file. The files are written here by
Python's csv module and by openpyxl."""

from __future__ import annotations

import csv

import openpyxl
import pytest

from workbook_gen.batching.designfile import decimal_comma, design_rows, separator
from workbook_gen.errors import SceneError

ROWS = [["l_AB", "l_BC", "branch"], ["32.5", "100", "open"], ["30", "105.25", "crossed"]]


def write_csv(path, rows, delimiter=",", encoding="utf-8"):
    with open(path, "w", newline="", encoding=encoding) as f:
        csv.writer(f, delimiter=delimiter).writerows(rows)
    return path


@pytest.mark.parametrize("delimiter, encoding", [(",", "utf-8"), (";", "utf-8-sig"),
                                                 (",", "cp1252"), (";", "cp1252")])
def test_csv_as_written(tmp_path, delimiter, encoding):
    rows = [*ROWS, ["31", "99", "Größe – é"]]
    path = write_csv(tmp_path / "d.csv", rows, delimiter, encoding)
    got, comma = design_rows(path, "--design")
    assert got == rows and comma == (delimiter == ";")


def test_decimal_commas_in_a_semicolon_file(tmp_path):
    rows = [["l_AB", "e"], ["32,5", "-0,25"], ["1,5E-3", "7"]]
    path = write_csv(tmp_path / "de.csv", rows, ";")
    got, comma = design_rows(path, "--design")
    assert comma and [[decimal_comma(c) for c in r] for r in got[1:]] == \
        [["32.5", "-0.25"], ["1.5E-3", "7"]]
    assert float(decimal_comma("32,5")) == 32.5
    assert decimal_comma("1,000,000") == "1,000,000"     # not a decimal comma: as it is
    assert decimal_comma(3.5) == 3.5


def test_separator_of_a_single_column():
    assert separator("l_AB\n32,5\n33\n") == ";"             # a decimal comma: a ; file
    assert separator("l_AB\n32.5\n33\n") == ","
    assert separator("a;b,c\n") == ","                      # ties go to ,
    assert separator("a;b;c,d\n") == ";"


def test_xlsx_first_sheet_as_openpyxl_reads_it(tmp_path):
    book = openpyxl.Workbook()
    sheet = book.active
    for row in [["l_AB", "l_BC", "branch"], [32.5, 100, "open"], [30, 105.25, "crossed"]]:
        sheet.append(row)
    book.create_sheet("other").append(["ignored"])
    book.save(tmp_path / "d.xlsx")
    got, comma = design_rows(tmp_path / "d.xlsx", "--design")
    assert got == [["l_AB", "l_BC", "branch"], [32.5, 100, "open"], [30, 105.25, "crossed"]]
    assert comma is False


@pytest.mark.parametrize("name, data, words", [
    ("d.txt", b"a,b\n1,2\n", "expected a .csv or .xlsx"),
    ("d.xlsx", b"not a zip", "not a readable xlsx"),
    ("missing.csv", None, "cannot read"),
])
def test_refusals_name_the_file(tmp_path, name, data, words):
    path = tmp_path / name
    if data is not None:
        path.write_bytes(data)
    with pytest.raises(SceneError, match=words) as info:
        design_rows(path, f"--design {path.name}")
    assert path.name in str(info.value)
