"""Which engine reproduces the corpus's cached values: ours, formualizer, IronCalc, LibreOffice.

For every workbook of ../shared/corpus/xlsx (or the files given), the formula cells that
hold a cached value and call no volatile function (NOW, TODAY, RAND, RANDBETWEEN,
RANDARRAY) are the cells counted. Each engine recomputes the workbook in a child process
with a per-file timeout (a hang or a crash costs that engine that file only):

- **ours**: ``workbook_gen.audit(path)`` (Excel semantics; LibreOffice's for a file
  LibreOffice saved). Its disagreeing cells come with both values; its "not checked"
  cells are not computed; the rest agree with their cached value by the audit's stricter
  tolerance (relative 1e-10).
- **formualizer**: ``load_workbook(path)``, ``evaluate_all()``, ``get_value`` per cell.
- **IronCalc**: ``load_from_xlsx(path, "en", "UTC")``, ``evaluate()``, ``get_cell_value``.
- **LibreOffice**: a copy recalculated headless with recalculation forced
  (``workbook_gen.engines.libreoffice``), its values read back.

One rule judges every engine (``reproduces``): numbers within a relative 1e-9 (absolute
1e-12 near zero), errors, text and booleans equal, an empty text equal to an empty
cell. A cell an engine could not compute (the file failed or timed out, no value or an empty
one, an error that is not one of Excel's such as #N/IMPL!, or #NAME? where the cached
value is not: a function it lacks) is "not computed".

    python bench/peers.py [--limit N] [--timeout 180] [--engines ours,formualizer,...]
                          [--json docs/bench/peers.json] [FILE ...]
"""

from __future__ import annotations

import argparse
import datetime as dt
import json
import math
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
sys.path.insert(0, str(ROOT))
import benchinfo  # noqa: E402

CORPUS = Path("/work/shared/corpus/xlsx")
ENGINES = ("ours", "formualizer", "ironcalc", "libreoffice")
LABEL = {"ours": "ours", "formualizer": "formualizer", "ironcalc": "IronCalc",
         "libreoffice": "LibreOffice"}
VOLATILE = re.compile(r"(?<![A-Za-z0-9_.])(?:_xlfn\.)?(NOW|TODAY|RAND|RANDBETWEEN|RANDARRAY)\s*\(",
                      re.IGNORECASE)
EXCEL_ERRORS = {"#NULL!", "#DIV/0!", "#VALUE!", "#REF!", "#NAME?", "#NUM!", "#N/A", "#SPILL!",
                "#CALC!", "#GETTING_DATA", "#FIELD!", "#BLOCKED!", "#CONNECT!", "#BUSY!",
                "#UNKNOWN!"}
# formualizer's error kinds, as Excel writes them
_FZ_ERRORS = {"Null": "#NULL!", "Div": "#DIV/0!", "Value": "#VALUE!", "Ref": "#REF!",
              "Name": "#NAME?", "Num": "#NUM!", "Na": "#N/A", "Spill": "#SPILL!",
              "Calc": "#CALC!", "GettingData": "#GETTING_DATA"}
NOT_COMPUTED = {"missing": True}  # a child's answer for a cell it has no value for


# ---------------------------------------------------------------- values as JSON

def encode(value) -> object:
    """A cell value as JSON: errors as {"error": "#N/A"}, numbers as floats."""
    from workbook_gen.xlerror import ExcelError
    if isinstance(value, ExcelError):
        return {"error": value.value}
    if isinstance(value, bool) or value is None or isinstance(value, str):
        return value
    if isinstance(value, (int, float)):
        return float(value)
    return {"error": f"#OTHER {type(value).__name__}"}


def _number(v) -> float | None:
    return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else None


def reproduces(cached, value) -> bool:
    """The one rule for every engine: does ``value`` (JSON-encoded) equal ``cached``?"""
    a, b = _number(cached), _number(value)
    if a is not None and b is not None:
        if not (math.isfinite(a) and math.isfinite(b)):
            return a == b
        return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)
    if cached in (None, "") and value in (None, ""):
        return True
    if isinstance(cached, bool) or isinstance(value, bool):
        return type(cached) is type(value) and cached == value
    return cached == value


