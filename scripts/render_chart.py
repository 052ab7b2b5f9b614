"""Render the Charts sheet of a generated workbook to PNG with LibreOffice headless.

    python scripts/render_chart.py outputs/sewing_machine.xlsx docs/sewing_machine_charts.png

The script copies the workbook with every sheet but Charts hidden (the
generated file is left as it is), has LibreOffice export the copy to PDF and
turns the first page into a PNG with pdftoppm (Debian's poppler-utils).
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

from workbook_gen.engines.libreoffice import find_soffice

HIDE = ("Table", "Parameters", "Checks", "Summary", "About")


def charts_only_copy(src: Path, dst: Path) -> None:
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            data = zin.read(item.filename)
            if item.filename == "xl/workbook.xml":
                text = data.decode().replace("<workbookView ", '<workbookView activeTab="4" ', 1)
                for name in HIDE:
                    text = text.replace(f'<sheet name="{name}" ', f'<sheet name="{name}" state="hidden" ')
                data = text.encode()
            elif item.filename.startswith("xl/worksheets/sheet"):
                data = data.replace(b' tabSelected="1"', b"")
            zout.writestr(item, data)


def main(src: str, png: str, dpi: str = "90") -> None:
    soffice = find_soffice()
    if soffice is None or shutil.which("pdftoppm") is None:
        sys.exit("needs LibreOffice and pdftoppm: apt-get install libreoffice-calc poppler-utils")
    with tempfile.TemporaryDirectory() as tmp:
        copy = Path(tmp) / "charts.xlsx"
        charts_only_copy(Path(src), copy)
        subprocess.run([soffice, f"-env:UserInstallation=file://{tmp}/profile", "--headless",
                        "--convert-to", "pdf", "--outdir", tmp, str(copy)],
                       check=True, capture_output=True, timeout=300)
        subprocess.run(["pdftoppm", "-r", dpi, "-png", "-f", "1", "-l", "1", "-singlefile",
                        str(Path(tmp) / "charts.pdf"), str(Path(tmp) / "page")], check=True)
        shutil.copyfile(Path(tmp) / "page.png", png)
    print(png)


if __name__ == "__main__":
    main(*sys.argv[1:4])
