"""Batches that vary template options like parameters (docs/batch.md, Variants;
issue 22 items 1 and 3).

Every varied option's workbook is compared with what `generate --set OPTION=VALUE`
writes (the option set directly, bytes), its Table with the 50-digit reference of that
branch (tests/mp_reference.py), and the summary with the workbook read back by
openpyxl.  Bad option values: one line, exit 2, nothing written.  Design files with
`;` and a decimal comma (what Excel writes in a German locale), and the Python API's
``vary`` mapping, against the command line's strings.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import openpyxl
import pytest

from workbook_gen import batch, cli
from workbook_gen.errors import SceneError

import mp_reference

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR = str(ROOT / "templates" / "four_bar.toml")
BALANCED = str(ROOT / "templates" / "four_bar_balanced.toml")
FIVE_BAR = str(ROOT / "templates" / "five_bar.toml")
SEWING = str(ROOT / "templates" / "sewing_machine.toml")
FOUR_BAR_PARAMS = {"l_O1O2": 100.0, "l_O1A": 40.0, "l_AB": 120.0, "l_O2B": 80.0,
                   "l_AC": 60.0, "delta_C": 30.0, "omega_2": 10.0}


def _rows(path: Path) -> list[dict[str, str]]:
    """summary.csv's rows by column name (the header's unit, ``y_C_max [mm]``, dropped)."""
    with path.open(newline="", encoding="utf-8") as handle:
        return [{k.split(" [")[0]: v for k, v in row.items()} for row in csv.DictReader(handle)]


def _table(path: Path) -> dict[str, list]:
    """The Table sheet's cached values by header name (the unit dropped)."""
    sheet = openpyxl.load_workbook(path, read_only=True, data_only=True)["Table"]
    rows = list(sheet.iter_rows(values_only=True))
    names = [str(h).split(" [")[0] for h in rows[0]]
    return {n: [r[i] for r in rows[1:]] for i, n in enumerate(names)}


def _generate(scene: str, folder: Path, stem: str, sets: list[str], step: str) -> bytes:
    """What `generate` writes for the variant, over the batch's own file (the About
    sheet names the file's path)."""
    target = folder / f"{stem}.xlsx"
    made = target.read_bytes()
    target.unlink()
    args = ["generate", scene, "--out", str(folder), "--name", stem, "--step", step]
    for item in sets:
        args += ["--set", item]
    assert cli.main(args) == 0
    again = target.read_bytes()
    target.write_bytes(made)
    return again


@pytest.fixture(scope="module")
def branches(tmp_path_factory):
    """four_bar, branch x l_AB at 30 deg, in this process."""
    out = tmp_path_factory.mktemp("branches")
    frame = batch(FOUR_BAR, vary=["branch=open,crossed", "l_AB=115,120"], out=out, jobs=1,
                  step=30.0, progress=False)
    return frame, out / "four_bar-batch"


def test_branch_varies_and_each_workbook_is_what_generate_writes(branches, capsys):
    frame, folder = branches
    assert list(frame["branch"]) == ["open", "open", "crossed", "crossed"]
    assert list(frame["l_AB"]) == [115.0, 120.0, 115.0, 120.0]
    assert list(frame["status"]) == ["ok"] * 4
    for index, (branch, l_ab) in enumerate(zip(frame["branch"], frame["l_AB"]), start=1):
        stem = f"four_bar-{index:04d}"
        assert _generate(FOUR_BAR, folder, stem, [f"branch={branch}", f"l_AB={l_ab!r}"],
                         "30") == (folder / f"{stem}.xlsx").read_bytes()
    capsys.readouterr()


def test_each_branch_workbook_follows_its_own_branch_at_50_digits(branches):
    frame, folder = branches
    for index, (branch, l_ab) in enumerate(zip(frame["branch"], frame["l_AB"]), start=1):
        table = _table(folder / f"four_bar-{index:04d}.xlsx")
        inputs = table["theta_2"]
        ref, _ = mp_reference.solve("four_bar", {**FOUR_BAR_PARAMS, "l_AB": l_ab}, inputs,
                                    {"branch": branch})
        for name in ("theta_3", "theta_4", "x_C", "y_C"):
            for got, want in zip(table[name], ref[name]):
                diff = float(got) - float(want)
                if name.startswith("theta"):
                    diff = (diff + 180.0) % 360.0 - 180.0
                assert abs(diff) < 1e-9, (branch, name, got, float(want))
    # the two branches are different mechanisms: the coupler point's path differs
    open_y = _table(folder / "four_bar-0001.xlsx")["y_C"]
    crossed_y = _table(folder / "four_bar-0003.xlsx")["y_C"]
    assert max(abs(a - b) for a, b in zip(open_y, crossed_y)) > 10.0


