"""Batch speed, as ratios within one run (docs/batch.md; issue 9):

1. 1,000 sewing-machine variants at 10 deg with ``--jobs 2`` against a loop of
   ``write_workbook`` in one process;
2. ``--summary-only`` over 1,000,000 variants (``--summary N`` another size): seconds,
   variants/s against the file batch, peak memory of the command and of its workers,
   and the same variants' needle position y_C and its extremes in plain numpy (one
   closed form of the ~70 summary columns, nothing written) as the peer;
3. Dask, a LocalCluster of 2 single-threaded worker processes, against ``--jobs 2``.

    python bench/batch.py                 # the figures the README quotes
    python bench/batch.py --variants 200 --summary 20000   # a quicker look
    python bench/batch.py --parts 2 --summary 100000       # --summary-only alone
    python bench/batch.py --json docs/bench/batch.json     # also the figures as JSON

``--json FILE`` also writes the figures with the machine and the load (bench/benchinfo.py).
"""

from __future__ import annotations

import argparse
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCENE = str(ROOT / "templates" / "sewing_machine.toml")
sys.path.insert(0, str(ROOT / "bench"))
import benchinfo  # noqa: E402


def cpu_now() -> float:
    """CPU seconds (user + sys) of this process and its finished children so far."""
    import resource
    me, kids = (resource.getrusage(w) for w in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))
    return me.ru_utime + me.ru_stime + kids.ru_utime + kids.ru_stime


def grid(count: int) -> list[str]:
    """``count`` variants (a multiple of 10): l_BC in 0.1 mm steps x 10 values of l_AB."""
    rows = count // 10
    return [f"l_BC=95:{95 + (rows - 1) * 0.1:.1f}:0.1", "l_AB=30:31.8:0.2"]


def file_batch(out: Path, count: int, jobs: int | None = None, client=None) -> float:
    from workbook_gen import batch
    start = time.perf_counter()
    frame = batch(SCENE, vary=grid(count), out=out, jobs=jobs, client=client, progress=False)
    seconds = time.perf_counter() - start
    assert len(frame) == count and frame.attrs["failed"] == 0
    return seconds


def loop(out: Path, count: int) -> float:
    """The peer: a loop of load_scene + write_workbook in this process."""
    from workbook_gen import load_scene, write_workbook
    from workbook_gen.batching.variants import from_specs
    params = ["l_AB", "l_BC"]
    design = from_specs(grid(count), params + ["l_BE", "beta_E", "x_F", "y_F", "l_FG",
                                                "omega_1"])
    start = time.perf_counter()
    for variant in design.variants:
        scene = load_scene(SCENE, overrides=dict(variant.values),
                           name=f"sewing_machine-{variant.index:04d}")
        write_workbook(scene, out)
    return time.perf_counter() - start


def summary_grid(count: int) -> list[str]:
    """``count`` variants (a multiple of 100): l_BC in 0.01 mm steps x 100 values of l_AB."""
    rows = count // 100
    return [f"l_BC=95:{95 + (rows - 1) * 0.01:.2f}:0.01", "l_AB=30:31.98:0.02"]


def summary_only(out: Path, count: int, jobs: int) -> tuple[float, ...]:
    """(seconds, peak MB of the command's process, peak MB of any worker, CPU seconds of
    the command, CPU seconds of its workers, summary columns) of ``batch
    --summary-only`` in a child (as the command line runs it: the summary not read
    back as a DataFrame)."""
    vary = summary_grid(count)
    code = ("import resource, sys, time; from workbook_gen.batching.api import run_batch as run; "
            "import pyarrow.parquet as pq; t = time.perf_counter(); "
            f"f = run({SCENE!r}, vary={vary!r}, out={str(out)!r}, jobs={jobs}, "
            "summary_only=True, progress=False); s = time.perf_counter() - t; "
            f"assert f.count == {count}; "
            "me, kids = (resource.getrusage(w) for w in (resource.RUSAGE_SELF, "
            "resource.RUSAGE_CHILDREN)); "
            "print(s, me.ru_maxrss / 1024, kids.ru_maxrss / 1024, "
            "me.ru_utime + me.ru_stime, kids.ru_utime + kids.ru_stime, "
            "len(pq.read_schema(f.folder / 'summary.parquet')))")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    result = subprocess.run([sys.executable, "-c", code], env=env, check=True,
                            capture_output=True, text=True)
    return tuple(float(x) for x in result.stdout.split())


