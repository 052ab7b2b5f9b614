"""workbook-gen batch (docs/batch.md): variants, one workbook per variant that is byte for byte
what `generate` writes, the summary against closed-form references and against the
workbooks themselves, failure isolation, determinism, resuming, --summary-only."""

from __future__ import annotations

import csv
import re
import zipfile
from pathlib import Path

import numpy as np
import openpyxl
import pytest

from workbook_gen import batch, cli
from workbook_gen.batching import summary_only
from workbook_gen.batching.variants import from_design, from_specs
from workbook_gen.errors import SceneError

ROOT = Path(__file__).resolve().parents[2]
SEWING = str(ROOT / "templates" / "sewing_machine.toml")
FOUR_BAR = str(ROOT / "templates" / "four_bar.toml")
PARAMS = ["l_AB", "l_BC", "l_BE", "beta_E", "x_F", "y_F", "l_FG", "omega_1"]
# Two lengths, one refused (non-positive), one partial (rod shorter than the crank).
VARY = ["l_BC=20,95,105", "l_AB=-1,30,32"]


def _read_csv(path: Path) -> list[dict[str, str]]:
    """The rows keyed by column name, the header's unit left off (``y_C_max [mm]``)."""
    with path.open(newline="") as handle:
        return [{k.split(" [")[0]: v for k, v in row.items()} for row in csv.DictReader(handle)]


def _files(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())
            if p.suffix in (".xlsx", ".csv")}


@pytest.fixture(scope="module")
def sewing_batch(tmp_path_factory):
    """The 3 x 3 sewing-machine batch at 30 deg, in this process (jobs=1)."""
    out = tmp_path_factory.mktemp("batch1")
    frame = batch(SEWING, vary=VARY, out=out, jobs=1, step=30.0, progress=False)
    return frame, out / "sewing_machine-batch"


# -- 1. variants --------------------------------------------------------------------------

def test_grid_keeps_a_stop_on_the_grid_and_no_accumulated_rounding():
    design = from_specs(["l_BC=95:105:0.5"], PARAMS)
    values = [dict(v.values)["l_BC"] for v in design.variants]
    assert len(values) == 21 and values[-1] == 105.0
    assert values == [95 + i / 2 for i in range(21)]  # exact halves: no 95.50000000000001
    short = [dict(v.values)["l_BC"] for v in from_specs(["l_BC=0:1:0.3"], PARAMS).variants]
    assert short == [0.0, 0.3, 0.6, 0.9]


def test_several_vary_make_the_full_factorial_last_fastest():
    design = from_specs(["l_BC=95:105:5", "l_AB=30,32"], PARAMS)
    assert [v.values for v in design.variants] == [
        (("l_BC", a), ("l_AB", b)) for a in (95.0, 100.0, 105.0) for b in (30.0, 32.0)]
    assert [v.index for v in design.variants] == list(range(1, 7))


def test_random_variants_are_numpy_default_rng_draws_in_spec_order():
    design = from_specs(["l_AB=normal:32:0.05", "l_BC=uniform:99:101"], PARAMS,
                        samples=5, seed=7)
    rng = np.random.default_rng(7)
    expected_ab, expected_bc = rng.normal(32, 0.05, 5), rng.uniform(99, 101, 5)
    assert [dict(v.values)["l_AB"] for v in design.variants] == expected_ab.tolist()
    assert [dict(v.values)["l_BC"] for v in design.variants] == expected_bc.tolist()


def test_design_files_csv_and_xlsx_with_names_and_empty_cells(tmp_path):
    rows = [["variant", "l_AB", "l_BC"], ["base", "", ""], ["long rod", "32", "110"],
            ["short crank", "28.5", ""]]
    path = tmp_path / "design.csv"
    path.write_text("\n".join(",".join(r) for r in rows) + "\n")
    book = openpyxl.Workbook()
    for r in rows:
        book.active.append([float(c) if c.replace(".", "").isdigit() else (c or None)
                            for c in r])
    book.save(tmp_path / "design.xlsx")
    for name in ("design.csv", "design.xlsx"):
        design = from_design(tmp_path / name, PARAMS)
        assert design.names == ("l_AB", "l_BC")
        assert [v.label for v in design.variants] == ["base", "long rod", "short crank"]
        assert [v.values for v in design.variants] == [
            (), (("l_AB", 32.0), ("l_BC", 110.0)), (("l_AB", 28.5),)]


