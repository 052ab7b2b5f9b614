"""The batch summary an engineer comparing designs reads first (docs/batch.md, summary.xlsx; issue
22 item 2): a random study's Statistics sheet against numpy and scipy over the summary.csv values,
LibreOffice recalculating it to the same numbers, our audit passing it; the Sensitivity chart; one
chart per varied parameter; variant numbers as numbers."""

from __future__ import annotations

import csv
import math
import re
import zipfile
from pathlib import Path

import numpy as np
import openpyxl
import pytest
from scipy import stats

from workbook_gen import audit, batch
from workbook_gen.engines.libreoffice import read_formula_values, recalculated_values_many

ROOT = Path(__file__).resolve().parents[2]
SEWING = str(ROOT / "templates" / "sewing_machine.toml")
# 120 samples: 112 ok, 7 partial (l_BC < l_AB: some rows cannot assemble), 1 refused
# (l_AB <= 0): the statistics must leave the last 8 out.
RANDOM = ["l_AB=normal:32:12", "l_BC=uniform:30:110"]
PARAMS = ["l_AB", "l_BC"]


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    out = tmp_path_factory.mktemp("stats")
    frame = batch(SEWING, vary=RANDOM, samples=120, seed=1, out=out, summary_only=True,
                  step=30.0, progress=False)
    folder = out / "sewing_machine-batch"
    statuses = [s.split(":")[0] for s in frame["status"]]
    assert (statuses.count("ok"), statuses.count("partial"), statuses.count("refused")) == (
        112, 7, 1)
    return folder


def _csv_columns(folder: Path) -> dict[str, list[str]]:
    """summary.csv's columns by name (the unit left off the header)."""
    with (folder / "summary.csv").open(newline="") as handle:
        rows = list(csv.reader(handle))
    return {head.split(" [")[0]: [r[i] for r in rows[1:]] for i, head in enumerate(rows[0])}


def _statistics(folder: Path) -> dict[str, dict[str, object]]:
    """{quantity: {header: cached value}} of the Statistics sheet's table."""
    sheet = openpyxl.load_workbook(folder / "summary.xlsx", data_only=True)["Statistics"]
    rows = list(sheet.iter_rows(values_only=True))
    top = next(i for i, r in enumerate(rows) if r[0] == "quantity")
    head = rows[top]
    table = {}
    for row in rows[top + 1:]:
        if not row[0]:
            break
        table[row[0]] = {h: v for h, v in zip(head, row) if h}
    return table


def test_statistics_are_numpys_over_the_ok_variants_of_summary_csv(study):
    columns = _csv_columns(study)
    ok = np.array([s == "ok" for s in columns["status"]])
    table = _statistics(study)
    x = np.array([[float(v) for v in columns[p]] for p in PARAMS]).T[ok]
    # every output's max and min and the spans, 15 x 2 + 3 (not the exact stroke, a text
    # where the rod is shorter than the crank)
    assert len(table) == 33 and {"y_C_max", "theta_5_min", "needle_stroke"} <= set(table)
    for name, got in table.items():
        y = np.array([float(v) if v else np.nan for v in columns[name]])[ok]
        assert got["unit"] == {"y_C_max": "mm", "theta_5_min": "deg",
                               "omega_5_max": "rad/s"}.get(name, got["unit"])
        assert got["n"] == 112
        expected = {"mean": np.mean(y), "standard deviation": stats.tstd(y), "min": y.min(),
                    "max": y.max(), "median": np.median(y),
                    "5th percentile": stats.scoreatpercentile(y, 5),
                    "95th percentile": stats.scoreatpercentile(y, 95)}
        for key, value in expected.items():
            assert got[key] == pytest.approx(value, rel=1e-12, abs=1e-12 * np.abs(y).max()), (
                name, key)
        # the SRC as least squares on standardised variables, not through correlations
        zx = (x - x.mean(axis=0)) / x.std(axis=0, ddof=1)
        zy = (y - y.mean()) / y.std(ddof=1)
        src, *_ = np.linalg.lstsq(zx, zy, rcond=None)
        r2 = 1 - np.sum((zy - zx @ src) ** 2) / np.sum(zy ** 2)
        for p, s in zip(PARAMS, src):
            assert got[f"SRC {p}"] == pytest.approx(s, abs=1e-9), (name, p)
            assert got[f"r {p}"] == pytest.approx(stats.pearsonr(x[:, PARAMS.index(p)], y)[0],
                                                  abs=1e-12)
        assert got["R^2"] == pytest.approx(r2, abs=1e-9)
    # the needle stroke is 2 l_AB: all of it the crank's, none the rod's
    stroke = table["needle_stroke"]
    assert stroke["SRC l_AB"] == pytest.approx(1.0) and abs(stroke["SRC l_BC"]) < 1e-9


def test_partial_and_refused_variants_are_left_out(study):
    """With them, the statistics would differ: the partial variants' extremes are over
    the rows that assemble."""
    columns = _csv_columns(study)
    y = np.array([float(v) if v else np.nan for v in columns["a_C_max"]])
    everything = y[np.isfinite(y)]
    assert len(everything) == 119
    assert _statistics(study)["a_C_max"]["mean"] != pytest.approx(np.mean(everything),
                                                                  rel=1e-6)


@pytest.fixture(scope="module")
def speed_study(tmp_path_factory):
    """One parameter, the crank's speed: the positions do not depend on it (their
    columns constant: no effect computed), the velocities are proportional to it."""
    out = tmp_path_factory.mktemp("omega")
    batch(SEWING, vary=["omega_1=normal:6.28:0.1"], samples=30, seed=2, out=out,
          summary_only=True, step=30.0, progress=False)
    return out / "sewing_machine-batch"


