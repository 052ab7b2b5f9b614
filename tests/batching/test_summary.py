"""batching/summary.py: summary.csv, summary.xlsx and summary.parquet of a table of
hand-made rows, read back by Python's csv module, openpyxl and pyarrow: the headers
with units, each value (numbers to the bit, None as empty), the Variants sheet's frozen
header, autofilter, conditional formats and HYPERLINK file cells, the About sheet (a
long line cut at Excel's 32,767 characters a cell: support.microsoft.com, "Excel
specifications and limits"), blocks added out of order, and nothing left on abort."""

from __future__ import annotations

import csv
import zipfile
from pathlib import Path

import openpyxl
import pyarrow.parquet as pq
import pytest

from workbook_gen.batching.summary import SummaryWriter, cell_pieces, write_summaries
from workbook_gen.batching.summary_only import SummaryJob, summary_rows
from workbook_gen.batching.job import JobSpec
from workbook_gen.batching.table import Table
from workbook_gen.batching.variants import from_specs
from workbook_gen.pruning import select
from workbook_gen.scene import load_scene

LONG = "x" * 40_000


def _row(status, y_max, ratio, audit="", missing=0, file="f.xlsx"):
    return {"file": file, "status": status, "y_C_max": y_max, "time_ratio": ratio,
            "grashof_class": "Grashof crank-rocker", "audit": audit,
            "rows_flagged": None if missing is None else 0, "rows_not_assembled": missing}


ROWS = [_row("ok", 91.5, 1.25, file="four_bar-1.xlsx"),
        _row("partial", 80.1, "n/a: needs a crank-rocker", missing=3,
             file="four_bar-2.xlsx"),
        _row("refused: l_AB must be positive", None, None, missing=None, file=""),
        _row("ok", 0.1 + 0.2, 1.5, "fail", file="four_bar-4.xlsx")]


def _table():
    scene = load_scene("templates/four_bar.toml")
    design = from_specs(["l_O1A=30,40", "l_AB=100,120"], list(scene.parameters))
    table = Table(design, select(scene.template, scene.outputs),
                  dict(scene.parameters) | dict(scene.options))
    for v in design.variants:
        table.put(v, ROWS[v.index - 1])
    return table


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    folder = tmp_path_factory.mktemp("summary")
    table = _table()
    write_summaries(table, folder / "summary.csv", folder / "summary.xlsx",
                    [("command", "workbook-gen batch " + LONG), ("version", "1")])
    return folder, table


def test_csv(written):
    folder, table = written
    with open(folder / "summary.csv", newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    head, body = rows[0], rows[1:]
    assert head == table.headers and "l_O1A [mm]" in head and "y_C_max [mm]" in head
    col = {name: i for i, name in enumerate(table.columns)}
    assert [r[col["variant"]] for r in body] == ["1", "2", "3", "4"]
    assert [r[col["l_AB"]] for r in body] == ["100.0", "120.0", "100.0", "120.0"]
    assert [float(r[col["y_C_max"]]) if r[col["y_C_max"]] else None for r in body] == \
        [91.5, 80.1, None, 0.1 + 0.2]                                   # to the bit
    assert [r[col["time_ratio"]] for r in body][1] == "n/a: needs a crank-rocker"
    assert [r[col["rows_not_assembled"]] for r in body] == ["0", "3", "", "0"]
    assert [r[col["audit"]] for r in body] == ["", "", "", "fail"]


def test_xlsx(written):
    folder, table = written
    book = openpyxl.load_workbook(folder / "summary.xlsx")
    sheet = book["Variants"]
    assert [c.value for c in sheet[1]] == table.headers
    assert sheet.freeze_panes == "A2"
    last = openpyxl.utils.get_column_letter(len(table.columns))
    assert sheet.auto_filter.ref == f"A1:{last}5"
    rules = [r.formula[0] for cf in sheet.conditional_formatting for r in cf.rules]
    assert rules == ['LEFT($C2,7)="refused"', '$C2="partial"', f'${last}2="fail"']
    col = table.columns.index("file") + 1
    assert sheet.cell(2, col).value == '=HYPERLINK("four_bar-1.xlsx","four_bar-1.xlsx")'
    values = openpyxl.load_workbook(folder / "summary.xlsx", data_only=True)["Variants"]
    y = table.columns.index("y_C_max") + 1
    assert [values.cell(r, y).value for r in range(2, 6)] == [91.5, 80.1, None, 0.1 + 0.2]
    assert values.cell(2, col).value == "four_bar-1.xlsx"
    about = [row for row in book["About"].iter_rows(values_only=True)]
    assert about[0][0] == "command" and about[2][0] == "version"
    assert about[0][1] + about[1][1] == "workbook-gen batch " + LONG
    assert len(about[0][1]) == 32_767
    assert {"Variants", "Charts", "About"} <= set(book.sheetnames)
    with zipfile.ZipFile(folder / "summary.xlsx") as z:
        assert z.testzip() is None


def test_parquet(written):
    folder, table = written
    frame = pq.read_table(folder / "summary.parquet")
    assert frame.column_names == table.headers
    y = frame.column(table.headers[table.columns.index("y_C_max")]).to_pylist()
    assert y == [91.5, 80.1, None, 0.1 + 0.2]


def test_blocks_out_of_order_give_the_same_files(tmp_path):
    text = Path("templates/four_bar.toml").read_text()
    spec = JobSpec(text, "four_bar.toml", step=30.0, stem="four_bar")
    scene = load_scene("templates/four_bar.toml", step=30.0)
    design = from_specs(["l_O1A=30,35,40,45"], list(scene.parameters))
    job = SummaryJob(spec, ("l_O1A",))
    variants = list(design.variants)
    parts = [variants[:2], variants[2:]]
    outputs = {}
    for order in ("forward", "backward"):
        table = Table(design, select(scene.template, scene.outputs),
                      dict(scene.parameters) | dict(scene.options), keep=False)
        folder = tmp_path / order
        folder.mkdir()
        writer = SummaryWriter(table, folder / "summary.csv", folder / "summary.xlsx")
        for part in (parts if order == "forward" else parts[::-1]):
            data, block = summary_rows(job, part)
            table.put_block(part, data)
            writer.add(part[0].index, len(part), block, part, data)
        writer.finish([("command", "x")])
        outputs[order] = {p.name: p.read_bytes() for p in folder.iterdir()}
    assert outputs["forward"] == outputs["backward"]
    assert set(outputs["forward"]) == {"summary.csv", "summary.xlsx", "summary.parquet"}
    body = outputs["forward"]["summary.csv"].decode().splitlines()[1:]
    assert [line.split(",")[0] for line in body] == ["1", "2", "3", "4"]


def test_abort_leaves_nothing(tmp_path):
    writer = SummaryWriter(_table(), tmp_path / "summary.csv", tmp_path / "summary.xlsx")
    writer.abort()
    assert list(tmp_path.iterdir()) == []


def test_cell_pieces_count_utf16_units():
    assert [len(p) for p in cell_pieces("a" * 70_000)] == [32_767, 32_767, 4_466]
    # a character beyond the BMP takes two UTF-16 code units: each piece within the
    # limit in code units, none cut inside a character, the text kept whole
    text = "a" + "\U0001F600" * 3 + "b" * 9
    pieces = cell_pieces(text, limit=4)
    assert "".join(pieces) == text
    assert all(0 < len(p.encode("utf-16-le")) // 2 <= 4 for p in pieces)
    assert cell_pieces("") == [""]