def test_summary_shows_the_option_as_text_and_the_extremes_of_its_workbook(branches):
    frame, folder = branches
    rows = _rows(folder / "summary.csv")
    with (folder / "summary.csv").open(encoding="utf-8") as handle:  # an option has no unit
        assert handle.readline().split(",")[:5] == [
            "variant", "file", "status", "branch", "l_AB [mm]"]
    sheet = openpyxl.load_workbook(folder / "summary.xlsx", read_only=True)["Variants"]
    cells = list(sheet.iter_rows(min_row=2, max_row=5, max_col=5, values_only=True))
    assert [c[3] for c in cells] == ["open", "open", "crossed", "crossed"]  # texts
    for row in rows:
        y = _table(folder / row["file"])["y_C"]
        assert float(row["y_C_max"]) == max(y) and float(row["y_C_min"]) == min(y)


def test_summary_only_with_options_equals_the_per_variant_summary(branches, tmp_path):
    frame, folder = branches
    batch(FOUR_BAR, vary=["branch=open,crossed", "l_AB=115,120"], out=tmp_path, jobs=1,
          step=30.0, summary_only=True, progress=False)
    slow = _rows(folder / "summary.csv")
    fast = _rows(tmp_path / "four_bar-batch" / "summary.csv")
    for a, b in zip(slow, fast):
        assert a.pop("file").endswith(".xlsx") and b.pop("file") == ""
        assert a == b


def test_five_bar_method_newton_workbook_is_what_generate_writes(tmp_path, capsys):
    frame = batch(FIVE_BAR, vary={"method": ["closed", "newton"]}, out=tmp_path, jobs=1,
                  step=30.0, progress=False)
    folder = tmp_path / "five_bar-batch"
    assert list(frame["method"]) == ["closed", "newton"]
    assert _generate(FIVE_BAR, folder, "five_bar-0002", ["method=newton"], "30") == (
        folder / "five_bar-0002.xlsx").read_bytes()
    closed, newton = (_table(folder / f"five_bar-000{i}.xlsx") for i in (1, 2))
    assert not any(n.endswith("_iter") or "newton" in n.lower() for n in closed) or (
        set(newton) > set(closed))
    assert len(newton) > len(closed)  # the Newton steps are columns of their own
    capsys.readouterr()


def test_balance_true_and_false_side_by_side_with_the_columns_of_both(tmp_path, capsys):
    frame = batch(BALANCED, vary=["balance=true,false"], out=tmp_path, jobs=1, step=30.0,
                  progress=False)
    folder = tmp_path / "four_bar_balanced-batch"
    assert list(frame["balance"]) == ["true", "false"]
    assert list(frame["status"]) == ["ok", "ok"]
    assert _generate(BALANCED, folder, "four_bar_balanced-0002", ["balance=false"], "30") == (
        folder / "four_bar_balanced-0002.xlsx").read_bytes()
    balanced, plain = (_table(folder / f"four_bar_balanced-000{i}.xlsx") for i in (1, 2))
    only_balanced = [f"{q}_max" for q in balanced if f"{q}_max" in frame.columns
                     and q not in plain]
    assert only_balanced, "the counterweights' outputs are summary columns"
    for column in only_balanced:
        assert not math.isnan(frame[column][0]) and math.isnan(frame[column][1])
    # The shaking force: balanced to rounding, unbalanced clearly not (read back)
    assert max(abs(v) for v in balanced["F_x"]) < 1e-9 < max(abs(v) for v in plain["F_x"])
    rows = _rows(folder / "summary.csv")
    assert float(rows[1]["F_x_max"]) == max(plain["F_x"])
    fast = batch(BALANCED, vary=["balance=true,false"], out=tmp_path / "fast", jobs=1,
                 step=30.0, summary_only=True, progress=False)
    assert list(fast.columns) == list(frame.columns)
    for a, b in zip(rows, _rows(tmp_path / "fast/four_bar_balanced-batch/summary.csv")):
        a.pop("file"), b.pop("file")
        assert a == b
    capsys.readouterr()


