"""Render one sheet of a workbook (by default the Charts sheet) to PNG with LibreOffice.

    python scripts/render_chart.py outputs/sewing_machine.xlsx docs/sewing_machine_charts.png
    python scripts/render_chart.py out/sewing_machine_tradeoff.xlsx docs/x.png --sheet Charts

The script copies the workbook with every other sheet hidden and the sheet scaled to fit
one page (the given file is left as it is: its own page setup prints the charts over
several pages), has LibreOffice export the copy to PDF and turns that page into a PNG
with pdftoppm (Debian's poppler-utils).
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


ONE_PAGE = '<pageSetup orientation="landscape" fitToWidth="1" fitToHeight="1"/>'


def fit_one_page(xml: str) -> str:
    """A worksheet's XML scaled to print on one page (the whole sheet in the PNG)."""
    xml = re.sub(r"<pageSetup [^>]*/>", "", xml)
    xml = re.sub(r"<sheetPr>(.*?)</sheetPr>|<sheetPr/>", "", xml, flags=re.S)
    xml = re.sub(r"(<worksheet [^>]*>)", r'\1<sheetPr><pageSetUpPr fitToPage="1"/></sheetPr>',
                 xml, count=1)
    if "<pageMargins " in xml:
        return re.sub(r"(<pageMargins [^>]*/>)", r"\1" + ONE_PAGE, xml, count=1)
    return re.sub(r"(<drawing |</worksheet>)", ONE_PAGE + r"\1", xml, count=1)


def single_sheet_copy(src: Path, dst: Path, sheet: str) -> None:
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        rels = zin.read("xl/_rels/workbook.xml.rels").decode()
        book = zin.read("xl/workbook.xml").decode()
        rid = re.search(rf'<sheet name="{re.escape(sheet)}" [^>]*r:id="([^"]+)"', book)
        target = re.search(rf'Id="{rid.group(1)}"[^>]*Target="([^"]+)"', rels) if rid else None
        part = "xl/" + target.group(1).lstrip("/").removeprefix("xl/") if target else None
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
                if item.filename == part:
                    data = fit_one_page(data.decode()).encode()
            zout.writestr(item, data)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("workbook")
    parser.add_argument("png")
    parser.add_argument("dpi", nargs="?", default="90")
    parser.add_argument("--sheet", default="Charts")
    parser.add_argument("--crop", metavar="X,Y,W,H",
                        help="only this part of the page, in fractions of its width and "
                             "height (0.05,0.08,0.5,0.3: the top left charts)")
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
        crop = []
        if args.crop:  # pdftoppm crops in pixels: an A4 landscape page at this dpi
            x, y, w, h = (float(v) for v in args.crop.split(","))
            width, height = 11.69 * float(args.dpi), 8.27 * float(args.dpi)
            crop = ["-x", str(round(x * width)), "-y", str(round(y * height)),
                    "-W", str(round(w * width)), "-H", str(round(h * height))]
        subprocess.run(["pdftoppm", "-r", args.dpi, "-png", "-f", "1", "-l", "1", "-singlefile",
                        *crop, str(Path(tmp) / "sheet.pdf"), str(Path(tmp) / "page")],
                       check=True)
        shutil.copyfile(Path(tmp) / "page.png", args.png)
    print(args.png)


if __name__ == "__main__":
    main()
