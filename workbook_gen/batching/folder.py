"""The batch folder ``DIR/<name>-batch/``: what made it, what is complete, resuming.

``.batch.json`` records the command's inputs (scene text, --set, --step, the variants,
--summary-only, --audit, the generator's version).  ``.batch-journal.jsonl`` gets one
line per finished variant (its file's SHA-256 and its summary row), appended after
the workbook was renamed into place.  Run again with the same inputs and no --force:
a variant whose workbook is on disk with the journal's hash is kept untouched (not
rewritten), the rest are made.  Different inputs without --force: refused.
"""

from __future__ import annotations

import hashlib
import json
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Mapping

from ..errors import OutputExistsError
from ..files import write_bytes_atomically

MANIFEST = ".batch.json"
JOURNAL = ".batch-journal.jsonl"
SUMMARIES = ("summary.csv", "summary.xlsx")


def digest(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


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

    def start(self, resume: bool, command: str) -> None:
        """Record the command; without ``resume`` clear what an earlier batch left."""
        if not resume:
            pattern = re.compile(re.escape(self.stem) + r"-\d+\.xlsx")
            if self.path.is_dir():
                for item in self.path.iterdir():
                    if pattern.fullmatch(item.name) or item.name in SUMMARIES + (JOURNAL,):
                        item.unlink()
        text = json.dumps({"key": self.key, "command": command, "inputs": self.identity},
                          indent=1, sort_keys=True)
        write_bytes_atomically(self.path / MANIFEST, text.encode(), force=True)

    def finished(self) -> dict[int, dict]:
        """Rows of the variants already complete: journal entries whose workbook (if
        any) is on disk with the recorded hash."""
        journal = self.path / JOURNAL
        done: dict[int, dict] = {}
        if not journal.exists():
            return done
        for line in journal.read_text(encoding="utf-8").splitlines():
            try:
                entry = json.loads(line)
            except ValueError:
                continue  # a line cut short by an interruption
            row = entry["row"]
            if row.get("file"):
                target = self.path / row["file"]
                try:
                    if digest(target.read_bytes()) != entry["sha256"]:
                        continue
                except OSError:
                    continue
            done[int(entry["index"])] = row
        return done

    def journal(self):
        return _Journal(self.path / JOURNAL)


class _Journal:
    def __init__(self, path: Path):
        self.handle = path.open("a", encoding="utf-8")

    def add(self, index: int, data: bytes | None, row: Mapping[str, object]) -> None:
        entry = {"index": index, "sha256": digest(data) if data is not None else None,
                 "row": dict(row)}
        self.handle.write(json.dumps(entry) + "\n")
        self.handle.flush()

    def close(self) -> None:
        self.handle.close()
