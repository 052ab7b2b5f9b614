"""batching/columnar.py: summary.parquet, read by pyarrow, holds what summary.csv holds
(read by Python's csv module) and summary.xlsx's Variants sheet (read by openpyxl): the
same columns in the same order, integers as int64, every number to the bit (csv keeps
repr's 17 digits), the texts; written in row groups as the rows arrive."""

from __future__ import annotations

import csv
import math

import openpyxl
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from workbook_gen import batch


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    out = tmp_path_factory.mktemp("columnar")
    batch("templates/slider_crank.toml", vary={"l_AB": "30:60:5", "e": [0, 5, 95]},
          out=str(out), summary_only=True, jobs=1)
    (folder,) = out.iterdir()
    return folder


def number(text: str) -> float | None:
    return None if text == "" else float(text)


def test_parquet_holds_the_csv_and_the_xlsx(folder):
    table = pq.read_table(folder / "summary.parquet")
    with open(folder / "summary.csv", newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    assert table.column_names == header
    assert table.num_rows == len(body) == 7 * 3
    sheet = openpyxl.load_workbook(folder / "summary.xlsx", read_only=True)["Variants"]
    xlsx = [list(r) for r in sheet.iter_rows(values_only=True)]
    assert list(xlsx[0][:len(header)]) == header
    for j, name in enumerate(header):
        column = table.column(name)
        values = column.to_pylist()
        if pa.types.is_integer(column.type):
            assert values == [int(r[j]) for r in body], name
        elif pa.types.is_floating(column.type):
            for i, (v, r) in enumerate(zip(values, body)):
                want = number(r[j])
                if want is None or math.isnan(want):
                    assert v is None or math.isnan(v), (name, i)
                else:
                    assert v == want, (name, i, v, r[j])   # to the bit
                    assert xlsx[i + 1][j] == v, (name, i)
        else:
            assert [v or "" for v in values] == [r[j] for r in body], name
    assert "variant" in header and table.column("variant").type == pa.int64()


def test_written_in_row_groups_with_the_csvs_units_in_names(folder):
    meta = pq.ParquetFile(folder / "summary.parquet").metadata
    assert meta.num_row_groups >= 1 and meta.num_rows == 21
    names = pq.read_schema(folder / "summary.parquet").names
    assert "l_AB [mm]" in names and "s_C_max [mm]" in names