def verdict(cached, value) -> str:
    """"r" (reproduces), "c" (contradicts) or "n" (not computed)."""
    if value == NOT_COMPUTED or (value is None and cached not in (None, "")):
        return "n"  # no value: a formula always has one (formualizer's unloaded sheets)
    if isinstance(value, dict) and "error" in value:
        error = value["error"]
        if error not in EXCEL_ERRORS:
            return "n"  # the engine's own mark (#N/IMPL!, #ERROR!, ...)
        if error == "#NAME?" and cached != value:
            return "n"  # a function (or name) the engine lacks
    return "r" if reproduces(cached, value) else "c"


# ---------------------------------------------------------------- children

def cells_runner(path: str) -> dict:
    """The counted cells: [sheet, row, col, cell name, cached value]; and the others."""
    from workbook_gen.cellref import cell_name
    from workbook_gen.auditor.inputs import read_inputs
    inputs = read_inputs(path)
    cells, volatile, no_value = [], 0, 0
    for key, cached in inputs.cached.items():
        if cached is None:
            no_value += 1
        elif VOLATILE.search(inputs.text_of(key)):
            volatile += 1
        else:
            cells.append([key[0], key[1], key[2], cell_name(key), encode(cached)])
    return {"cells": cells, "volatile": volatile, "no_value": no_value,
            "date1904": bool(inputs.book.date1904)}


def ours_runner(path: str, cells: list) -> list:
    from workbook_gen import audit
    report = audit(path)
    wrong = {m.cell: m.recomputed for m in report.mismatches}
    out = []
    for _, _, _, name, _ in cells:
        if name in report.not_checked or name in report.by_contract:
            out.append(NOT_COMPUTED)
        elif name in wrong:
            out.append(encode(wrong[name]))
        else:
            out.append("=")  # agrees by the audit's own comparison
    return out


def _serial(value, date1904: bool) -> float:
    from openpyxl.utils.datetime import CALENDAR_MAC_1904, CALENDAR_WINDOWS_1900, to_excel
    return float(to_excel(value, CALENDAR_MAC_1904 if date1904 else CALENDAR_WINDOWS_1900))


def formualizer_runner(path: str, cells: list, date1904: bool = False) -> list:
    import formualizer
    book = formualizer.load_workbook(path)
    book.evaluate_all()
    out = []
    for sheet, row, col, _, _ in cells:
        try:
            v = book.get_value(sheet, row, col)
        except Exception:  # noqa: BLE001 - a peer's failure on one cell is "not computed"
            out.append(NOT_COMPUTED)
            continue
        if isinstance(v, dict):
            kind = v.get("kind", "?")
            v = {"error": _FZ_ERRORS.get(kind, f"#FZ:{kind}")} if v.get("type") == "Error" \
                else {"error": f"#FZ:{v}"}
        elif isinstance(v, (int, float)) and not isinstance(v, bool):
            v = float(v)
        elif isinstance(v, (dt.datetime, dt.date, dt.time, dt.timedelta)):
            v = _serial(v, date1904)  # formualizer gives a date-formatted number as a date
        elif not (v is None or isinstance(v, (bool, str))):
            v = {"error": f"#FZ:{type(v).__name__}"}
        out.append(v)
    return out


def ironcalc_runner(path: str, cells: list) -> list:
    import ironcalc
    model = ironcalc.load_from_xlsx(path, "en", "UTC")
    model.evaluate()
    index = {p["name"]: i for i, p in enumerate(model.get_worksheets_properties())}
    error_type = ironcalc.CellType.ErrorValue
    out = []
    for sheet, row, col, _, _ in cells:
        try:
            i = index[sheet]
            v = model.get_cell_value(i, row, col)
            if model.get_cell_type(i, row, col) == error_type:
                v = {"error": str(v)}
        except Exception:  # noqa: BLE001
            out.append(NOT_COMPUTED)
            continue
        out.append(float(v) if isinstance(v, int) and not isinstance(v, bool) else v)
    return out