def test_semicolon_design_with_decimal_comma_and_an_option_column(tmp_path, capsys):
    # What Excel writes as "CSV (semicolon delimited)" in a German locale: ';' between
    # cells, a decimal comma, Windows-1252 text.
    design = tmp_path / "design.csv"
    design.write_bytes("variant;branch;l_AB\r\nÖffnung;open;117,5\r\nKreuz;crossed;\r\n"
                       .encode("cp1252"))
    frame = batch(FOUR_BAR, design=design, out=tmp_path / "out", jobs=1, step=30.0,
                  progress=False)
    folder = tmp_path / "out/four_bar-batch"
    assert list(frame["variant"]) == ["Öffnung", "Kreuz"]
    assert list(frame["branch"]) == ["open", "crossed"]
    assert list(frame["l_AB"]) == [117.5, 120.0]
    assert _generate(FOUR_BAR, folder, "four_bar-0001", ["branch=open", "l_AB=117.5"],
                     "30") == (folder / "four_bar-0001.xlsx").read_bytes()
    assert _generate(FOUR_BAR, folder, "four_bar-0002", ["branch=crossed"], "30") == (
        folder / "four_bar-0002.xlsx").read_bytes()
    capsys.readouterr()


def test_xlsx_design_with_option_columns_as_excel_types(tmp_path):
    design = tmp_path / "design.xlsx"
    book = openpyxl.Workbook()
    sheet = book.active
    for row in (["variant", "balance", "branch"], ["a", True, "crossed"], ["b", False, None]):
        sheet.append(row)
    book.save(design)
    frame = batch(BALANCED, design=design, out=tmp_path / "out", jobs=1, step=30.0,
                  summary_only=True, progress=False)
    assert list(frame["balance"]) == ["true", "false"]
    assert list(frame["branch"]) == ["crossed", "open"]
    assert list(frame["status"]) == ["ok", "ok"]


@pytest.mark.parametrize("comma, semi", [
    ("variant,l_AB,l_BC\nlow,30.5,\nhigh,34,104.25\n",
     "variant;l_AB;l_BC\nlow;30,5;\nhigh;34;104.25\n"),
    # one column: Excel writes no separator, only the decimal comma
    ("l_AB\n30.5\n34\n-0.25\n", "l_AB\r\n30,5\r\n34\r\n-0,25\r\n"),
])
def test_comma_and_semicolon_design_files_give_the_same_summary(tmp_path, comma, semi):
    (tmp_path / "c.csv").write_text(comma, encoding="utf-8")
    (tmp_path / "s.csv").write_bytes(semi.encode("utf-8"))
    for name in ("c", "s"):
        batch(SEWING, design=tmp_path / f"{name}.csv", out=tmp_path / name, jobs=1,
              step=30.0, summary_only=True, progress=False)
    assert (tmp_path / "c/sewing_machine-batch/summary.csv").read_bytes() == (
        tmp_path / "s/sewing_machine-batch/summary.csv").read_bytes()


def test_python_vary_mapping_equals_the_command_line_strings(tmp_path, capsys):
    assert cli.main(["batch", SEWING, "--vary", "l_AB=30,32", "--vary", "l_BC=95:105:5",
                     "--step", "30", "--summary-only", "--quiet", "--out",
                     str(tmp_path / "cli")]) == 0
    batch(SEWING, vary={"l_AB": range(30, 33, 2), "l_BC": "95:105:5"}, step=30.0,
          summary_only=True, out=tmp_path / "api", progress=False)
    batch(SEWING, vary={"l_AB": np.array([30.0, 32.0]), "l_BC": [np.int64(95), 100.0, 105]},
          step=30.0, summary_only=True, out=tmp_path / "np", progress=False)
    for name in ("summary.csv", "summary.xlsx"):  # the About sheet's command too
        want = (tmp_path / "cli/sewing_machine-batch" / name).read_bytes()
        assert (tmp_path / "api/sewing_machine-batch" / name).read_bytes() == want
    assert (tmp_path / "np/sewing_machine-batch/summary.csv").read_bytes() == (
        tmp_path / "cli/sewing_machine-batch/summary.csv").read_bytes()
    capsys.readouterr()


