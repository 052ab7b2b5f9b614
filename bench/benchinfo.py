"""What every benchmark's ``--json FILE`` records besides its figures: the command, the
machine (CPU model, cores, Python, LibreOffice and package versions) and when and under
what load it ran (UTC start and end, the 1-minute load average at start and end, so that a
run on a loaded machine is visible).  scripts/readme_figures.py renders the README's speed
figures from these files (docs/bench/*.json).

    record = Record()              # at the start of the run
    ...                            # measure
    record.write(path, figures)    # at the end: {"command", "machine", "run", "figures"}
"""

from __future__ import annotations

import datetime
import json
import os
import platform
import subprocess
import sys
from importlib import metadata
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("workbook-gen", "numpy", "XlsxWriter", "openpyxl", "mpmath", "pandas", "formualizer",
            "formulas", "ironcalc", "dask", "distributed")


def _now() -> str:
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")


def _load() -> float | None:
    try:
        return round(os.getloadavg()[0], 2)
    except OSError:
        return None


def cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text(encoding="utf-8").splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def libreoffice_version() -> str | None:
    """``soffice --version``'s version number, None if LibreOffice is not found."""
    try:
        out = subprocess.run(["soffice", "--version"], capture_output=True, text=True,
                             timeout=120).stdout.split()
    except (OSError, subprocess.TimeoutExpired):
        return None
    return next((w for w in out if w[:1].isdigit()), " ".join(out) or None)


def machine() -> dict:
    versions = {}
    for name in PACKAGES:
        try:
            versions[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            versions[name] = None
    return {"cpu": cpu_model(), "cores": os.cpu_count(), "arch": platform.machine(),
            "system": f"{platform.system()} {platform.release()}",
            "python": platform.python_version(), "libreoffice": libreoffice_version(),
            "packages": versions}


class Record:
    """Started when the run starts; ``write`` adds the end and the figures."""

    def __init__(self) -> None:
        args, rest = [], list(sys.argv[1:])
        while rest:  # the command as given, without the --json FILE it was told to write
            arg = rest.pop(0)
            if arg == "--json":
                rest[:1] = []
            elif not arg.startswith("--json="):
                args.append(arg)
        self.command = " ".join(["python", os.path.relpath(sys.argv[0], ROOT)] + args)
        self.started, self.load_start = _now(), _load()

    def describe(self) -> dict:
        """{"command", "machine", "run"}: what ran, where, when and under what load."""
        return {"command": self.command, "machine": machine(),
                "run": {"started": self.started, "finished": _now(),
                        "load_start": self.load_start, "load_end": _load()}}

    def write(self, path: str | Path, figures: dict) -> None:
        """Write the record as JSON to ``path`` (atomically: a temporary file renamed)."""
        data = {**self.describe(), "figures": figures}
        path = Path(path)
        tmp = path.with_name(f".{path.name}.tmp")
        tmp.write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
        os.replace(tmp, path)


def check_writable(path: str | None) -> None:
    """Exit 2 with one line before measuring if ``--json``'s folder does not exist."""
    if path is not None and not Path(path).resolve().parent.is_dir():
        print(f"--json {path}: no such folder {Path(path).resolve().parent}", file=sys.stderr)
        sys.exit(2)
