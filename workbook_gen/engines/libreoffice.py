"""Recalculate an xlsx in LibreOffice headless, with recalculation forced, and read the values back.

LibreOffice keeps the cached values of an xlsx file unless told otherwise. Each call runs in
its own temporary user profile whose settings force recalculation on load (OOXML and ODF),
so the file it saves holds LibreOffice's own results. A private profile per call also lets
several calls run at once: two soffice processes that share a profile collide.
"""

from __future__ import annotations

import datetime
import functools
import logging
import warnings
import os
import shutil
import signal
import subprocess
import tempfile
import zipfile
from pathlib import Path

import openpyxl
from openpyxl.utils.datetime import CALENDAR_WINDOWS_1900, to_excel

from workbook_gen.errors import WorkbookGenError
from workbook_gen.xlerror import ExcelError

log = logging.getLogger(__name__)

#: Environment variable that names the soffice executable explicitly.
SOFFICE_ENV = "WORKBOOK_GEN_SOFFICE"

_CANDIDATES = ("soffice", "libreoffice")
_KNOWN_PATHS = (
    "/usr/bin/soffice",
    "/usr/lib/libreoffice/program/soffice",
    "/opt/libreoffice/program/soffice",
    "/Applications/LibreOffice.app/Contents/MacOS/soffice",
)

# 0 = always recalculate, 1 = never, 2 = ask (LibreOffice's default for xlsx is "never").
_REGISTRY = """<?xml version="1.0" encoding="UTF-8"?>
<oor:items xmlns:oor="http://openoffice.org/2001/registry" \
xmlns:xs="http://www.w3.org/2001/XMLSchema" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">
<item oor:path="/org.openoffice.Office.Calc/Formula/Load">\
<prop oor:name="OOXMLRecalcMode" oor:op="fuse"><value>0</value></prop></item>
<item oor:path="/org.openoffice.Office.Calc/Formula/Load">\
<prop oor:name="ODFRecalcMode" oor:op="fuse"><value>0</value></prop></item>
</oor:items>
"""

_XLSX_FILTER = "xlsx:Calc MS Excel 2007 XML"


def find_soffice() -> str | None:
    """Path of the LibreOffice ``soffice`` executable, or None when it is not installed."""
    explicit = os.environ.get(SOFFICE_ENV)
    if explicit:
        return explicit if os.access(explicit, os.X_OK) else None
    for name in _CANDIDATES:
        found = shutil.which(name)
        if found:
            return found
    for path in _KNOWN_PATHS:
        if os.access(path, os.X_OK):
            return path
    return None


def _write_profile(profile: Path) -> None:
    user = profile / "user"
    user.mkdir(parents=True)
    (user / "registrymodifications.xcu").write_text(_REGISTRY, encoding="utf-8")


def _target_path(src: Path, out_dir: Path) -> Path:
    """Where the result goes: out_dir/<name>, or <stem>.recalculated.xlsx beside src itself."""
    target = out_dir / f"{src.stem}.xlsx"
    if target.resolve() == src.resolve():
        target = out_dir / f"{src.stem}.recalculated.xlsx"
    return target


def _run(cmd: list[str], timeout: float) -> subprocess.CompletedProcess[str]:
    """Run cmd in its own process group; on timeout kill the whole group (oosplash + soffice.bin)."""
    proc = subprocess.Popen(
        cmd,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        out, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        proc.communicate()
        raise
    return subprocess.CompletedProcess(cmd, proc.returncode, out, err)


def recalculate(src: Path | str, out_dir: Path | str, *, timeout: float = 300) -> Path:
    """Recalculate ``src`` in LibreOffice (recalculation forced) and save it as xlsx in ``out_dir``.

    Returns the path of the saved file: ``out_dir/<stem>.xlsx``, or ``<stem>.recalculated.xlsx``
    when that would be ``src`` itself (src is never overwritten). Raises WorkbookGenError when
    soffice is missing, times out or writes no file.
    """
    src = Path(src)
    out_dir = Path(out_dir)
    if not src.is_file():
        raise WorkbookGenError(f"{src}: no such file to recalculate")
    if not zipfile.is_zipfile(src):
        # LibreOffice would import any other file as text and save that: refuse it instead
        raise WorkbookGenError(f"{src}: not an xlsx file (not a zip archive)")
    soffice = find_soffice()
    if soffice is None:
        raise WorkbookGenError(
            "LibreOffice (soffice) not found: install it (bash scripts/install-test-deps.sh) "
            f"or set {SOFFICE_ENV}"
        )
    out_dir.mkdir(parents=True, exist_ok=True)
    target = _target_path(src, out_dir)
    with tempfile.TemporaryDirectory(prefix="workbook-gen-lo-") as tmp:
        tmp_path = Path(tmp)
        profile = tmp_path / "profile"
        conv_dir = tmp_path / "out"
        conv_dir.mkdir()
        _write_profile(profile)
        cmd = [
            soffice,
            f"-env:UserInstallation={profile.as_uri()}",
            "--headless", "--invisible", "--nologo", "--nodefault",
            "--norestore", "--nolockcheck",
            "--convert-to", _XLSX_FILTER,
            "--outdir", str(conv_dir),
            str(src.resolve()),
        ]
        log.debug("running %s", cmd)
        try:
            done = _run(cmd, timeout)
        except subprocess.TimeoutExpired:
            raise WorkbookGenError(
                f"{src}: LibreOffice did not finish within {timeout:g} s (killed)"
            ) from None
        except OSError as exc:
            raise WorkbookGenError(f"cannot run LibreOffice ({soffice}): {exc}") from None
        produced = conv_dir / f"{src.stem}.xlsx"
        if not produced.is_file():
            detail = " ".join((done.stderr or done.stdout or "").split())[:200]
            raise WorkbookGenError(
                f"{src}: LibreOffice wrote no file (exit {done.returncode})"
                + (f": {detail}" if detail else "")
            )
        shutil.move(str(produced), target)
    return target


def cell_value(value: object, data_type: str, epoch=None) -> object:
    """A recalculated formula cell's value in the evaluator's types (openpyxl reads a
    number in a date or time format as a datetime: back to the serial number)."""
    if data_type == "e":
        err = ExcelError.from_text(str(value))
        if err is not None:
            return err
    if data_type == "str" and value is None:
        return ""  # a formula that yields "" is saved as t="str" with an empty <v>
    if isinstance(value, bool) or value is None or isinstance(value, str):
        return value
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, (datetime.datetime, datetime.date, datetime.time, datetime.timedelta)):
        return float(to_excel(value, epoch or CALENDAR_WINDOWS_1900))
    return value


