"""The Summary's extremes over the ok rows, and figures that hold only under a condition
(issue 21 items 2 and 3, docs/workbook.md, Summary).

One flagged row (a dead centre, a change point, a tangent rod) never turns a Summary cell
into an error value while one row is ok; the extremes and their inputs are those of the
ok rows, read here from the Table with pandas (the status column), and LibreOffice
recalculating the file agrees; the Summary says how many rows it counted.  A figure
whose condition fails shows "n/a: needs ...", in the workbook and in the batch summary.
"""

from __future__ import annotations

import math
from pathlib import Path

import openpyxl
import pandas as pd
import pytest

from workbook_gen import audit, batch, load_scene, write_workbook
from workbook_gen.engines.libreoffice import recalculated_values
from tests.engines.test_libreoffice_recalc import compare_with_libreoffice

ROOT = Path(__file__).resolve().parents[2]
# (template, overrides): each with at least one flagged row among ok rows
FLAGGED = [
    ("sewing_machine", {"l_BC": 32.0}),     # rod = crank: dead centres
    ("four_bar", {"l_O2B": 60.0}),          # change point
    ("slider_crank", {"l_BC": 50.0}),       # l_BC = l_AB + e: the rod tangent at one angle
]


def _summary(path) -> dict[str, tuple]:
    sheet = openpyxl.load_workbook(path, data_only=True)["Summary"]
    return {row[0]: row[1:] for row in sheet.iter_rows(values_only=True) if row[0]}


@pytest.fixture(scope="module")
def flagged_books(tmp_path_factory):
    out = tmp_path_factory.mktemp("flagged")
    return [write_workbook(load_scene(ROOT / "templates" / f"{t}.toml", overrides=o), out)
            for t, o in FLAGGED]


@pytest.mark.parametrize("index", range(len(FLAGGED)))
def test_extremes_are_the_ok_rows_and_never_an_error(flagged_books, index):
    path = flagged_books[index]
    table = pd.read_excel(path, sheet_name="Table")
    ok = table["status"] == "ok"
    assert 0 < ok.sum() < len(table), table["status"].value_counts()
    summary = _summary(path)
    inputs = table.columns[0]
    checked = 0
    for header in table.columns[1:-1]:
        name = header.split(" [")[0]
        if name not in summary or summary[name][0] in (None, "unit"):
            continue
        unit, hi, at_hi, lo, at_lo = summary[name][:5]
        values = pd.to_numeric(table.loc[ok, header], errors="coerce").dropna()
        assert isinstance(hi, float) and isinstance(lo, float), (name, hi, lo)
        assert hi == values.max() and lo == values.min(), name
        if at_hi != "tie":
            assert at_hi == table.loc[values.idxmax(), inputs], name
            assert at_lo == table.loc[values.idxmin(), inputs], name
        checked += 1
    assert checked >= 5
    assert summary["rows in the extremes"][1] == ok.sum()
    report = audit(path)
    assert report.mismatches == [] and report.not_checked == {}


@pytest.mark.parametrize("index", range(len(FLAGGED)))
def test_libreoffice_agrees_with_the_summary(flagged_books, index):
    cells, worst = compare_with_libreoffice(flagged_books[index])
    assert cells > 100 and worst <= 1e-12


def test_a_figure_whose_condition_fails_is_not_applicable(tmp_path):
    tangent = write_workbook(load_scene(ROOT / "templates" / "slider_crank.toml",
                                        overrides={"l_BC": 50.0}), tmp_path)
    figures = _summary(tangent)
    for label in ("stroke, exact", "time ratio"):
        assert figures[label][1] == "n/a: needs l_BC > l_AB + |e|", figures[label]
    theirs = recalculated_values(tangent)["Summary"]
    assert "n/a: needs l_BC > l_AB + |e|" in theirs.values()
    # where it holds: the exact stroke between the dead centres, computed here
    l_AB, l_BC, e = 40.0, 80.0, 10.0
    folder = tmp_path / "long"
    long_rod = write_workbook(load_scene(ROOT / "templates" / "slider_crank.toml",
                                         overrides={"l_BC": l_BC}), folder)
    stroke = math.sqrt((l_BC + l_AB) ** 2 - e ** 2) - math.sqrt((l_BC - l_AB) ** 2 - e ** 2)
    assert math.isclose(_summary(long_rod)["stroke, exact"][1], stroke, rel_tol=1e-14)


def test_the_batch_summary_follows_the_same_rules(tmp_path):
    frame = batch(str(ROOT / "templates" / "slider_crank.toml"), vary=["l_BC=40:60:10"],
                  out=tmp_path, progress=False, step=30.0)
    by_rod = frame.set_index("l_BC")
    assert by_rod.loc[50.0, "stroke_exact"] == "n/a: needs l_BC > l_AB + |e|"
    assert isinstance(by_rod.loc[60.0, "stroke_exact"], float)
    for rod, row in by_rod.iterrows():
        if row["file"]:
            book = Path(tmp_path) / "slider_crank-batch" / row["file"]
            summary = _summary(book)
            assert row["v_C_max"] == summary["v_C"][1], rod


def test_batch_summary_counts_the_flagged_rows_like_the_workbook(tmp_path):
    """docs/batch.md, summary.csv: the batch summary follows the Summary's rules and says how many
    rows its extremes left out: rows_flagged (not converged, a dead centre...) beside
    rows_not_assembled, equal to the workbook's own count of flagged rows."""
    import openpyxl
    from workbook_gen.batching import batch
    frame = batch("templates/five_bar.toml", vary={"iterations": [2, 8]},
                  sets={"method": "newton"}, out=str(tmp_path))
    folder = frame.attrs["folder"]
    for _, row in frame.iterrows():
        table = openpyxl.load_workbook(f"{folder}/{row['file']}", data_only=True)["Table"]
        status = [r[-1] for r in table.iter_rows(min_row=2, values_only=True)]
        flagged = sum(s not in ("ok", "cannot assemble") for s in status)
        assert row["rows_flagged"] == flagged
    assert list(frame["rows_flagged"]) == [37, 0]   # 2 Newton steps converge nowhere
