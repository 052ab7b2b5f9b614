"""workbook_gen/files.py: outputs are written atomically (a temporary file beside the
target, then a rename), never over an existing file without ``force``; a failed build
leaves neither the target nor a temporary file; places that cannot be written are refused
in one line (OutputError) before any work."""

from __future__ import annotations

import os
import stat

import pytest

from workbook_gen.errors import OutputError, OutputExistsError
from workbook_gen.files import refuse_existing, write_atomically, write_bytes_atomically


def test_writes_the_bytes_with_ordinary_permissions(tmp_path):
    target = tmp_path / "deep" / "er" / "book.xlsx"
    assert write_bytes_atomically(target, b"abc", force=False) == target
    assert target.read_bytes() == b"abc"
    assert stat.S_IMODE(target.stat().st_mode) == 0o644
    assert sorted(p.name for p in target.parent.iterdir()) == ["book.xlsx"]


def test_an_existing_file_needs_force(tmp_path):
    target = tmp_path / "book.xlsx"
    target.write_bytes(b"old")
    with pytest.raises(OutputExistsError, match="--force"):
        write_bytes_atomically(target, b"new", force=False)
    assert target.read_bytes() == b"old"
    with pytest.raises(OutputExistsError):
        refuse_existing(target, force=False)
    write_bytes_atomically(target, b"new", force=True)
    assert target.read_bytes() == b"new"


def test_a_failed_build_leaves_nothing(tmp_path):
    target = tmp_path / "book.xlsx"

    def build(temp):
        temp.write_bytes(b"half")
        raise RuntimeError("the generator failed")

    with pytest.raises(RuntimeError):
        write_atomically(target, build, force=False)
    assert list(tmp_path.iterdir()) == []
    target.write_bytes(b"old")                       # and an old file survives it
    with pytest.raises(KeyboardInterrupt):
        write_atomically(target, lambda t: (_ for _ in ()).throw(KeyboardInterrupt()),
                         force=True)
    assert target.read_bytes() == b"old" and len(list(tmp_path.iterdir())) == 1


def test_places_that_cannot_be_written_are_refused(tmp_path):
    a_file = tmp_path / "plain"
    a_file.write_text("x")
    with pytest.raises(OutputError, match="is a file, not a folder"):
        refuse_existing(a_file / "book.xlsx", force=True)
    (tmp_path / "dir.xlsx").mkdir()
    with pytest.raises(OutputError, match="is a folder"):
        write_bytes_atomically(tmp_path / "dir.xlsx", b"x", force=True)
    if os.geteuid() != 0:                            # root writes anywhere
        locked = tmp_path / "locked"
        locked.mkdir(mode=0o555)
        with pytest.raises(OutputError, match="cannot write there"):
            refuse_existing(locked / "book.xlsx", force=False)


def test_the_placing_step_is_the_callers(tmp_path):
    target, seen = tmp_path / "book.xlsx", []

    def place(temp, dest):
        seen.append((temp.parent, temp.name.startswith(".book."), temp.read_bytes()))
        os.replace(temp, dest)

    write_atomically(target, lambda t: t.write_bytes(b"xyz"), force=False, place=place)
    assert seen == [(tmp_path, True, b"xyz")] and target.read_bytes() == b"xyz"