@pytest.mark.parametrize("args, message", [
    (["--vary", "l_XY=1,2"], "not a parameter"),
    (["--vary", "l_BC=95:105:0"], "STEP must not be 0"),
    (["--vary", "l_BC=95:abc:1"], "is not a number"),
    (["--vary", "l_BC=normal:100:1"], "needs --samples"),
    (["--vary", "l_BC=normal:100:1", "--vary", "l_AB=30,32", "--samples", "3"],
     "cannot be mixed"),
    (["--vary", "l_BC=95:105:5", "--set", "l_BC=3"], "not both"),
    (["--vary", "l_BC=105:95:5"], "never reaches"),
    (["--design", "missing.csv"], "cannot read"),
    (["--set", "l_BC=-3", "--vary", "l_AB=30,32"], "must be > 0"),
])
def test_a_bad_spec_exits_2_and_writes_nothing(tmp_path, capsys, args, message):
    out = tmp_path / "out"
    code = cli.main(["batch", SEWING, "--out", str(out), "--quiet", "--jobs", "1"] + args)
    assert code == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1
    assert not out.exists()


# -- 2. one workbook per variant, the bytes of generate -----------------------------------

def test_each_workbook_is_byte_for_byte_what_generate_writes(sewing_batch, capsys):
    frame, folder = sewing_batch
    # generate --name <stem> --out <the batch folder> (the About sheet names the file's
    # path), with --set in the --vary order, over the batch's own file.
    for variant, (l_bc, l_ab) in ((2, (20.0, 30.0)), (9, (105.0, 32.0))):
        name = f"sewing_machine-{variant:04d}.xlsx"
        made = (folder / name).read_bytes()
        (folder / name).unlink()
        assert cli.main(["generate", SEWING, "--out", str(folder), "--name", name[:-5],
                         "--step", "30", "--set", f"l_BC={l_bc!r}", "--set",
                         f"l_AB={l_ab!r}"]) == 0
        assert (folder / name).read_bytes() == made
    capsys.readouterr()


# -- 3. the summary --------------------------------------------------------------------

def test_needle_extremes_match_the_closed_form_for_every_variant(sewing_batch):
    frame, folder = sewing_batch
    rows = _read_csv(folder / "summary.csv")
    assert [r["variant"] for r in rows] == [str(i) for i in range(1, 10)]
    for row in rows:
        l_bc, l_ab = float(row["l_BC"]), float(row["l_AB"])
        if row["status"] != "ok":
            continue
        # Needle bar on the line through A below B: C highest at 90 deg, lowest at 270.
        assert float(row["y_C_max"]) == pytest.approx(l_ab - l_bc, abs=1e-12)
        assert float(row["y_C_max_at"]) == 90.0
        assert float(row["y_C_min"]) == pytest.approx(-l_ab - l_bc, abs=1e-12)
        assert float(row["y_C_min_at"]) == 270.0
        assert float(row["needle_stroke"]) == pytest.approx(2 * l_ab, abs=1e-12)
        assert float(row["needle_stroke_exact"]) == 2 * l_ab


def test_summary_extremes_are_those_of_the_workbooks_tables(sewing_batch):
    frame, folder = sewing_batch
    rows = {r["file"]: r for r in _read_csv(folder / "summary.csv") if r["file"]}
    for name, row in rows.items():
        sheet = openpyxl.load_workbook(folder / name, read_only=True, data_only=True)["Table"]
        table = list(sheet.iter_rows(values_only=True))
        heads = [h.split(" [")[0] for h in table[0]]
        for q in ("y_C", "theta_5", "omega_5", "a_FE"):
            column = [(r[heads.index(q)], r[0]) for r in table[1:]]
            numbers = [(v, x) for v, x in column if isinstance(v, float)]
            lo = min(numbers, key=lambda p: p[0])
            hi = max(numbers, key=lambda p: p[0])
            assert float(row[f"{q}_min"]) == lo[0] and float(row[f"{q}_min_at"]) == lo[1]
            assert float(row[f"{q}_max"]) == hi[0] and float(row[f"{q}_max_at"]) == hi[1]
        not_assembled = sum(r[-1] == "cannot assemble" for r in table[1:])
        assert int(row["rows_not_assembled"]) == not_assembled


