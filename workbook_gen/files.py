"""Writing output files safely: never over an existing file without ``force``, and
atomically (a temporary file beside the target, then a rename), so a failed run
leaves nothing half-written. A place that cannot be written is refused before any work,
in one line (``OutputError``), never with the operating system's traceback."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Callable

from .errors import OutputError, OutputExistsError

Place = Callable[[Path, Path], object]   # (finished temporary, target): moves it into place


def refuse_existing(target: Path, force: bool) -> None:
    """Refuse before any work: an existing file without ``force``, a folder that is a
    file, a target that is a folder, a folder that cannot be written."""
    probe_writable(_refuse(Path(target), force))


def _refuse(target: Path, force: bool) -> Path:
    """``refuse_existing`` but for the probe; returns the nearest folder that exists."""
    folder = next((f for f in (target.parent, *target.parent.parents) if f.exists()),
                  Path("."))
    if not folder.is_dir():
        raise OutputError(f"{folder} is a file, not a folder: --out names the "
                          f"folder the file {target.name} is written into")
    if target.is_dir():
        raise OutputError(f"{target} is a folder: the output is a file of that name "
                          "(name another, or remove the folder)")
    if target.exists() and not force:
        raise OutputExistsError(f"{target} exists; use --force to overwrite it")
    return folder


def probe_writable(folder: Path) -> None:
    """Create and remove a file in ``folder``: the one test of permissions, read-only
    file systems and the rest that holds for every user, root included."""
    try:
        fd, name = tempfile.mkstemp(prefix=".workbook-gen.", suffix=".probe", dir=folder)
    except OSError as exc:
        raise OutputError(f"{folder}: cannot write there: {exc.strerror}") from None
    os.close(fd)
    os.unlink(name)


def write_atomically(target: Path, build: Callable[[Path], None], *, force: bool,
                     place: Place = os.replace) -> Path:
    """``build(temporary_path)`` writes the file; ``place(temporary_path, target)`` (a
    rename by default) then puts it in place of ``target``."""
    _refuse(target, force)  # (creating the temporary file is the probe)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        fd, temp = tempfile.mkstemp(prefix=f".{target.stem}.", suffix=".xlsx.tmp",
                                    dir=target.parent)
    except OSError as exc:
        raise OutputError(f"{target.parent}: cannot write there: {exc.strerror}") from None
    os.close(fd)
    try:
        build(Path(temp))
        os.chmod(temp, 0o644)
        place(Path(temp), target)
    except OSError as exc:
        Path(temp).unlink(missing_ok=True)
        if exc.filename in (None, temp, str(target)):  # the writing failed, not a read
            raise OutputError(f"{target}: cannot write: {exc.strerror}") from None
        raise
    except BaseException:
        Path(temp).unlink(missing_ok=True)
        raise
    return target


def write_bytes_atomically(target: Path, data: bytes, *, force: bool) -> Path:
    """Write ``data`` to ``target`` atomically (see ``write_atomically``)."""
    return write_atomically(target, lambda temp: temp.write_bytes(data), force=force)
