"""What a new user hits with scenes and the command line (issue 12 items 2, 5-8):
one clear line naming the key, exit 2, nothing created; the overrides a variant needs."""

from __future__ import annotations

import re
from pathlib import Path

import openpyxl
import pytest

from workbook_gen import cli
from workbook_gen.errors import SceneError
from workbook_gen.scene import MAX_STEM, load_scene, parse_scene

TEMPLATES = Path(__file__).resolve().parent.parent / "templates"
SLIDER = (TEMPLATES / "slider_crank.toml").read_text()
ACTUATOR = (TEMPLATES / "actuator_linkage.toml").read_text()


def main(capsys, *args: str) -> tuple[int, str, str]:
    code = cli.main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


def write(tmp_path: Path, text: str, name: str = "scene.toml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def refused(capsys, tmp_path, scene: Path, *extra, words=()) -> str:
    out = tmp_path / "out"
    code, _, err = main(capsys, "generate", scene, "--out", out, *extra)
    message = err.strip()
    assert code == 2, err
    assert "\n" not in message and "Traceback" not in message
    for word in words:
        assert word in message, message
    assert not out.exists(), "nothing may be created"
    return message


@pytest.mark.parametrize("bad, key", [
    ("a" * 300, "name"),
    ("a" * (MAX_STEM + 1), "name"),
    ("CON", "name"),
    ("nul.txt", "name"),
    ("trailing.", "name"),
    ("-dash", "name"),
])
def test_overlong_or_unsafe_scene_name_is_a_scene_error(capsys, tmp_path, bad, key):
    scene = write(tmp_path, SLIDER.replace('name = "slider_crank"', f'name = "{bad}"'))
    message = refused(capsys, tmp_path, scene, words=[str(scene), key])
    assert "file stem" in message


def test_overlong_name_option_is_refused_naming_it(capsys, tmp_path):
    scene = write(tmp_path, SLIDER)
    refused(capsys, tmp_path, scene, "--name", "b" * 300, words=["--name", "at most"])


def test_name_of_the_longest_allowed_stem_writes(capsys, tmp_path):
    scene = write(tmp_path, SLIDER)
    stem = "s" * MAX_STEM
    code, out, err = main(capsys, "generate", scene, "--out", tmp_path / "o", "--name", stem)
    assert code == 0, err
    assert Path(out.strip()).name == stem + ".xlsx"


@pytest.mark.parametrize("given, stem", [
    ("fb.xlsx", "fb"),                       # issue 22 item 15: not fb.xlsx.xlsx
    ("FB.XLSX", "FB"),
    ("Nähmaschine_v2", "Nähmaschine_v2"),    # letters of any script are letters
    ("Na\u0308hmaschine", "Nähmaschine"),    # NFD (as macOS types it) saved as NFC
    ("станок-1", "станок-1"),
])
def test_name_option_takes_letters_of_any_script_and_an_xlsx_suffix(capsys, tmp_path, given,
                                                                   stem):
    scene = write(tmp_path, SLIDER)
    code, out, err = main(capsys, "generate", scene, "--out", tmp_path / "o", "--name", given)
    assert code == 0, err
    assert Path(out.strip()).name == stem + ".xlsx"
    assert [p.name for p in (tmp_path / "o").iterdir()] == [stem + ".xlsx"]


@pytest.mark.parametrize("bad", ["a b", ".xlsx", "x/y", "x:y", "trailing."])
def test_name_option_refuses_what_is_not_a_file_stem(capsys, tmp_path, bad):
    scene = write(tmp_path, SLIDER)
    refused(capsys, tmp_path, scene, "--name", bad, words=["--name", "file stem"])


@pytest.mark.parametrize("extra, key", [
    (["--step", "1e9"], "--step"),
    (["--step", "200"], "--step"),
    (["--start", "10", "--stop", "10"], "--stop"),
])
def test_a_sweep_of_fewer_than_three_rows_is_refused_naming_the_key(capsys, tmp_path, extra,
                                                                    key):
    scene = write(tmp_path, SLIDER)
    refused(capsys, tmp_path, scene, *extra, words=[key, "at least 3"])


def test_a_sweep_step_in_the_scene_leaving_one_row_names_sweep_step(capsys, tmp_path):
    scene = write(tmp_path, SLIDER.replace("step = 10.0", "step = 1000.0"))
    refused(capsys, tmp_path, scene, words=["sweep.step", "1 row"])


def test_a_step_that_misses_the_stop_warns_naming_keys_and_last_row(capsys, tmp_path):
    scene = write(tmp_path, SLIDER)
    code, out, err = main(capsys, "generate", scene, "--out", tmp_path / "o", "--step", "7")
    assert code == 0, err
    assert "warning" in err and "--step = 7" in err and "sweep.stop = 360" in err
    assert "last row is 357" in err
    book = openpyxl.load_workbook(out.strip(), read_only=True)
    assert book["Table"].max_row == 1 + 52  # 0, 7, ..., 357


def test_a_step_that_reaches_the_stop_does_not_warn():
    scene = load_scene(TEMPLATES / "actuator_linkage.toml")  # 1..1.687 by 0.0687
    assert scene.warnings == () and scene.sweep.rows == 11
    assert load_scene(TEMPLATES / "slider_crank.toml", step=0.1).warnings == ()


def test_unknown_mechanism_names_file_and_key(capsys, tmp_path):
    scene = write(tmp_path, SLIDER.replace('mechanism = "slider_crank"', 'mechanism = "loom"'))
    refused(capsys, tmp_path, scene, words=[str(scene), "mechanism", "loom", "four_bar"])


def test_scene_saved_with_a_byte_order_mark_is_read(capsys, tmp_path):
    scene = tmp_path / "bom.toml"
    scene.write_bytes(b"\xef\xbb\xbf" + SLIDER.encode("utf-8"))
    code, out, err = main(capsys, "generate", scene, "--out", tmp_path / "o")
    assert code == 0, err
    assert Path(out.strip()).name == "slider_crank.xlsx"


@pytest.mark.parametrize("missing", ["u", "v"])
def test_mass_entry_without_centre_of_mass_is_refused(capsys, tmp_path, missing):
    text = (TEMPLATES / "slider_crank_masses.toml").read_text()
    entry = "crank = { m = 0.20, u = 15.0, v = 0.0 }"
    assert entry in text
    kept = ", ".join(p for p in ("m = 0.20", "u = 15.0", "v = 0.0") if p[0] != missing)
    scene = write(tmp_path, text.replace(entry, "crank = { " + kept + " }"))
    refused(capsys, tmp_path, scene, words=[str(scene), f"masses.crank.{missing}", "missing"])


def test_out_naming_an_existing_file_says_it_is_not_a_folder(capsys, tmp_path):
    scene = write(tmp_path, SLIDER)
    blocker = tmp_path / "taken.xlsx"
    blocker.write_bytes(b"precious")
    code, _, err = main(capsys, "generate", scene, "--out", blocker)
    assert code == 2
    assert "is a file, not a folder" in err and "--out" in err and "File exists" not in err
    assert blocker.read_bytes() == b"precious"


def _actuator_asking(quantities: str, options: str | None) -> str:
    head = ACTUATOR[:ACTUATOR.index("[outputs]")]
    text = head + f"[outputs]\nquantities = {quantities}\n"
    if options is not None:
        text += f"\n[options]\n{options}\n"
    return text


def test_asking_for_an_iterative_quantity_asks_for_its_method():
    scene = parse_scene(_actuator_asking('["phi_2_iter"]', None), "lever.toml")
    assert scene.options["method"] == "bisection"
    assert "phi_2_iter" in scene.outputs
    assert "phi_2_iter" in [q.name for q in scene.template.quantities]
    explicit = parse_scene(_actuator_asking('["phi_2_iter"]', 'method = "bisection"'), "x")
    assert dict(explicit.options) == dict(scene.options)


def test_iterative_quantity_with_a_conflicting_method_is_an_error_saying_so():
    with pytest.raises(SceneError) as caught:
        parse_scene(_actuator_asking('["phi_2_iter"]', 'method = "closed"'), "lever.toml")
    message = str(caught.value)
    assert "lever.toml" in message and "phi_2_iter" in message
    assert "options.method" in message and "bisection" in message and "'closed'" in message


def test_closed_form_outputs_keep_the_closed_method():
    scene = parse_scene(_actuator_asking('["phi_2", "gamma"]', None), "x")
    assert scene.options.get("method", "closed") == "closed"


def test_set_overrides_an_option_start_stop_and_name_beside_the_baseline(capsys, tmp_path):
    scene = write(tmp_path, (TEMPLATES / "four_bar.toml").read_text())
    out = tmp_path / "o"
    assert main(capsys, "generate", scene, "--out", out)[0] == 0
    code, printed, err = main(capsys, "generate", scene, "--out", out, "--set", "branch=crossed",
                              "--set", "l_O2B=85", "--start", "20", "--stop", "80",
                              "--step", "5", "--name", "four_bar_crossed")
    assert code == 0, err
    assert sorted(p.name for p in out.iterdir()) == ["four_bar.xlsx", "four_bar_crossed.xlsx"]
    book = openpyxl.load_workbook(printed.strip(), read_only=True)
    table = [row for row in book["Table"].iter_rows(values_only=True)]
    assert [r[0] for r in table[1:]] == list(range(20, 81, 5))
    about = {r[0]: r[1] for r in book["About"].iter_rows(values_only=True) if r[0]}
    assert '"branch": "crossed"' in about["options"]
    for word in ("--set branch=crossed", "--set l_O2B=85", "--start 20", "--stop 80",
                 "--name four_bar_crossed"):
        assert word in about["overrides"]


def test_crossed_branch_by_set_equals_crossed_branch_in_the_scene(tmp_path):
    text = (TEMPLATES / "four_bar.toml").read_text()
    by_set = load_scene(write(tmp_path, text), overrides={"branch": "crossed"})
    in_file = re.sub(r'branch = "open"', 'branch = "crossed"', text)
    assert 'branch = "crossed"' in in_file
    by_file = parse_scene(in_file, "x")
    from workbook_gen.tabulate import compute
    assert compute(by_set).equals(compute(by_file))
    assert compute(by_set)["theta_3 [deg]"].iloc[4] != compute(load_scene(
        write(tmp_path, text, "b.toml")))["theta_3 [deg]"].iloc[4]


@pytest.mark.parametrize("item, words", [
    ("branch=sideways", ["options.branch", "sideways"]),
    ("l_AB=long", ["parameters.l_AB", "number", "long"]),
    ("l_AB", ["--set", "NAME=VALUE"]),
])
def test_bad_set_values_name_the_key(capsys, tmp_path, item, words):
    scene = write(tmp_path, (TEMPLATES / "four_bar.toml").read_text())
    refused(capsys, tmp_path, scene, "--set", item, words=words)


def test_python_load_scene_takes_the_same_overrides():
    scene = load_scene(TEMPLATES / "four_bar.toml", overrides={"branch": "crossed", "l_AB": 130},
                       step=5.0, start=10.0, stop=50.0, name="variant")
    assert scene.name == "variant" and scene.options["branch"] == "crossed"
    assert scene.parameters["l_AB"] == 130.0
    assert scene.sweep.values() == [10.0, 15.0, 20.0, 25.0, 30.0, 35.0, 40.0, 45.0, 50.0]
