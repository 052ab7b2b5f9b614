"""The batch folder ``DIR/<name>-batch/``: what made it, what is complete, resuming.

``.batch.json`` records the command's inputs (scene text, --set, --step, the variants,
--summary-only, --audit, the generator's version).  ``.batch-journal.jsonl`` gets one
line per finished variant (its file's SHA-256 and its summary row), appended after
the workbook was renamed into place, and one per summary written (its SHA-256,
appended before the rename).  Run again with the same inputs and no --force:

- a variant whose workbook is on disk with the journal's hash is kept untouched (not
  rewritten), the rest are made;
- a workbook or summary that differs from what the batch wrote (edited since, or put
  there by someone else) is kept, not regenerated, and named (``kept``): a rerun never
  destroys work; --force replaces them;
- the temporary files a killed run left (``.summary.*.csv.tmp``, ``.summary.*.parquet.tmp``,
  ``.<name>-0007.*.xlsx.tmp``, ``..batch.*.xlsx.tmp``, the write probe
  ``.workbook-gen.*.probe``) are removed, whatever the mode.

Different inputs without --force: refused.  While a run writes the folder it holds a
lock on it (``flock``, released however the process ends), so a second run into the
same folder is refused rather than sweeping away the first one's temporary files.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping

from ..errors import OutputExistsError
from ..files import write_bytes_atomically

try:
    import fcntl
except ImportError:  # Windows: no lock
    fcntl = None

MANIFEST = ".batch.json"
JOURNAL = ".batch-journal.jsonl"
SUMMARIES = ("summary.csv", "summary.xlsx")
# tempfile.mkstemp's names: prefix, 8 characters of this alphabet, suffix.
_RANDOM = r"\.[a-z0-9_]{8}\."
_held: set[int] = set()   # the lock descriptors this process holds


def _close_held_in_child() -> None:
    """A forked worker must not keep the folder locked after its parent has ended."""
    for fd in _held:
        with contextlib.suppress(OSError):
            os.close(fd)
    _held.clear()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_close_held_in_child)


def digest(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def file_digest(path: Path) -> str:
    with path.open("rb") as handle:
        return hashlib.file_digest(handle, "sha256").hexdigest()


@dataclass
class Resumed:
    """What a rerun finds: the rows of the variants kept (complete, or edited since)
    and the names of the edited workbooks among them."""

    rows: dict[int, dict] = field(default_factory=dict)
    edited: dict[int, str] = field(default_factory=dict)


@dataclass
class Folder:
    path: Path
    stem: str
    identity: dict

    @property
    def key(self) -> str:
        return digest(json.dumps(self.identity, sort_keys=True).encode())

    def check(self, force: bool) -> bool:
        """Whether this is a resumption of the same command.  Refuses (OutputExistsError)
        a folder made by another command, or holding files we did not make, unless
        ``force``."""
        if not self.path.exists():
            return False
        if not self.path.is_dir():
            raise OutputExistsError(f"{self.path} exists and is not a folder")
        manifest = self.path / MANIFEST
        if manifest.exists():
            try:
                made_by = json.loads(manifest.read_text(encoding="utf-8")).get("key")
            except (OSError, ValueError):
                made_by = None
            if made_by == self.key and not force:
                return True
            if not force:
                raise OutputExistsError(
                    f"{self.path} holds a batch made by another command (other scene, "
                    f"--set, --step, variants, --summary-only, --audit or version); use "
                    f"--force to replace it, or another --out")
            return False
        if any(self.path.iterdir()) and not force:
            raise OutputExistsError(f"{self.path} exists and was not made by workbook-gen "
                                    f"batch; use --force to write into it, or another --out")
        return False

    @contextlib.contextmanager
    def locked(self):
        """The folder (which exists) held by this run; OutputExistsError if another
        run holds it."""
        if fcntl is None:
            yield
            return
        fd = os.open(self.path, os.O_RDONLY)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(fd)
            raise OutputExistsError(
                f"{self.path} is being written by another workbook-gen batch that is still "
                f"running; wait for it to end, or use another --out") from None
        _held.add(fd)
        try:
            yield
        finally:
            _held.discard(fd)
            os.close(fd)

    def temporaries(self) -> list[Path]:
        """Temporary files a killed run of a batch left in the folder."""
        pattern = re.compile(r"\.(?:(?:" + re.escape(self.stem) + r"-\d+|summary|\.batch)"
                             + _RANDOM + r"(?:xlsx|csv|parquet|texts\.parquet|final\.parquet)\.tmp|workbook-gen" + _RANDOM
                             + r"probe)")
        return [p for p in self.path.iterdir() if pattern.fullmatch(p.name)]

    def start(self, resume: bool, command: str) -> None:
        """Record the command; remove the temporary files of a killed run; without
        ``resume`` clear what an earlier batch left."""
        for item in self.temporaries():
            item.unlink(missing_ok=True)
        if not resume:
            pattern = re.compile(re.escape(self.stem) + r"-\d+\.xlsx")
            if self.path.is_dir():
                for item in self.path.iterdir():
                    if pattern.fullmatch(item.name) or item.name in SUMMARIES + (JOURNAL,):
                        item.unlink()
        text = json.dumps({"key": self.key, "command": command, "inputs": self.identity},
                          indent=1, sort_keys=True)
        write_bytes_atomically(self.path / MANIFEST, text.encode(), force=True)

    def _entries(self):
        journal = self.path / JOURNAL
        if not journal.exists():
            return
        for line in journal.read_text(encoding="utf-8").splitlines():
            try:
                yield json.loads(line)
            except ValueError:
                continue  # a line cut short by an interruption

    def finished(self) -> Resumed:
        """The variants a rerun keeps: journal entries whose workbook (if any) is on
        disk, with the recorded hash (complete) or another one (edited since)."""
        resumed = Resumed()
        for entry in self._entries():
            if "index" not in entry:
                continue
            index, row = int(entry["index"]), entry["row"]
            resumed.edited.pop(index, None)
            resumed.rows.pop(index, None)
            if row.get("file"):
                try:
                    if file_digest(self.path / row["file"]) != entry["sha256"]:
                        resumed.edited[index] = row["file"]
                except OSError:
                    continue  # gone: made again
            resumed.rows[index] = row
        return resumed

    def differs(self, name: str, data: bytes) -> bool:
        """Whether the workbook ``name``, on disk without a journal entry (a run killed
        between its rename and its journal line, or a file put there), is other than
        ``data``, what the batch makes for it."""
        try:
            return file_digest(self.path / name) != digest(data)
        except OSError:
            return True

    def place_summary(self, temporary: Path, target: Path) -> bool:
        """Move a finished summary into place, unless the one there differs from every
        summary this batch wrote under that name (edited since: kept, and the new one
        discarded).  Whether it was placed."""
        recorded = {e["sha256"] for e in self._entries() if e.get("summary") == target.name}
        if target.exists():
            try:
                ours = file_digest(target) in recorded
            except OSError:
                ours = False
            if not ours:
                temporary.unlink(missing_ok=True)
                return False
        line = json.dumps({"summary": target.name, "sha256": file_digest(temporary)})
        with (self.path / JOURNAL).open("a", encoding="utf-8") as journal:
            journal.write(line + "\n")  # before the rename: a kill between leaves ours
        os.replace(temporary, target)
        return True

    def journal(self):
        return _Journal(self.path / JOURNAL)


class _Journal:
    def __init__(self, path: Path):
        torn = False
        with contextlib.suppress(OSError), path.open("rb") as old:
            if old.seek(0, os.SEEK_END):
                old.seek(-1, os.SEEK_END)
                torn = old.read(1) != b"\n"  # a line cut short by a kill
        self.handle = path.open("a", encoding="utf-8")
        if torn:
            self.handle.write("\n")

    def add(self, index: int, data: bytes | None, row: Mapping[str, object]) -> None:
        entry = {"index": index, "sha256": digest(data) if data is not None else None,
                 "row": dict(row)}
        self.handle.write(json.dumps(entry) + "\n")
        self.handle.flush()

    def close(self) -> None:
        self.handle.close()
