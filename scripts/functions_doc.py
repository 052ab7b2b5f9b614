"""Write docs/functions.md from the function registry (``--check``: exit 1 if it is stale)."""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from workbook_gen.formula.functions.catalog import markdown  # noqa: E402


def main(argv: list[str]) -> int:
    target = ROOT / "docs" / "functions.md"
    text = markdown(ROOT)
    if "--check" in argv:
        current = target.read_text() if target.exists() else ""
        if current != text:
            print("docs/functions.md is stale: run python scripts/functions_doc.py",
                  file=sys.stderr)
            return 1
        return 0
    target.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
