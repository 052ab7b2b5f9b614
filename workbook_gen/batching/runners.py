"""Runners: where the unit of work runs.  Each takes ``fn(spec, chunk)`` over chunks
of variants and yields ``(chunk, result)`` as they finish, in any order; they only
schedule and collect (the results are the same whichever runs them).

- ``InProcess``: this process, one chunk after the other;
- ``LocalPool``: ``jobs`` worker processes, each importing the package once and running
  many chunks, a bounded number of chunks in flight;
- ``DaskRunner``: an existing Dask distributed cluster (``Client``): tasks return their
  results to this process, at most a few per worker thread are in flight, ``pure=False``
  and ``retries`` so a chunk lost with a killed worker is run again.
"""

from __future__ import annotations

import concurrent.futures as cf
import multiprocessing
import os
from typing import Callable, Iterable, Iterator, Sequence, TypeVar

from ..errors import WorkbookGenError

T = TypeVar("T")
Chunk = Sequence


def chunks(items: Sequence[T], size: int) -> list[Sequence[T]]:
    return [items[i:i + size] for i in range(0, len(items), size)]


class InProcess:
    name = "in-process"

    def run(self, fn: Callable, spec, parts: Iterable[Chunk]) -> Iterator[tuple[Chunk, object]]:
        for part in parts:
            yield part, fn(spec, part)


class LocalPool:
    """``jobs`` worker processes (forked where the platform allows: the workers start
    with the package imported and the per-process caches (compiled trees, row
    templates) filled by the first chunk, which runs in this process)."""

    def __init__(self, jobs: int):
        self.jobs = jobs
        self.name = f"{jobs} local processes"

    def run(self, fn: Callable, spec, parts: Iterable[Chunk]) -> Iterator[tuple[Chunk, object]]:
        methods = multiprocessing.get_all_start_methods()
        fork = "fork" in methods
        context = multiprocessing.get_context("fork" if fork else None)
        limit = 2 * self.jobs
        parts = iter(parts)
        if fork:  # the first chunk here: forked workers start with its caches warm
            first = next(parts, None)
            if first is None:
                return
            yield first, fn(spec, first)
        with cf.ProcessPoolExecutor(self.jobs, mp_context=context) as pool:
            pending: dict[cf.Future, Chunk] = {}
            for part in parts:
                pending[pool.submit(fn, spec, part)] = part
                if len(pending) >= limit:
                    break
            while pending:
                done, _ = cf.wait(pending, return_when=cf.FIRST_COMPLETED)
                for future in done:
                    part = pending.pop(future)
                    yield part, future.result()
                    for more in parts:
                        pending[pool.submit(fn, spec, more)] = more
                        break


class DaskRunner:
    """A Dask distributed ``Client`` (``Client("tcp://host:8786")``)."""

    def __init__(self, client, per_thread: int = 2, retries: int = 3):
        self.client = client
        self.per_thread = per_thread
        self.retries = retries
        self.name = f"Dask cluster at {getattr(client, 'scheduler', None) and client.scheduler.address}"

    def run(self, fn: Callable, spec, parts: Iterable[Chunk]) -> Iterator[tuple[Chunk, object]]:
        from distributed import as_completed
        threads = sum(self.client.nthreads().values()) or 1
        limit = max(2, self.per_thread * threads)
        parts = iter(parts)
        owner = {}

        def submit(part):
            future = self.client.submit(fn, spec, part, pure=False, retries=self.retries)
            owner[future.key] = part
            return future

        first = []
        for part in parts:
            first.append(submit(part))
            if len(first) >= limit:
                break
        if not first:
            return
        queue = as_completed(first)
        for future in queue:
            result = future.result()
            part = owner.pop(future.key)
            future.release()
            for more in parts:
                queue.add(submit(more))
                break
            yield part, result


def connect(address: str):
    """A Dask client for ``--scheduler ADDRESS`` (WorkbookGenError if it cannot connect)."""
    try:
        from distributed import Client
    except ImportError:
        raise WorkbookGenError("--scheduler needs Dask distributed: pip install "
                               "'workbook-gen[distributed]'") from None
    try:
        return Client(address, timeout="10s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise WorkbookGenError(f"--scheduler {address}: cannot connect: {exc}") from None


def default_jobs() -> int:
    return os.cpu_count() or 1


def pick(jobs: int | None, client) -> InProcess | LocalPool | DaskRunner:
    if client is not None:
        return DaskRunner(client)
    jobs = default_jobs() if jobs is None else jobs
    return InProcess() if jobs <= 1 else LocalPool(jobs)
