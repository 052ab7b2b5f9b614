"""Bad scenes (docs/scene.md, Errors): exit 2, one line naming file, key and value,
nothing written."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

GOOD = Path("templates/sewing_machine.toml").read_text()


def run(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "workbook_gen.cli", *args], cwd=cwd,
                          capture_output=True, text=True, timeout=120)


def scene(tmp_path: Path, text: str) -> str:
    path = tmp_path / "bad.toml"
    path.write_text(text)
    return str(path)


BAD = [
    # (scene text, extra args, words the message must hold)
    (GOOD.replace("l_AB = 32.0", "l_AB = -3.0"), [], ["parameters.l_AB", "> 0", "-3.0"]),
    (GOOD.replace("step = 10.0", "step = 0.0"), [], ["sweep.step", "> 0", "0.0"]),
    (GOOD, ["--step", "0"], ["--step", "> 0"]),
    ("colour = \"red\"\n" + GOOD, [], ["colour", "not a scene key", "red"]),
    (GOOD + "\ncolour = \"red\"\n", [], ["outputs.colour", "not an outputs key", "red"]),
    (GOOD.replace("l_BC = 100.0", "l_BC = \"long\""), [], ["parameters.l_BC", "number", "long"]),
    (GOOD.replace("l_AB = 32.0", "l_AB = 32.0\nl_XY = 1.0"), [], ["parameters.l_XY", "not a parameter"]),
    (GOOD.replace("step = 10.0", "step = 0.0001"), [], ["sweep.step", "more rows than Excel", "0.0001"]),
    (GOOD.replace("l_BC = 100.0", "l_BC = 10.0").replace("stop = 360.0", "stop = 30.0"), [],
     ["cannot be assembled anywhere", "l_BC = 10"]),
    (GOOD.replace('"y_C", ', '"y_Q", '), [], ["outputs.quantities", "y_Q"]),
    (GOOD.replace('name = "sewing_machine"', 'name = "../evil"'), [], ["name", "../evil"]),
    (GOOD.replace('mechanism = "sewing_machine"', 'mechanism = "loom"'), [], ["loom"]),
    (GOOD.replace("x_F = -60.0", "x_F = 0.0").replace("y_F = -20.0", "y_F = 0.0"), [],
     ["parameters.x_F", "must not coincide"]),
    (GOOD, ["--set", "l_AB"], ["--set", "NAME=VALUE"]),
    (GOOD + "\n[broken\n", [], ["not valid TOML"]),
]


@pytest.mark.parametrize("text, extra, words", BAD, ids=[" ".join(b[2][:2]) for b in BAD])
def test_bad_scene_exits_2_with_one_line_and_writes_nothing(tmp_path, text, extra, words):
    path = scene(tmp_path, text)
    out = tmp_path / "out"
    result = run("generate", path, "--out", str(out), *extra, cwd=Path.cwd())
    assert result.returncode == 2, result.stderr
    message = result.stderr.strip()
    assert "\n" not in message and "Traceback" not in message
    assert "--set" in extra or "--step" in extra or path in message or "loom" in message
    for word in words:
        assert word in message, message
    assert not out.exists() or not any(out.iterdir())


def test_existing_file_is_kept_without_force(tmp_path):
    path = scene(tmp_path, GOOD)
    out = tmp_path / "out"
    out.mkdir()
    target = out / "sewing_machine.xlsx"
    target.write_bytes(b"precious")
    result = run("generate", path, "--out", str(out), cwd=Path.cwd())
    assert result.returncode == 2 and "--force" in result.stderr
    assert target.read_bytes() == b"precious"
    result = run("generate", path, "--out", str(out), "--force", cwd=Path.cwd())
    assert result.returncode == 0 and result.stdout.strip() == str(target)
    assert target.read_bytes()[:2] == b"PK"
    assert [p.name for p in out.iterdir()] == ["sewing_machine.xlsx"]  # no temporary left


def test_list_shows_templates_parameters_and_outputs():
    result = run("list", cwd=Path.cwd())
    assert result.returncode == 0
    for word in ("sewing_machine", "slider_crank", "l_BC", "theta_5 [deg]", "s_C [mm]"):
        assert word in result.stdout


def test_generate_with_overrides_and_step(tmp_path):
    path = scene(tmp_path, GOOD)
    result = run("generate", path, "--out", str(tmp_path), "--set", "l_BC=105",
                 "--step", "5", cwd=Path.cwd())
    assert result.returncode == 0, result.stderr
    import openpyxl
    book = openpyxl.load_workbook(result.stdout.strip(), data_only=True)
    assert book["Table"].max_row == 1 + 73
    values = {r[0]: r[1] for r in book["Parameters"].iter_rows(min_row=2, values_only=True)}
    assert values["l_BC"] == 105