def test_libreoffice_recalculates_the_statistics_and_our_audit_passes(study, speed_study,
                                                                     libreoffice, tmp_path):
    paths = [study / "summary.xlsx", tmp_path / "speed.xlsx"]
    paths[1].write_bytes((speed_study / "summary.xlsx").read_bytes())  # stems must differ
    theirs = [values["Statistics"] for values in recalculated_values_many(paths)]
    # 8 statistics a row; 2 SRC, R^2 and 2 r a row, and the 2 x 2 correlations; the speed
    # study's 34 rows (the exact stroke a number throughout) and its effects on the 20
    # that vary (not the 10 position extremes, the 3 spans, the exact stroke)
    for path, lo, cells in zip(paths, theirs, (33 * 13 + 4, 34 * 8 + 20 * 3 + 1)):
        ours = read_formula_values(path)["Statistics"]
        assert len(ours) == cells and set(lo) == set(ours)
        for cell, value in ours.items():
            assert isinstance(value, float) and math.isfinite(value), cell
            assert lo[cell] == pytest.approx(value, rel=1e-12, abs=1e-12), (path.name, cell)
        assert audit(path).ok


def test_a_column_that_does_not_vary_gets_no_effect(speed_study):
    table = _statistics(speed_study)
    assert table["y_C_min"]["standard deviation"] == 0.0
    assert table["y_C_min"]["SRC omega_1"] == table["y_C_min"]["R^2"] == "constant"
    assert table["v_C_max"]["SRC omega_1"] == pytest.approx(1.0, abs=1e-12)  # v = omega x
    assert table["v_C_min"]["SRC omega_1"] == pytest.approx(-1.0, abs=1e-12)
    assert table["v_C_max"]["R^2"] == pytest.approx(1.0, abs=1e-12)


def test_the_sensitivity_chart_is_a_bar_chart_of_the_src_with_a_legend(study):
    with zipfile.ZipFile(study / "summary.xlsx") as z:
        book = z.read("xl/workbook.xml").decode()
        assert re.findall(r'<sheet name="([^"]+)"', book)[:4] == [
            "Variants", "Statistics", "Charts", "About"]
        charts = [z.read(n).decode() for n in z.namelist() if n.startswith("xl/charts/")]
    bars = [c for c in charts if "<c:barChart>" in c]
    assert len(bars) == 1
    bar = bars[0]
    assert bar.count("<c:ser>") == 2 and "<c:legend>" in bar and "Sensitivity" in bar
    assert "Statistics!$K$7:$K$39" in bar and "Statistics!$L$7:$L$39" in bar
    notes = [c.value for c in openpyxl.load_workbook(study / "summary.xlsx")["Statistics"]["A"]
             [:5]]
    assert any("standardised regression coefficient" in (n or "") for n in notes)


def test_one_chart_per_quantity_and_varied_parameter_markers_only(study):
    with zipfile.ZipFile(study / "summary.xlsx") as z:
        scatter = [z.read(n).decode() for n in sorted(z.namelist())
                   if n.startswith("xl/charts/") and "<c:scatterChart>" in z.read(n).decode()]
    assert len(scatter) == 18 * 2  # 15 outputs and 3 spans, against l_AB and against l_BC
    against = [re.search(r"<c:valAx>.*?<a:t>([^<]*)</a:t>", c, re.S).group(1) for c in scatter]
    assert against.count("l_AB [mm]") == against.count("l_BC [mm]") == 18
    series = [x for c in scatter for x in c.split("<c:ser>")[1:]]
    assert len(series) == 3 * 2 + 15 * 2 * 2  # samples: markers, no line through them
    assert all(x.split("<c:marker>")[0].endswith("<c:spPr><a:ln><a:noFill/></a:ln></c:spPr>")
               for x in series)


def test_variant_numbers_are_numbers_and_design_names_stay_text(study, tmp_path):
    sheet = openpyxl.load_workbook(study / "summary.xlsx", read_only=True)["Variants"]
    labels = [r[0] for r in sheet.iter_rows(min_row=2, values_only=True)]
    assert labels == list(range(1, 121))  # sorts 1, 2, ..., 10, not 1, 10, 100
    design = tmp_path / "d.csv"
    design.write_text("variant,l_AB\n007,30\n,31\nbaseline,32\n12,33\n")
    batch(SEWING, design=design, out=tmp_path, summary_only=True, step=30.0, progress=False)
    sheet = openpyxl.load_workbook(tmp_path / "sewing_machine-batch" / "summary.xlsx",
                                   read_only=True)["Variants"]
    assert [r[0] for r in sheet.iter_rows(min_row=2, values_only=True)] == [
        "007", 2, "baseline", 12]
    with (tmp_path / "sewing_machine-batch" / "summary.csv").open() as handle:
        assert [line.split(",")[0] for line in handle][1:] == ["007", "2", "baseline", "12"]


def test_a_grid_has_no_statistics_sheet(tmp_path):
    batch(SEWING, vary=["l_AB=30,32"], out=tmp_path, summary_only=True, step=30.0,
          progress=False)
    book = openpyxl.load_workbook(tmp_path / "sewing_machine-batch" / "summary.xlsx",
                                  read_only=True)
    assert book.sheetnames == ["Variants", "Charts", "About"]
