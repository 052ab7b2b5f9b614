"""Per template scene: columns written, formula cells, worst error against the independent
reference model and against LibreOffice recalculating the file, audit verdict.

    python bench/templates.py            # every scene in templates/
"""

from __future__ import annotations

import sys
import tempfile
from collections import defaultdict
from pathlib import Path

from workbook_gen import audit
from workbook_gen.engines.libreoffice import read_formula_values, recalculated_values
from workbook_gen.scene import load_scene
from workbook_gen.workbook import write_workbook


def libreoffice_worst(path: Path) -> float:
    """Largest |ours - LibreOffice| over the column's magnitude, numeric formula cells.
    A column that vanishes to rounding (a balanced shaking force) is measured against
    1e-6 of the sheet's largest value instead of its own noise."""
    ours, theirs = read_formula_values(path), recalculated_values(path)
    worst = 0.0
    for sheet, cells in ours.items():
        scale: dict[str, float] = defaultdict(float)
        for ref, v in cells.items():
            if isinstance(v, float):
                col = ref.rstrip("0123456789")
                scale[col] = max(scale[col], abs(v), 1.0 if sheet == "Checks" else 0.0)
        floor = 1e-6 * max(scale.values(), default=0.0)
        for col in scale:
            scale[col] = max(scale[col], floor)
        for ref, v in cells.items():
            w = theirs[sheet].get(ref)
            if isinstance(v, float) and isinstance(w, float) and sheet != "Summary":
                col = ref.rstrip("0123456789")
                worst = max(worst, abs(v - w) / scale[col] if scale[col] else 0.0)
    return worst


def main(paths: list[str]) -> None:
    print(f"{'scene':<28}{'columns':>8}{'formula cells':>15}{'vs reference':>14}"
          f"{'vs LibreOffice':>16}  audit")
    for scene_path in paths:
        scene = load_scene(scene_path)
        with tempfile.TemporaryDirectory() as out:
            path = write_workbook(scene, out)
            report = audit(path)
            worst_ref = max(report.reference.values(), default=float("nan"))
            worst_lo = libreoffice_worst(path)
            from workbook_gen.pruning import select
            columns = len(select(scene.template, scene.outputs).columns) + 2
            print(f"{Path(scene_path).stem:<28}{columns:>8}{report.formula_cells:>15,}"
                  f"{worst_ref:>14.1e}{worst_lo:>16.1e}  {'ok' if report.ok else 'FAILED'}")


if __name__ == "__main__":
    main(sys.argv[1:] or sorted(str(p) for p in Path("templates").glob("*.toml")))