def libreoffice_runner(path: str, cells: list, timeout: float) -> list:
    """LibreOffice's values of ``cells`` in its recalculated copy, read by position: the
    cells an array formula fills are plain values there, not formulas."""
    import openpyxl
    from workbook_gen.engines.libreoffice import cell_value, recalculate
    wanted: dict[str, dict[tuple[int, int], int]] = {}
    for i, (sheet, row, col, _, _) in enumerate(cells):
        wanted.setdefault(sheet, {})[(row, col)] = i
    out: list = [NOT_COMPUTED] * len(cells)
    with tempfile.TemporaryDirectory(prefix="workbook-gen-peers-lo-") as tmp:
        book = openpyxl.load_workbook(recalculate(path, tmp, timeout=timeout),
                                      read_only=True, data_only=True)
        book._date_formats, book._timedelta_formats = set(), set()  # numbers stay numbers
        try:
            for ws in book.worksheets:
                here = wanted.get(ws.title)
                if not here:
                    continue
                last = max(r for r, _ in here)
                for row in ws.iter_rows(max_row=last):
                    for cell in row:
                        i = here.get((getattr(cell, "row", None), getattr(cell, "column", None)))
                        if i is not None:
                            out[i] = encode(cell_value(cell.value, cell.data_type, book.epoch))
        finally:
            book.close()
    return out


def child_main(engine: str, path: str, cells_file: str | None, timeout: float) -> None:
    if engine == "cells":
        result = cells_runner(path)
    else:
        given = json.loads(Path(cells_file).read_text(encoding="utf-8"))
        cells = given["cells"]
        if engine == "libreoffice":
            result = libreoffice_runner(path, cells, timeout)
        elif engine == "formualizer":
            result = formualizer_runner(path, cells, given["date1904"])
        else:
            result = {"ours": ours_runner, "ironcalc": ironcalc_runner}[engine](path, cells)
    sys.stdout.write(json.dumps(result) + "\n")


def run_child(engine: str, path: Path, cells_file: Path | None, timeout: float):
    """(result, seconds, note): the child's JSON, or None with why."""
    cmd = [sys.executable, __file__, "--child", engine, str(path)]
    if cells_file is not None:
        cmd += ["--cells-file", str(cells_file)]
    cmd += ["--timeout", str(timeout)]
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            stdin=subprocess.DEVNULL, start_new_session=True)
    try:
        out, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        try:  # the whole group: LibreOffice's soffice.bin too
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        proc.communicate()
        return None, time.perf_counter() - start, f"timed out after {timeout:g} s"
    seconds = time.perf_counter() - start
    lines = out.strip().splitlines()
    if proc.returncode != 0 or not lines:
        tail = (err or out).strip().splitlines()
        return None, seconds, f"exit {proc.returncode}: {tail[-1][:160] if tail else ''}"
    return json.loads(lines[-1]), seconds, ""


# ---------------------------------------------------------------- the run

def measure_file(path: Path, engines, timeout: float, tmp: Path) -> dict:
    """{"cells", "volatile", "no_value", engine: {"r", "c", "n", "seconds", "note"}}."""
    found, seconds, note = run_child("cells", path, None, timeout)
    if found is None:
        return {"file": path.name, "cells": 0, "note": f"cells not read: {note}"}
    cells = found["cells"]
    cells_file = tmp / "cells.json"
    cells_file.write_text(json.dumps(found), encoding="utf-8")
    row = {"file": path.name, "cells": len(cells), "volatile": found["volatile"],
           "no_value": found["no_value"]}
    for engine in engines:
        counts = {"r": 0, "c": 0, "n": 0}
        values, seconds, note = run_child(engine, path, cells_file, timeout) if cells else \
            ([], 0.0, "")
        if values is None:
            counts["n"] = len(cells)
        else:
            for cell, value in zip(cells, values):
                counts["r" if value == "=" else verdict(cell[4], value)] += 1
        row[engine] = {**counts, "seconds": round(seconds, 3), "note": note}
    return row


