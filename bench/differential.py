"""The differential test against LibreOffice, at scale: random well-typed formulas
(tests/differential.py) recalculated by LibreOffice headless in one run and compared with
the evaluator's LibreOffice dialect; prints each difference, grouped by the outermost
function, and the count of differences the generator's KNOWN table explains.

    python bench/differential.py [--cases 5000] [--seed S] [--timeout 900] [--show 5]

The suite runs a small seeded slice of the same (tests/formula/functions/test_dialect.py).
"""

from __future__ import annotations

import argparse
import collections
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT))
import differential  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=5000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--timeout", type=float, default=900, help="LibreOffice's run [s]")
    parser.add_argument("--show", type=int, default=5, help="differences shown per function")
    args = parser.parse_args()
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="workbook-gen-differential-") as tmp:
        formulas, theirs, ours, parts = differential.run(Path(tmp), args.seed, args.cases,
                                                         timeout=args.timeout)
        new, known = differential.compare(formulas, theirs, ours, parts)
    groups: dict[str, list] = collections.defaultdict(list)
    for d in new:
        groups[d.functions[0]].append(d)
    for name, found in sorted(groups.items(), key=lambda kv: -len(kv[1])):
        print(f"{name}: {len(found)}")
        for d in found[:args.show]:
            print(f"  Cases!A{d.row} ={d.formula}\n      LibreOffice {d.libreoffice!r}, "
                  f"ours {d.ours!r}")
    by_rule = collections.Counter(k.name for d in known for k in differential.KNOWN
                                  if k.explains(d))
    print(f"seed {args.seed}: {len(formulas)} cases, {len(new)} differ, {len(known)} more "
          f"differ as the KNOWN table explains ("
          + ", ".join(f"{name}: {n}" for name, n in by_rule.items())
          + f"); {time.perf_counter() - start:.0f} s")
    return 1 if new else 0


if __name__ == "__main__":
    sys.exit(main())