@pytest.mark.parametrize("vary, words", [
    ({"branch": ["open", "sideways"]}, ["vary['branch']", "one of open, crossed",
                                        "'sideways'"]),
    ({"l_AB": "30,x"}, ["vary['l_AB']", "'x' is not a number"]),
    ({"l_AB": [30, "x"]}, ["vary['l_AB']", "'x' is not a number"]),
    ({"l_XY": [1, 2]}, ["vary['l_XY']", "not a parameter or option"]),
    ({"balance": ["yes"]}, ["vary['balance']", "true, false"]),
    ("l_AB=30,32", ["a mapping"]),
])
def test_api_errors_are_exceptions_naming_the_argument_not_a_flag(tmp_path, vary, words):
    with pytest.raises(SceneError) as caught:
        batch(FOUR_BAR, vary=vary, out=tmp_path, jobs=1, progress=False)
    message = str(caught.value)
    assert all(w in message for w in words) and "--" not in message, message
    assert not list(tmp_path.iterdir())


def test_api_samples_without_a_random_spec_names_the_arguments(tmp_path):
    with pytest.raises(SceneError, match=r"^samples and seed go with a random spec"):
        batch(FOUR_BAR, vary={"l_AB": [118, 120]}, samples=3, out=tmp_path, progress=False)


@pytest.mark.parametrize("scene, args, words", [
    (FOUR_BAR, ["--vary", "branch=open,sideways"], ["one of open, crossed", "'sideways'"]),
    (FOUR_BAR, ["--vary", "balance=yes"], ["balance must be true, false"]),
    (FOUR_BAR, ["--vary", "branch=normal:1:2"], ["option", "list of its values"]),
    (FOUR_BAR, ["--vary", "branch=open,open"], ["listed twice"]),
    (FOUR_BAR, ["--vary", "branch=open,crossed", "--set", "branch=crossed"], ["not both"]),
    (FOUR_BAR, ["--vary", "branch=open,crossed", "--vary", "l_AB=normal:120:1",
                "--samples", "3"], ["random study", "--set branch=VALUE"]),
    (FIVE_BAR, ["--vary", "method=closed,bisection"], ["one of closed, newton"]),
    (FIVE_BAR, ["--vary", "iterations=0,4"], ["iterations must be an integer 1..20"]),
    (FIVE_BAR, ["--vary", "iterations=2.5"], ["an integer 1..20", "'2.5'"]),
])
def test_a_bad_option_value_exits_2_with_one_line_and_writes_nothing(
        tmp_path, capsys, scene, args, words):
    out = tmp_path / "out"
    code = cli.main(["batch", scene, "--out", str(out), "--quiet", "--jobs", "1"] + args)
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1, err
    assert all(w in err for w in words), err
    assert not out.exists()


def test_a_bad_option_in_a_design_file_exits_2_naming_row_and_values(tmp_path, capsys):
    design = tmp_path / "d.csv"
    design.write_text("branch;l_AB\nopen;118\nsideways;120\n", encoding="utf-8")
    out = tmp_path / "out"
    code = cli.main(["batch", FOUR_BAR, "--design", str(design), "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and "row 3" in err and "one of open, crossed" in err, err
    assert len(err.strip().splitlines()) == 1 and not out.exists()


def test_refused_variants_of_each_branch_read_alike_with_and_without_workbooks(tmp_path):
    # a non-positive length and a coupler too long to close, in each branch
    vary = {"branch": ["open", "crossed"], "l_AB": [-1, 120, 500]}
    slow = batch(FOUR_BAR, vary=vary, out=tmp_path / "slow", jobs=1, step=30.0,
                 progress=False)
    fast = batch(FOUR_BAR, vary=vary, out=tmp_path / "fast", jobs=1, step=30.0,
                 summary_only=True, progress=False)
    assert [s.split(":")[0] for s in slow["status"]] == ["refused", "ok", "refused"] * 2
    assert "must be > 0" in slow["status"][3] and "cannot be assembled" in slow["status"][5]
    a = _rows(tmp_path / "slow/four_bar-batch/summary.csv")
    b = _rows(tmp_path / "fast/four_bar-batch/summary.csv")
    for x, y in zip(a, b):
        x.pop("file"), y.pop("file")
        assert x == y
