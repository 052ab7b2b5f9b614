"""Runners: where the unit of work runs.  Each takes ``fn(spec, chunk)`` over chunks
of variants and yields ``(chunk, result)`` as they finish, in any order; they only
schedule and collect (the results are the same whichever runs them).

- ``InProcess``: this process, one chunk after the other;
- ``LocalPool``: ``jobs`` worker processes, each importing the package once and running
  many chunks, a bounded number of chunks in flight; stopped at once (the chunks in
  flight dropped) when the caller stops early (an error, SIGTERM, Ctrl-C);
- ``DaskRunner``: an existing Dask distributed cluster (``Client``): tasks return their
  results to this process, at most a few per worker thread are in flight, ``pure=False``
  and ``retries`` so a chunk lost with a killed worker is run again.  ``wait_for_workers``
  says when none is connected, and waits (or gives up after a timeout).
"""

from __future__ import annotations

import concurrent.futures as cf
import logging
import multiprocessing
import os
import time
from typing import Callable, Iterable, Iterator, Sequence, TypeVar

from .. import terminate
from ..errors import WorkbookGenError

log = logging.getLogger(__name__)
T = TypeVar("T")
NOTICE = 2.0    # seconds without a Dask worker before saying so
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
        pool = cf.ProcessPoolExecutor(self.jobs, mp_context=context)
        try:
            pending: dict[cf.Future, Chunk] = {}
            for part in parts:
                pending[pool.submit(fn, spec, part)] = part
                if len(pending) >= limit:
                    break
            while pending:
                done, _ = cf.wait(pending, timeout=terminate.POLL,
                                  return_when=cf.FIRST_COMPLETED)
                terminate.check()
                for future in done:
                    part = pending.pop(future)
                    yield part, future.result()
                    for more in parts:
                        pending[pool.submit(fn, spec, more)] = more
                        break
        except BaseException:  # GeneratorExit too: the caller stopped early
            _stop(pool)
            raise
        pool.shutdown(wait=True)


def _stop(pool: cf.ProcessPoolExecutor) -> None:
    """Drop the chunks not started and end the workers now (SIGTERM: the work in flight
    is lost, its results not wanted), rather than wait for the chunks they run."""
    terminate = getattr(pool, "terminate_workers", None)  # Python 3.14
    if terminate is not None:
        terminate()
        return
    # A worker ended while it sends a result leaves the pool's thread reading the rest
    # for ever (this process holds the pipe's other end too), and the interpreter's exit
    # waiting for that thread: closing our end, once the workers are gone, lets the read
    # end.  Private attributes, taken before shutdown() drops them (the test
    # test_a_pool_stopped_mid_result_lets_the_process_exit notices a change).
    processes = list((getattr(pool, "_processes", None) or {}).values())
    writer = getattr(getattr(pool, "_result_queue", None), "_writer", None)
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        if process.is_alive():
            process.terminate()
    for process in processes:
        process.join(timeout=10)
        if process.is_alive():  # deaf to SIGTERM
            process.kill()
            process.join()
    if writer is not None:
        writer.close()


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


def connect(address: str, timeout: float | None = None):
    """A Dask client for ``--scheduler ADDRESS`` (WorkbookGenError if it cannot connect
    within 10 s, or ``timeout`` if shorter)."""
    try:
        from distributed import Client
    except ImportError:
        raise WorkbookGenError("--scheduler needs Dask distributed: pip install "
                               "'workbook-gen[distributed]'") from None
    limit = 10.0 if timeout is None else min(10.0, timeout)
    try:
        return Client(address, timeout=f"{limit}s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise WorkbookGenError(f"--scheduler {address}: cannot connect: {exc}") from None


def wait_for_workers(client, timeout: float | None = None) -> None:
    """Return once a worker is connected to the client's cluster.  After ``NOTICE``
    seconds without one, log a warning ("waiting for Dask workers at ADDRESS: none
    connected") and go on waiting; after ``timeout`` seconds (None: no limit) raise
    WorkbookGenError."""
    address = getattr(client.scheduler, "address", None) or str(client)
    started = time.monotonic()
    said = False
    while True:  # in slices, so that a SIGTERM is seen (terminate.check)
        waited = time.monotonic() - started
        if not said and waited >= NOTICE:
            log.warning("waiting for Dask workers at %s: none connected", address)
            said = True
        if timeout is not None and waited >= timeout:
            raise WorkbookGenError(f"--scheduler {address}: no Dask worker connected "
                                   f"within --timeout {timeout:g} s")
        limits = [terminate.POLL] + ([] if said else [NOTICE - waited]) + (
            [] if timeout is None else [timeout - waited])
        try:
            client.wait_for_workers(1, timeout=max(0.01, min(limits)))
            break
        except TimeoutError:
            terminate.check()
    if said:
        log.warning("Dask workers at %s: %d connected", address, len(client.nthreads()))


def default_jobs() -> int:
    return os.cpu_count() or 1


def pick(jobs: int | None, client) -> InProcess | LocalPool | DaskRunner:
    if client is not None:
        return DaskRunner(client)
    jobs = default_jobs() if jobs is None else jobs
    return InProcess() if jobs <= 1 else LocalPool(jobs)