def totals(rows: list[dict], engines) -> dict:
    out = {"files": len(rows), "cells": sum(r["cells"] for r in rows),
           "volatile": sum(r.get("volatile", 0) for r in rows),
           "no_value": sum(r.get("no_value", 0) for r in rows)}
    for e in engines:
        out[e] = {k: sum(r[e][k] for r in rows if e in r) for k in ("r", "c", "n")}
        out[e]["seconds"] = round(sum(r[e]["seconds"] for r in rows if e in r), 1)
        out[e]["failed_files"] = sum(1 for r in rows if e in r and r[e]["note"])
    return out


def print_table(total: dict, engines) -> None:
    print(f"{total['files']} files, {total['cells']:,} non-volatile formula cells with a "
          f"cached value ({total['volatile']:,} volatile and {total['no_value']:,} without a "
          "cached value left out)")
    print()
    print("| engine | reproduces | contradicts | not computed | files failed | seconds |")
    print("|---|---|---|---|---|---|")
    for e in sorted(engines, key=lambda e: -total[e]["r"]):
        t = total[e]
        print(f"| {LABEL[e]} | {t['r']:,} | {t['c']:,} | {t['n']:,} | {t['failed_files']} | "
              f"{t['seconds']:.0f} |")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="*", type=Path, help=f"workbooks (default {CORPUS})")
    parser.add_argument("--limit", type=int, help="the first N workbooks only")
    parser.add_argument("--timeout", type=float, default=180, help="per engine and file [s]")
    parser.add_argument("--engines", default=",".join(ENGINES),
                        help=f"comma-separated, of {','.join(ENGINES)}")
    parser.add_argument("--json", metavar="FILE", help="also write the figures per file")
    parser.add_argument("--child", help=argparse.SUPPRESS)
    parser.add_argument("--cells-file", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        child_main(args.child, str(args.files[0]), args.cells_file, args.timeout)
        return 0
    engines = [e for e in args.engines.split(",") if e]
    unknown = set(engines) - set(ENGINES)
    if unknown:
        parser.error(f"unknown engines {sorted(unknown)}")
    benchinfo.check_writable(args.json)
    record = benchinfo.Record()
    paths = args.files or [CORPUS]
    files = [f for p in paths for f in (sorted(p.glob("*.xls[xm]")) if p.is_dir() else [p])]
    files = files[:args.limit] if args.limit else files
    info = benchinfo.machine()
    print(f"machine: {info['cpu']}, {info['cores']} cores, Python {info['python']}, "
          f"LibreOffice {info['libreoffice']}, formualizer {_version('formualizer')}, "
          f"IronCalc {_version('ironcalc')}; timeout {args.timeout:g} s per engine and file")
    rows = []
    with tempfile.TemporaryDirectory(prefix="workbook-gen-peers-") as tmp:
        for i, f in enumerate(files, 1):
            row = measure_file(f, engines, args.timeout, Path(tmp))
            rows.append(row)
            if args.json:  # after every file: a run cut short keeps what it measured
                record.write(args.json, {"engines": engines, "timeout": args.timeout,
                                         "files_planned": len(files),
                                         "totals": totals(rows, engines), "files": rows})
            print(f"  [{i}/{len(files)}] {f.name[:48]:<48} {row['cells']:>6} cells  "
                  + "  ".join(f"{e} {row[e]['r']}/{row[e]['c']}/{row[e]['n']}"
                              for e in engines if e in row)
                  + "".join(f"  ({e}: {row[e]['note']})" for e in engines
                            if e in row and row[e]['note'])
                  + (f"  ({row['note']})" if row.get("note") else ""),
                  file=sys.stderr, flush=True)
    total = totals(rows, engines)
    print_table(total, engines)
    if args.json:
        record.write(args.json, {"engines": engines, "timeout": args.timeout,
                                 "files_planned": len(files), "totals": total, "files": rows})
    return 0


def _version(name: str) -> str:
    from importlib import metadata
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "not installed"


if __name__ == "__main__":
    sys.exit(main())