def _openpyxl_quiet(fn):
    """Run ``fn`` without openpyxl's warnings about the parts of a file it drops (data
    validation extensions, conditional formatting, ...), on loading and on reading rows
    (read-only sheets are parsed as they are read): only values are read here."""
    @functools.wraps(fn)
    def quiet(*args, **kwargs):
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", category=UserWarning, module="openpyxl")
            return fn(*args, **kwargs)
    return quiet


@_openpyxl_quiet
def _formula_cells(path: Path) -> dict[str, set[str]]:
    wb = openpyxl.load_workbook(path, read_only=True, data_only=False)
    try:
        cells: dict[str, set[str]] = {}
        for ws in wb.worksheets:
            found = cells.setdefault(ws.title, set())
            for row in ws.iter_rows():
                for cell in row:
                    if cell.data_type == "f":
                        found.add(cell.coordinate)
        return cells
    finally:
        wb.close()


@_openpyxl_quiet
def read_formula_values(path: Path | str) -> dict[str, dict[str, object]]:
    """{sheet: {"B2": value}} of every formula cell's cached value in an xlsx file."""
    path = Path(path)
    formulas = _formula_cells(path)
    wb = openpyxl.load_workbook(path, read_only=True, data_only=True)
    # numbers stay numbers: openpyxl would read one in a date format as a datetime (and
    # a serial past 9999-12-31 as an error); cell_value converts back if it still does
    wb._date_formats, wb._timedelta_formats = set(), set()
    try:
        result: dict[str, dict[str, object]] = {}
        for ws in wb.worksheets:
            wanted = formulas.get(ws.title, set())
            values: dict[str, object] = {}
            result[ws.title] = values
            if not wanted:
                continue
            for row in ws.iter_rows():
                for cell in row:
                    coord = getattr(cell, "coordinate", None)
                    if coord in wanted:
                        values[coord] = cell_value(cell.value, cell.data_type, wb.epoch)
            for coord in wanted - values.keys():
                values[coord] = None
        return result
    finally:
        wb.close()


def recalculated_values(src: Path | str, *, timeout: float = 300) -> dict[str, dict[str, object]]:
    """{sheet: {"B2": value}} of every formula cell of ``src`` after LibreOffice recalculated it.

    Values are float, str, bool, None or ExcelError (error cells).
    """
    with tempfile.TemporaryDirectory(prefix="workbook-gen-recalc-") as tmp:
        return read_formula_values(recalculate(src, tmp, timeout=timeout))


def recalculated_values_many(srcs: list[Path | str], *,
                             timeout: float = 600) -> list[dict[str, dict[str, object]]]:
    """As ``recalculated_values`` for several xlsx files in one LibreOffice run (one start-up
    instead of one per file); the files' stems must differ."""
    srcs = [Path(s) for s in srcs]
    stems = [s.stem for s in srcs]
    if len(set(stems)) != len(stems):
        raise WorkbookGenError(f"files to recalculate together need different names: {stems}")
    soffice = find_soffice()
    if soffice is None:
        raise WorkbookGenError(f"LibreOffice (soffice) not found: set {SOFFICE_ENV}")
    for src in srcs:
        if not zipfile.is_zipfile(src):
            raise WorkbookGenError(f"{src}: not an xlsx file (not a zip archive)")
    with tempfile.TemporaryDirectory(prefix="workbook-gen-lo-") as tmp:
        tmp_path = Path(tmp)
        profile, conv_dir = tmp_path / "profile", tmp_path / "out"
        conv_dir.mkdir()
        _write_profile(profile)
        cmd = [soffice, f"-env:UserInstallation={profile.as_uri()}", "--headless",
               "--invisible", "--nologo", "--nodefault", "--norestore", "--nolockcheck",
               "--convert-to", _XLSX_FILTER, "--outdir", str(conv_dir),
               *(str(s.resolve()) for s in srcs)]
        try:
            done = _run(cmd, timeout)
        except subprocess.TimeoutExpired:
            raise WorkbookGenError(f"LibreOffice did not finish within {timeout:g} s") from None
        out = []
        for src in srcs:
            produced = conv_dir / f"{src.stem}.xlsx"
            if not produced.is_file():
                raise WorkbookGenError(f"{src}: LibreOffice wrote no file "
                                       f"(exit {done.returncode})")
            out.append(read_formula_values(produced))
        return out
