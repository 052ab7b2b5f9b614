"""Count the audit's findings per kind on the real-world corpus (false-alarm survey).

For every workbook of ../shared/corpus/xlsx: formula cells, the findings of each kind
(docs/audit.md, Findings and the file) and the seconds the findings took; then the totals.
A file the audit refuses is listed with its reason. Inspect samples with
``workbook-gen audit FILE --verbose``.

    python bench/findings.py [CORPUS_DIR | FILE...]
"""

from __future__ import annotations

import collections
import sys
from pathlib import Path

from workbook_gen.auditor import audit
from workbook_gen.auditor.findings import KINDS

CORPUS = Path(__file__).resolve().parents[2] / "shared" / "corpus" / "xlsx"


def main(argv: list[str]) -> int:
    paths = [Path(a) for a in argv] or [CORPUS]
    files = [f for p in paths for f in (sorted(p.glob("*.xls[xm]")) if p.is_dir() else [p])]
    if not files:
        print(f"no workbooks under {', '.join(map(str, paths))}", file=sys.stderr)
        return 2
    total: collections.Counter = collections.Counter()
    refused = 0
    for f in files:
        try:
            report = audit(f)
        except Exception as exc:  # a survey: a refusal or a crash is noted, the rest goes on
            refused += 1
            print(f"{f.name[:50]:<50} refused: {type(exc).__name__}: {str(exc)[:90]}")
            continue
        counts = collections.Counter(x.kind for x in report.findings if x.kind in KINDS)
        total += counts
        print(f"{f.name[:50]:<50} {report.formula_cells:>6} formulas "
              f"{report.timings.get('findings', 0.0):5.2f} s  "
              + " ".join(f"{k}={v}" for k, v in sorted(counts.items())), flush=True)
    print(f"{len(files)} files, {refused} refused; findings: "
          + ", ".join(f"{k} {total[k]}" for k in KINDS))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
