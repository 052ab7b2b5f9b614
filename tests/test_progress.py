"""The package's progress bar: drawn on a terminal, silent otherwise."""

from __future__ import annotations

import io
import subprocess
import sys

from workbook_gen.progress import Progress


class FakeTerminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_progress_is_silent_when_the_stream_is_not_a_terminal():
    stream = io.StringIO()
    with Progress(5, desc="work", stream=stream) as bar:
        for i in range(5):
            bar(f"step {i}")
    assert stream.getvalue() == ""
    assert bar.done == 5 and not bar.enabled


def test_progress_draws_a_bar_with_count_on_a_terminal():
    stream = FakeTerminal()
    with Progress(4, desc="work", step="row", stream=stream, leave=True) as bar:
        bar.update(2)
        bar("half")
        bar.update(1)
    text = stream.getvalue()
    assert "work" in text and "4/4" in text and "row" in text


def test_progress_quiet_draws_nothing_even_on_a_terminal():
    stream = FakeTerminal()
    with Progress(3, stream=stream, quiet=True) as bar:
        bar.update(3)
    assert stream.getvalue() == ""


def test_silent_progress_does_not_import_tqdm():
    code = ("import io, sys; from workbook_gen.progress import Progress\n"
            "with Progress(3, stream=io.StringIO()) as bar: bar.update(3)\n"
            "print('tqdm' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_writing_a_workbook_reports_every_row_of_table_and_checks(tmp_path):
    from workbook_gen.scene import load_scene
    from workbook_gen.workbook import write_workbook
    scene = load_scene("templates/slider_crank.toml", step=5.0)
    counts = []
    write_workbook(scene, tmp_path, progress=counts.append)
    assert sum(counts) == 2 * scene.sweep.rows


def test_generate_prints_no_bar_when_stderr_is_not_a_terminal(tmp_path, capsys):
    from workbook_gen.cli import main
    assert main(["generate", "templates/slider_crank.toml", "--out", str(tmp_path)]) == 0
    captured = capsys.readouterr()
    assert captured.err == "" and captured.out.strip().endswith("slider_crank.xlsx")


def test_generate_draws_the_bar_on_a_terminal(tmp_path):
    """A real pseudo-terminal (100 columns): the bar appears on stderr (its delay set to 0
    here: a 10-degree workbook takes less than the 1 s the command line waits)."""
    from terminal import run_in_terminal
    status, text = run_in_terminal(['generate', 'templates/slider_crank.toml', '--out', str(tmp_path)])
    assert status == 0, text
    assert "slider_crank.xlsx" in text and "row" in text and "%" in text