def numpy_peer(count: int) -> tuple[float, float]:
    """(seconds, peak MB) of plain numpy over the same variants and crank angles (the
    template's step, 10 deg): the needle position y_C = l_AB sin t - sqrt(l_BC^2 -
    (l_AB cos t)^2) and its min and max with their angles, in blocks of 10,000
    variants, in a child process."""
    code = f"""
import resource, time
import numpy as np
from workbook_gen.batching.variants import from_specs
t0 = time.perf_counter()
design = from_specs({summary_grid(count)!r}, ["l_AB", "l_BC"])
l_bc, l_ab = (np.asarray(c) for c in design.variants.columns)
angles = np.radians(np.arange(0.0, 360.0 + 1e-9, 10.0))
s, c = np.sin(angles), np.cos(angles)
lo, hi = np.empty(len(l_ab)), np.empty(len(l_ab))
lo_at, hi_at = np.empty(len(l_ab)), np.empty(len(l_ab))
for a in range(0, len(l_ab), 10_000):
    ab, bc = l_ab[a:a + 10_000, None], l_bc[a:a + 10_000, None]
    y = ab * s - np.sqrt(bc ** 2 - (ab * c) ** 2)
    i, j = y.argmin(axis=1), y.argmax(axis=1)
    rows = np.arange(len(y))
    lo[a:a + 10_000], hi[a:a + 10_000] = y[rows, i], y[rows, j]
    lo_at[a:a + 10_000], hi_at[a:a + 10_000] = angles[i], angles[j]
seconds = time.perf_counter() - t0
assert np.allclose(hi, l_ab - l_bc, rtol=0, atol=1e-9)
print(seconds, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)
"""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    result = subprocess.run([sys.executable, "-c", code], env=env, check=True,
                            capture_output=True, text=True)
    seconds, peak = (float(x) for x in result.stdout.split())
    return seconds, peak


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--variants", type=int, default=1000, help="file batch size (x10)")
    parser.add_argument("--summary", type=int, default=1_000_000,
                        help="summary-only size (x100, at most 1,048,500)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--parts", default="123", help="which figures (default: all three)")
    parser.add_argument("--json", metavar="FILE", help="also write the figures, the machine "
                        "and the load to FILE")
    args = parser.parse_args()
    benchinfo.check_writable(args.json)
    record = benchinfo.Record()
    figures: dict = {"scene": str(Path(SCENE).relative_to(ROOT)), "jobs": args.jobs}
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores, Python "
          f"{platform.python_version()}, {platform.system()} {platform.release()}")
    n = args.variants
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        pool = None
        if "1" in args.parts:
            cpu = cpu_now()
            pool = file_batch(tmp / "pool", n, jobs=args.jobs)
            pool_cpu = cpu_now() - cpu
            print(f"1. {n:,} variants at 10 deg, --jobs {args.jobs}: {pool:.1f} s "
                  f"({n / pool:.1f} variants/s)", flush=True)
            single = loop(tmp / "loop", n)
            print(f"   loop of write_workbook in one process: {single:.1f} s ({n / single:.1f} "
                  f"variants/s); --jobs {args.jobs} is {single / pool:.2f}x faster", flush=True)
            shutil.rmtree(tmp / "loop")
            figures["files"] = {"variants": n, "seconds": pool, "cpu": pool_cpu,
                                "loop_seconds": single}
        if "2" in args.parts:
            seconds, parent, workers, cpu, cpu_workers, columns = summary_only(
                tmp / "summary", args.summary, args.jobs)
            peer, peer_mb = numpy_peer(args.summary)
            figures["summary_only"] = {"variants": args.summary, "seconds": seconds,
                                       "peak_mb": parent, "worker_peak_mb": workers,
                                       "cpu": cpu, "worker_cpu": cpu_workers,
                                       "columns": int(columns), "numpy_seconds": peer,
                                       "numpy_peak_mb": peer_mb}
            rate = args.summary / seconds
            versus = f", {rate / (n / pool):.0f}x the file batch's" if pool else ""
            print(f"2. --summary-only, {args.summary:,} variants, --jobs {args.jobs}: "
                  f"{seconds:.1f} s ({rate:,.0f} variants/s{versus}); peak memory "
                  f"{parent:.0f} MB (command), {workers:.0f} MB (largest worker); CPU "
                  f"{cpu:.1f} s (command) + {cpu_workers:.1f} s (workers); "
                  f"{int(columns)} columns in summary.csv, .parquet and .xlsx", flush=True)
            print(f"   plain numpy, y_C's extremes only (1 of {int(columns)} columns, nothing "
                  f"written), one process: {peer:.2f} s, peak {peer_mb:.0f} MB; the batch "
                  f"takes {seconds / peer:.0f}x its time ({(cpu + cpu_workers) / peer:.0f}x in "
                  f"CPU)", flush=True)
        if "3" in args.parts:
            from distributed import Client, LocalCluster
            os.environ["PYTHONPATH"] = os.pathsep.join(
                [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep)
                               if p])
            with LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                              dashboard_address=":0") as cluster, Client(cluster) as client:
                # --jobs 2 just before and just after: the same load on a shared machine.
                before = file_batch(tmp / "before", n, jobs=args.jobs)
                dask = file_batch(tmp / "dask", n, client=client)
                after = file_batch(tmp / "after", n, jobs=args.jobs)
            local = (before + after) / 2
            figures["dask"] = {"variants": n, "workers": 2, "seconds": dask,
                               "jobs_before": before, "jobs_after": after}
            print(f"3. Dask LocalCluster, 2 worker processes: {dask:.1f} s for {n:,} variants; "
                  f"--jobs {args.jobs} before and after: {before:.1f} s, {after:.1f} s; Dask takes "
                  f"{dask / local:.2f}x the time (overhead {(dask - local) / n * 1000:+.1f} ms "
                  f"per variant)", flush=True)
    if args.json:
        record.write(args.json, figures)


if __name__ == "__main__":
    main()
