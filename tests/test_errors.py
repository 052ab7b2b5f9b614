"""workbook_gen/errors.py: every error a user can fix is a WorkbookGenError, and the
command line turns each into one line on stderr and exit code 2 (no traceback)."""

from __future__ import annotations

import inspect

import pytest

from workbook_gen import errors
from workbook_gen.cli import main


def test_every_error_is_a_workbook_gen_error():
    classes = [c for _, c in inspect.getmembers(errors, inspect.isclass)
               if c.__module__ == errors.__name__]
    assert len(classes) >= 9
    for cls in classes:
        assert issubclass(cls, errors.WorkbookGenError) and issubclass(cls, Exception)
    assert issubclass(errors.IllegalNameError, errors.SceneError)
    assert issubclass(errors.CannotAssembleError, errors.SceneError)


@pytest.mark.parametrize("args, words", [
    (["generate", "no_such_scene.toml"], "no_such_scene.toml"),
    (["audit", "no_such_book.xlsx"], "no_such_book.xlsx"),
    (["generate", "templates/four_bar.toml", "--set", "l_AB=abc"], "l_AB"),
])
def test_the_command_line_reports_one_line_and_exits_2(args, words, tmp_path, capsys):
    if args[0] == "generate":
        args = [*args, "--out", str(tmp_path)]
    assert main(args) == 2
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and words in lines[0], err
    assert "Traceback" not in err
    assert list(tmp_path.iterdir()) == []   # nothing written
