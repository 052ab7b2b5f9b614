"""Rewrite the README's measured figures from the committed tradeoff output, so the two
cannot drift apart.

    python scripts/readme_figures.py            # rewrite the marked blocks of README.md
    python scripts/readme_figures.py --check    # exit 1 if README.md is not up to date
    python scripts/readme_figures.py --measure  # re-measure (minutes), then rewrite

The data are the JSON objects ``workbook-gen tradeoff SCENE --json`` prints, one file per
scene under docs/tradeoff/ (``--measure`` writes them).  A block of README.md between
``<!-- figures: tradeoff NAME -->`` and ``<!-- /figures -->`` is the tables of NAME.json;
``<!-- figures: runtime -->`` holds the whole-run times.  Everything else in the README is
left as written.  tests/test_readme_figures.py checks the README equals what this script
makes from the committed data.
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "docs" / "tradeoff"
README = ROOT / "README.md"
# name -> (scene file, options replaced in a copy: the five-bar copy uses Newton steps)
SCENES = {
    "sewing_machine": ("templates/sewing_machine.toml", {}),
    "actuator_linkage": ("templates/actuator_linkage.toml", {}),
    "five_bar": ("templates/five_bar.toml", {"method": '"newton"', "iterations": "6"}),
}
LABELS = {"sewing_machine": "sewing machine", "actuator_linkage": "actuator",
          "five_bar": "five-bar"}
BLOCK = re.compile(r"(<!-- figures: (tradeoff (\w+)|runtime|audit-json) -->\n)(.*?)"
                   r"(<!-- /figures -->)", re.S)


def _e(x) -> str:
    return "n/a" if x is None else f"{x:.1e}"


def _count(x) -> str:
    return "" if x is None else f"{x:,}"


def _bytes(x) -> str:
    if x is None:
        return ""
    return f"{x / 1e6:.1f} M" if x >= 1e6 else f"{x / 1e3:.0f} k"


def _secs(x) -> str:
    return f"{x:.2f}"


def _rows(data, dimension):
    return [r for r in data["rows"] if r["dimension"] == dimension]


def tradeoff_block(data: dict) -> str:
    """The tables of one scene's tradeoff run."""
    steps = _rows(data, "step")
    deriv = {r["setting"]: r for r in _rows(data, "derivative")}
    unit = f" ({steps[0]['setting'].split()[-1]})" if steps else ""
    lines = [f"| step{unit} | extremes error | seconds | cells | bytes | central diff. | "
             "forward diff. |", "|---|---|---|---|---|---|---|"]
    for r in steps:
        step = r["setting"].split()[0]
        central = deriv.get(f"central, {r['setting']}", {}).get("max_error")
        forward = deriv.get(f"forward, {r['setting']}", {}).get("max_error")
        lines.append(f"| {step} | {_e(r['max_error'])} | {_secs(r['seconds'])} | "
                     f"{_count(r['cells'])} | {_bytes(r['bytes'])} | {_e(central)} | "
                     f"{_e(forward)} |")
    methods = [r for r in _rows(data, "method") if r["max_error"] is not None]
    if methods:
        lines += ["", "| method | error | seconds | cells | note |", "|---|---|---|---|---|"]
        for r in methods:
            lines.append(f"| {r['setting']} | {_e(r['max_error'])} | {_secs(r['seconds'])} | "
                         f"{_count(r['cells'])} | {r['note']} |")
    analytic = [r["max_error"] for r in deriv.values()
                if r["setting"].startswith("analytic") and r["max_error"] is not None]
    precision = {r["setting"]: r["max_error"] for r in _rows(data, "precision")}
    notes = []
    if analytic:
        notes.append(f"Analytic velocity and acceleration columns: at most {_e(max(analytic))} "
                     "at every step.")
    table = precision.get("float64, whole table")
    near = precision.get("float64, near the extremes")
    if table is not None:
        notes.append(f"Float64 against 50 digits: {_e(table)} over the table, {_e(near)} "
                     "next to the extremes.")
    if not methods:
        notes.append("No iterative method (n/a).")
    notes.append(f"Whole run: {data['seconds']:.0f} s.")
    return "\n".join(lines) + "\n\n" + " ".join(notes) + "\n"


def runtime_block(all_data: dict[str, dict]) -> str:
    parts = [f"{all_data[name]['seconds']:.0f} s ({LABELS[name]})" for name in SCENES
             if name in all_data]
    return "A whole run took " + ", ".join(parts) + " here, under load (see below).\n"


def audit_json_block() -> str:
    """The keys ``audit --json`` prints, from a real audit of a workbook that disagrees
    in one cell (so that a mismatch's keys show too)."""
    import tempfile
    import zipfile

    from workbook_gen import audit, load_scene, write_workbook
    with tempfile.TemporaryDirectory() as tmp:
        path = write_workbook(load_scene(ROOT / "templates" / "slider_crank.toml"), tmp)
        bad = Path(tmp) / "edited.xlsx"
        with zipfile.ZipFile(path) as zin, zipfile.ZipFile(bad, "w") as zout:
            for item in zin.infolist():
                data = zin.read(item.filename)
                if item.filename == "xl/worksheets/sheet1.xml":  # one cached value changed
                    data = re.sub(rb'(<c r="H3"[^>]*><f>[^<]*</f><v>)([^<]*)',
                                  rb"\g<1>12345", data, count=1)
                zout.writestr(item, data)
        report = audit(bad).to_json()
    keys = ", ".join(f"`{k}`" for k in report)
    mismatch = ", ".join(f"`{k}`" for k in report["mismatches"][0]) if report["mismatches"] \
        else "none"
    return f"{keys}; each of `mismatches` has {mismatch}.\n"


def load() -> dict[str, dict]:
    return {path.stem: json.loads(path.read_text(encoding="utf-8"))
            for path in sorted(DATA.glob("*.json"))}


def render(text: str, all_data: dict[str, dict]) -> str:
    """``text`` with every marked block rewritten from ``all_data``."""
    def block(match: re.Match) -> str:
        name = match.group(3)
        if match.group(2) == "audit-json":
            body = audit_json_block()
        elif name is None:
            body = runtime_block(all_data)
        elif name in all_data:
            body = tradeoff_block(all_data[name])
        else:
            raise SystemExit(f"README block names {name!r}, which has no {DATA}/{name}.json")
        return match.group(1) + body + match.group(5)
    return BLOCK.sub(block, text)


def measure() -> None:
    DATA.mkdir(parents=True, exist_ok=True)
    for name, (scene, options) in SCENES.items():
        text = (ROOT / scene).read_text(encoding="utf-8")
        for key, value in options.items():  # a copy of the scene with those options
            text = re.sub(rf"^{key} = .*$", f"{key} = {value}", text, count=1, flags=re.M)
        copy = DATA / f".{name}.toml"
        copy.write_text(text, encoding="utf-8")
        try:
            out = subprocess.run([sys.executable, "-m", "workbook_gen.cli", "tradeoff",
                                  str(copy), "--json"], check=True, capture_output=True,
                                 text=True, cwd=ROOT).stdout
        finally:
            copy.unlink(missing_ok=True)
        data = json.loads(out)
        data["scene"] = scene + "".join(f" ({k} = {v})" for k, v in options.items())
        (DATA / f"{name}.json").write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--measure", action="store_true")
    args = parser.parse_args()
    if args.measure:
        measure()
    text = README.read_text(encoding="utf-8")
    new = render(text, load())
    if args.check:
        if new != text:
            print("README.md is not up to date: run python scripts/readme_figures.py",
                  file=sys.stderr)
            return 1
        return 0
    README.write_text(new, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