def test_summary_columns_follow_the_spec(sewing_batch):
    frame, folder = sewing_batch
    head = next(csv.reader((folder / "summary.csv").open()))
    # the units from the template: the parameters' and outputs', the input's for _at
    assert head[:5] == ["variant", "file", "status", "l_BC [mm]", "l_AB [mm]"]
    assert head[5:9] == ["y_C_min [mm]", "y_C_min_at [deg]", "y_C_max [mm]",
                         "y_C_max_at [deg]"]
    assert "theta_5_max [deg]" in head and "omega_5_max [rad/s]" in head
    assert head[-2:] == ["rows_not_assembled", "audit"]
    assert {"needle_stroke [mm]", "lever_swing [deg]", "needle_stroke_exact [mm]"} <= set(head)
    assert [h.split(" [")[0] for h in head] == list(frame.columns) and len(frame) == 9
    assert frame.attrs["units"]["y_C_max"] == "mm"
    sheet = openpyxl.load_workbook(folder / "summary.xlsx", read_only=True)["Variants"]
    assert next(sheet.iter_rows(max_row=1, values_only=True)) == tuple(head)


def test_summary_xlsx_sheets_links_filter_and_native_charts(sewing_batch):
    frame, folder = sewing_batch
    book = openpyxl.load_workbook(folder / "summary.xlsx")
    assert book.sheetnames[:3] == ["Variants", "Charts", "About"]
    sheet = book["Variants"]
    assert sheet.freeze_panes == "A2"
    assert sheet.auto_filter.ref.startswith("A1:")
    assert sheet["B3"].value == ('=HYPERLINK("sewing_machine-0002.xlsx",'
                                 '"sewing_machine-0002.xlsx")')
    assert sheet["B2"].value is None and sheet["C2"].value.startswith("refused:")
    rules = [r.formula[0] for rng in sheet.conditional_formatting for r in rng.rules]
    assert any("refused" in f for f in rules) and any("partial" in f for f in rules)
    with zipfile.ZipFile(folder / "summary.xlsx") as z:
        charts = [n for n in z.namelist() if n.startswith("xl/charts/chart")]
        # 15 outputs and 3 spans, against each of the two varied grid parameters: one
        # series per l_AB value against l_BC, one per l_BC value against l_AB.
        assert len(charts) == 18 * 2
        stroke = z.read("xl/charts/chart1.xml").decode()  # the needle stroke, a span
        assert "<c:scatterChart>" in stroke and stroke.count("<c:ser>") == 3
        assert "l_AB = 30" in stroke and "ChartData" in stroke
        stroke_ab = z.read("xl/charts/chart2.xml").decode()  # against l_AB, per l_BC
        assert stroke_ab.count("<c:ser>") == 3 and "l_BC = 95" in stroke_ab
        assert "Variants!$E$2:$E$4" in stroke_ab and "l_AB [mm]" in stroke_ab
        needle = z.read("xl/charts/chart7.xml").decode()  # y_C: max and min per l_AB
        assert needle.count("<c:ser>") == 2 * 3 and "y_C [mm]: max and min" in needle
        assert "<c:legend>" in needle
        # max in reds, min in blues, a colour each per l_AB value, distinct
        series = needle.split("<c:ser>")[1:]
        colours = [re.search(r'srgbClr val="([0-9A-F]{6})"', x).group(1) for x in series]
        names = [re.search(r"<c:v>([^<]*)</c:v>", x).group(1) for x in series]
        reds = [c for c, n in zip(colours, names) if n.startswith("max")]
        blues = [c for c, n in zip(colours, names) if n.startswith("min")]
        assert len(reds) == len(blues) == 3 and len(set(colours)) == 6
        assert all(int(c[:2], 16) > int(c[4:], 16) for c in reds)
        assert all(int(c[4:], 16) > int(c[:2], 16) for c in blues)
    about = [r for r in book["About"].iter_rows(values_only=True)]
    assert about[0][0] == "command" and "--vary l_BC=20,95,105" in about[0][1]


# -- 4. failure isolation -----------------------------------------------------------------

def test_refused_and_partial_variants_do_not_stop_the_others(sewing_batch):
    frame, folder = sewing_batch
    status = dict(zip(frame["variant"], frame["status"]))
    for v in ("1", "4", "7"):  # l_AB = -1
        assert status[v] == "refused: parameters.l_AB must be > 0, got -1.0"
        assert not (folder / f"sewing_machine-000{v}.xlsx").exists()
    assert status["2"] == status["3"] == "partial"  # l_BC = 20 < l_AB: rows fail
    assert all(status[v] == "ok" for v in ("5", "6", "8", "9"))
    assert frame.attrs["failed"] == 5
    partial = frame.set_index("variant").loc["2"]
    # |x_B| = 30 |cos theta| <= 20 only near 90 and 270 deg: 2 x 3 rows of 13 assemble.
    assert partial["rows_not_assembled"] == 13 - 6


