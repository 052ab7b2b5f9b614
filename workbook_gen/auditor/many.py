"""Audit many workbooks: files and folders (every ``*.xlsx`` / ``*.xlsm`` under them), in
worker processes, one result per file in the order given.

    for result in audit_many(["a.xlsx", "folder/"], jobs=2):
        result.code, result.line(), result.json()

A file that cannot be read is a result with code 2 and its one-line reason; the others
go on. The exit code of a run is the worst of its files (0 agree, 1 disagree, 2 refused).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import WorkbookGenError, WorkbookReadError
from .verdict import KINDS

SUFFIXES = (".xlsx", ".xlsm")


def expand(paths: Iterable[str | Path]) -> list[Path]:
    """The workbooks named: files as given, folders searched recursively (sorted;
    Excel's ``~$`` lock files skipped). A path that does not exist is an error, and so is
    finding no workbook at all (a CI step must not pass with nothing audited)."""
    out: list[Path] = []
    paths = [Path(item) for item in paths]
    for path in paths:
        if path.is_dir():
            found = sorted(p for p in path.rglob("*") if p.suffix.lower() in SUFFIXES
                           and p.is_file() and not p.name.startswith("~$"))
            out.extend(found)
        elif path.exists():
            out.append(path)
        elif any(c in str(path) for c in "*?["):  # a pattern the shell left as it was
            raise WorkbookReadError(f"{path}: no such file or folder (a pattern that "
                                    "matched no file: nothing to audit)")
        else:
            raise WorkbookReadError(f"{path}: no such file or folder")
    if not out:
        where = ", ".join(str(p) for p in paths) or "no path given"
        raise WorkbookReadError(f"{where}: no workbook (*.xlsx, *.xlsm) found: nothing to audit")
    return out


@dataclass
class FileResult:
    path: str
    code: int                      # 0 ok, 1 cells disagree, 2 refused (error)
    error: str | None = None
    summary: dict = field(default_factory=dict)  # the report's JSON (None when refused)

    def line(self) -> str:
        if self.error is not None:
            return f"ERROR {self.path}: {self.error}"
        s = self.summary
        findings = len(s.get("findings", ()))
        word = "OK  " if self.code == 0 else "FAIL"
        sources = s.get("disagreements", 0)
        return (f"{word}  {self.path}: {s.get('formula_cells', 0)} formula cells, "
                f"{s.get('cells_agree', 0)} agree, {s.get('cells_disagree', 0)} disagree"
                + (f" ({sources} at the source)" if sources else "")
                + f", {s.get('cells_not_checked', 0)} not checked"
                + (f", {s['cells_by_contract']} by contract" if s.get("cells_by_contract") else "")
                + f", {findings} findings"
                + (", macros not checked" if s.get("macros") else "")
                + ("; no cached values: nothing verified" if s.get("saved_without_values")
                   else "")
                + "".join(f"; {c['message']}" for c in s.get("failed", ())))

    def json(self) -> dict:
        if self.error is not None:
            return {"file": self.path, "ok": False, "error": self.error}
        return self.summary


def audit_file(path: str, engine: str | None = None, max_cells: int | None = None
               ) -> FileResult:
    """One file's result; a refused file is a result, not an exception."""
    from . import audit
    try:
        report = audit(path, engine=engine, max_cells=max_cells)
    except WorkbookGenError as exc:
        message = " ".join(str(exc).split())
        return FileResult(path, 2, error=message.removeprefix(f"{path}: "))
    except (MemoryError, RecursionError) as exc:
        return FileResult(path, 2, error=f"{type(exc).__name__}: the file is too large or "
                                         "too deeply nested to audit")
    return FileResult(path, 0 if report.ok else 1, summary=report.to_json())


def audit_many(paths: Iterable[str | Path], *, jobs: int | None = None,
               engine: str | None = None,
               progress: Callable[[str], None] | None = None,
               max_cells: int | None = None) -> Iterator[FileResult]:
    """Results of ``expand(paths)`` in order, audited by ``jobs`` worker processes
    (default: the CPU count; 1 audits in this process)."""
    files = [str(p) for p in expand(paths)]
    jobs = max(1, min(jobs or os.cpu_count() or 1, len(files) or 1))
    if jobs == 1:
        for path in files:
            result = audit_file(path, engine, max_cells)
            if progress:
                progress(Path(path).name)
            yield result
        return
    with ProcessPoolExecutor(max_workers=jobs, initializer=_one_process) as pool:
        futures = [pool.submit(audit_file, path, engine, max_cells) for path in files]
        for path, future in zip(files, futures):
            try:
                result = future.result()
            except Exception as exc:  # a worker died (killed, out of memory): that file only
                result = FileResult(path, 2, error=f"the audit's worker failed: "
                                                   f"{type(exc).__name__}: {exc}")
            if progress:
                progress(Path(path).name)
            yield result


def _one_process() -> None:
    """In a worker: the workers already share the cores, so an audit forks no helper
    process of its own (workbook_gen/forked.py)."""
    os.environ["WORKBOOK_GEN_SERIAL"] = "1"


def total_line(results: list[FileResult]) -> str:
    ok = sum(r.code == 0 for r in results)
    fail = sum(r.code == 1 for r in results)
    refused = sum(r.code == 2 for r in results)
    cells = sum(r.summary.get("formula_cells", 0) for r in results)
    agree = sum(r.summary.get("cells_agree", 0) for r in results)
    disagree = sum(r.summary.get("cells_disagree", 0) for r in results)
    skipped = sum(r.summary.get("cells_not_checked", 0) for r in results)
    sources = sum(r.summary.get("disagreements", 0) for r in results)
    contract = sum(r.summary.get("cells_by_contract", 0) for r in results)
    unverified = sum(bool(r.summary.get("saved_without_values")) for r in results)
    kinds = [c["kind"] for r in results for c in r.summary.get("failed", ())]
    why = ", ".join(f"{kinds.count(k)} {text}" for k, text in KINDS.items() if k in kinds)
    return (f"total: {len(results)} files: {ok} ok, {fail} failed" + (f" ({why})" if why else "")
            + f", {refused} refused"
            + (f" ({unverified} saved without cached values: nothing verified)"
               if unverified else "")
            + f"; {cells} formula cells: {agree} agree, {disagree} disagree ({sources} at the "
            f"source), {skipped} not checked" + (f", {contract} by contract" if contract else ""))
