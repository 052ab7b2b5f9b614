"""Writing output files safely: never over an existing file without ``force``, and
atomically (a temporary file beside the target, then a rename), so a failed run
leaves nothing half-written."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Callable

Place = Callable[[Path, Path], object]   # (finished temporary, target): moves it into place

from .errors import OutputExistsError, WorkbookGenError


def refuse_existing(target: Path, force: bool) -> None:
    """Refuse before any work: an existing file without ``force``, a folder that is a file."""
    for folder in (target.parent, *target.parent.parents):
        if folder.exists():
            if not folder.is_dir():
                raise WorkbookGenError(f"{folder} is a file, not a folder: --out names the "
                                       f"folder the file {target.name} is written into")
            break
    if target.exists() and not force:
        raise OutputExistsError(f"{target} exists; use --force to overwrite it")


def write_atomically(target: Path, build: Callable[[Path], None], *, force: bool,
                     place: Place = os.replace) -> Path:
    """``build(temporary_path)`` writes the file; ``place(temporary_path, target)`` (a
    rename by default) then puts it in place of ``target``."""
    refuse_existing(target, force)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise WorkbookGenError(f"{target.parent}: cannot create the folder: {exc.strerror}") from None
    fd, temp = tempfile.mkstemp(prefix=f".{target.stem}.", suffix=".xlsx.tmp", dir=target.parent)
    os.close(fd)
    try:
        build(Path(temp))
        os.chmod(temp, 0o644)
        place(Path(temp), target)
    except BaseException:
        Path(temp).unlink(missing_ok=True)
        raise
    return target


def write_bytes_atomically(target: Path, data: bytes, *, force: bool) -> Path:
    """Write ``data`` to ``target`` atomically (see ``write_atomically``)."""
    return write_atomically(target, lambda temp: temp.write_bytes(data), force=force)