def test_a_variant_that_assembles_nowhere_is_refused_with_the_reason(tmp_path, capsys):
    code = cli.main(["batch", FOUR_BAR, "--vary", "l_AB=120,500", "--step", "30", "--out",
                     str(tmp_path), "--jobs", "1", "--quiet"])
    assert code == 1
    rows = _read_csv(tmp_path / "four_bar-batch" / "summary.csv")
    assert rows[0]["status"] == "ok"
    assert rows[1]["status"].startswith("refused: cannot be assembled anywhere")
    assert "l_AB = 500" in rows[1]["status"] and rows[1]["file"] == ""
    assert sorted(p.name for p in (tmp_path / "four_bar-batch").glob("*.xlsx")) == [
        "four_bar-0001.xlsx", "summary.xlsx"]


# -- 5. determinism and resuming ---------------------------------------------------------

def run_in(folder: Path, monkeypatch, **options) -> dict[str, bytes]:
    """The batch of VARY at 30 deg run from ``folder`` with ``--out out`` (the same
    relative path in every run, as the workbooks' About sheet names it)."""
    folder.mkdir(parents=True, exist_ok=True)
    monkeypatch.chdir(folder)
    batch(SEWING, vary=VARY, out="out", step=30.0, progress=False, **options)
    return _files(folder / "out" / "sewing_machine-batch")


def test_two_processes_write_the_same_bytes_as_one(tmp_path, monkeypatch):
    one = run_in(tmp_path / "one", monkeypatch, jobs=1)
    two = run_in(tmp_path / "two", monkeypatch, jobs=2)
    assert len(one) == 6 + 2 and one == two


def test_rerun_keeps_complete_variants_and_makes_the_missing(tmp_path, capsys):
    args = ["batch", SEWING, "--vary", "l_BC=95,100,105", "--step", "30", "--out",
            str(tmp_path), "--jobs", "1", "--quiet"]
    assert cli.main(args) == 0
    folder = tmp_path / "sewing_machine-batch"
    before = _files(folder)
    stamps = {p.name: p.stat().st_mtime_ns for p in folder.glob("sewing_machine-*.xlsx")}
    # An interruption: one workbook and the summaries not yet written, a torn journal line.
    (folder / "sewing_machine-0002.xlsx").unlink()
    (folder / "summary.csv").unlink()
    (folder / "summary.xlsx").unlink()
    with (folder / ".batch-journal.jsonl").open("a") as journal:
        journal.write('{"index": 2, "sha2')
    assert cli.main(args) == 0
    assert _files(folder) == before
    for name in ("sewing_machine-0001.xlsx", "sewing_machine-0003.xlsx"):
        assert (folder / name).stat().st_mtime_ns == stamps[name]  # not rewritten
    # Another command into the same folder: refused without --force.
    capsys.readouterr()
    other = ["batch", SEWING, "--vary", "l_BC=95,100", "--step", "30", "--out",
             str(tmp_path), "--jobs", "1", "--quiet"]
    assert cli.main(other) == 2
    assert "another command" in capsys.readouterr().err
    assert cli.main(other + ["--force"]) == 0
    assert sorted(p.name for p in folder.glob("sewing_machine-*.xlsx")) == [
        "sewing_machine-0001.xlsx", "sewing_machine-0002.xlsx"]


# -- 8. --summary-only --------------------------------------------------------------------

def test_summary_only_equals_the_per_variant_summaries(sewing_batch, tmp_path, monkeypatch):
    frame, folder = sewing_batch
    monkeypatch.setattr(summary_only, "BLOCK_ELEMENTS", 40)  # 3 variants of 13 rows a block
    fast = batch(SEWING, vary=VARY, out=tmp_path, jobs=1, step=30.0, summary_only=True,
                 progress=False)
    assert not list((tmp_path / "sewing_machine-batch").glob("sewing_machine-*.xlsx"))
    slow_rows = _read_csv(folder / "summary.csv")
    fast_rows = _read_csv(tmp_path / "sewing_machine-batch" / "summary.csv")
    for slow, quick in zip(slow_rows, fast_rows):
        assert quick.pop("file") == "" and slow.pop("file") in ("", f"sewing_machine-000"
                                                                  f"{slow['variant']}.xlsx")
        assert quick == slow  # the same numbers to the last digit
    assert list(fast.columns) == list(frame.columns)


