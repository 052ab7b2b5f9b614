"""Render one sheet of a workbook (by default the Charts sheet) to PNG with LibreOffice.

    python scripts/render_chart.py outputs/sewing_machine.xlsx docs/sewing_machine_charts.png
    python scripts/render_chart.py out/sewing_machine_tradeoff.xlsx docs/x.png --sheet Charts

The script copies the workbook with every other sheet hidden (the given file is left as
it is), has LibreOffice export the copy to PDF and turns the first page into a PNG with
pdftoppm (Debian's poppler-utils).
"""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

from workbook_gen.engines.libreoffice import find_soffice


def single_sheet_copy(src: Path, dst: Path, sheet: str) -> None:
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            data = zin.read(item.filename)
            if item.filename == "xl/workbook.xml":
                text = data.decode()
                names = re.findall(r'<sheet name="([^"]+)"', text)
                if sheet not in names:
                    sys.exit(f"{src}: no sheet named {sheet!r} (sheets: {', '.join(names)})")
                text = re.sub(r' activeTab="\d+"', "", text)
                text = text.replace("<workbookView ",
                                    f'<workbookView activeTab="{names.index(sheet)}" ', 1)
                for name in names:
                    element = re.search(f'<sheet name="{re.escape(name)}" [^>]*>', text)
                    if name != sheet and element and "state=" not in element.group(0):
                        text = text.replace(f'<sheet name="{name}" ',
                                            f'<sheet name="{name}" state="hidden" ')
                data = text.encode()
            elif item.filename.startswith("xl/worksheets/sheet"):
                data = data.replace(b' tabSelected="1"', b"")
            zout.writestr(item, data)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("workbook")
    parser.add_argument("png")
    parser.add_argument("dpi", nargs="?", default="90")
    parser.add_argument("--sheet", default="Charts")
    args = parser.parse_args()
    soffice = find_soffice()
    if soffice is None or shutil.which("pdftoppm") is None:
        sys.exit("needs LibreOffice and pdftoppm: apt-get install libreoffice-calc poppler-utils")
    with tempfile.TemporaryDirectory() as tmp:
        copy = Path(tmp) / "sheet.xlsx"
        single_sheet_copy(Path(args.workbook), copy, args.sheet)
        subprocess.run([soffice, f"-env:UserInstallation=file://{tmp}/profile", "--headless",
                        "--convert-to", "pdf", "--outdir", tmp, str(copy)],
                       check=True, capture_output=True, timeout=300)
        subprocess.run(["pdftoppm", "-r", args.dpi, "-png", "-f", "1", "-l", "1", "-singlefile",
                        str(Path(tmp) / "sheet.pdf"), str(Path(tmp) / "page")], check=True)
        shutil.copyfile(Path(tmp) / "page.png", args.png)
    print(args.png)


if __name__ == "__main__":
    main()