def test_summary_only_over_random_variants_in_two_processes(tmp_path):
    vary = ["l_AB=normal:32:8", "l_BC=uniform:20:110"]
    one = batch(SEWING, vary=vary, samples=40, seed=3, out=tmp_path / "a", jobs=1,
                step=30.0, summary_only=True, progress=False)
    two = batch(SEWING, vary=vary, samples=40, seed=3, out=tmp_path / "b", jobs=2,
                step=30.0, summary_only=True, progress=False)
    assert (tmp_path / "a/sewing_machine-batch/summary.csv").read_bytes() == (
        tmp_path / "b/sewing_machine-batch/summary.csv").read_bytes()
    assert set(s.split(":")[0] for s in one["status"]) <= {"ok", "partial", "refused"}
    ok = one[one["status"] == "ok"]
    assert len(ok) > 10
    assert np.allclose(ok["y_C_max"], ok["l_AB"] - ok["l_BC"], rtol=0, atol=1e-12)
    assert two.equals(one)


# -- 9, 10. --audit and progress ---------------------------------------------------------

def test_audit_records_ok_for_each_workbook_and_progress_stays_off_the_pipe(tmp_path, capsys):
    code = cli.main(["batch", SEWING, "--vary", "l_AB=30,32", "--step", "60", "--out",
                     str(tmp_path), "--jobs", "2", "--audit"])
    assert code == 0
    rows = _read_csv(tmp_path / "sewing_machine-batch" / "summary.csv")
    assert [r["audit"] for r in rows] == ["ok", "ok"]
    captured = capsys.readouterr()
    assert "variant/s" not in captured.err  # stderr is not a terminal here: no bar
    assert "2 variants, 2 ok" in captured.out


def test_progress_bar_shows_done_rate_and_time_left(tmp_path, capsys):
    batch(SEWING, vary=["l_AB=30,32"], out=tmp_path, jobs=1, step=60.0, progress=True)
    err = capsys.readouterr().err
    assert "2/2" in err and "variant/s" in err and "<" in err


def test_audit_with_summary_only_is_a_bad_spec():
    with pytest.raises(SceneError, match="makes none"):
        batch(SEWING, vary=["l_AB=30,32"], summary_only=True, audit=True)


def test_audit_column_records_fail_for_a_workbook_whose_cached_value_is_wrong(sewing_batch):
    """What --audit records, on a real workbook with one cached value changed by hand."""
    import io
    import re
    from workbook_gen.batching.job import _audit
    frame, folder = sewing_batch
    data = (folder / "sewing_machine-0005.xlsx").read_bytes()
    assert _audit(data, "good") == "ok"
    source, target = zipfile.ZipFile(io.BytesIO(data)), io.BytesIO()
    with zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as out:
        for item in source.infolist():
            body = source.read(item.filename)
            if item.filename == "xl/worksheets/sheet1.xml":  # the Table: a formula's value
                body, count = re.subn(rb"(<f>[^<]*</f><v>)([-0-9.E]+)(</v>)",
                                      rb"\g<1>12345.5\g<3>", body, count=1)
                assert count == 1
            out.writestr(item, body)
    assert _audit(target.getvalue(), "tampered") == "fail"


def test_design_file_batch_names_rows_and_keeps_the_scene_value_of_empty_cells(tmp_path,
                                                                             capsys):
    design = tmp_path / "table.csv"
    design.write_text("variant,l_AB,l_BC\nbaseline,,\nlong rod,,120\nbig crank,40,\n")
    code = cli.main(["batch", SEWING, "--design", str(design), "--step", "30", "--out",
                     str(tmp_path / "out"), "--jobs", "1", "--quiet"])
    assert code == 0
    rows = _read_csv(tmp_path / "out" / "sewing_machine-batch" / "summary.csv")
    assert [(r["variant"], r["file"], r["l_AB"], r["l_BC"]) for r in rows] == [
        ("baseline", "sewing_machine-0001.xlsx", "32.0", "100.0"),
        ("long rod", "sewing_machine-0002.xlsx", "32.0", "120.0"),
        ("big crank", "sewing_machine-0003.xlsx", "40.0", "100.0")]
    for row in rows:  # the closed form again: C highest at 90 deg
        assert float(row["y_C_max"]) == pytest.approx(float(row["l_AB"]) - float(row["l_BC"]),
                                                      abs=1e-12)
