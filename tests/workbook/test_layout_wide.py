"""Printing wide sheets (issue 22 item 17): the Table and the Checks print at a fixed,
readable scale across as many pages as they take, the header row and the input column
repeated, and only what an engineer reads (not the intermediate columns nor the Checks'
terms); the Checks' headers are not cut.

The page setup is read back from the xlsx XML and openpyxl; which columns are helpers
comes from the templates' quantities (``output=False``) and the Checks' header names, not
from the printing code.  One LibreOffice run exports the five-bar, four-bar and
sewing-machine workbooks to PDF; the font size of every run of text is read from the
PDF's content streams (the operand of ``Tf``: LibreOffice writes text unscaled, at the
size it prints) and the pages' text from pdftotext.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import zipfile
import zlib

import openpyxl
import pytest
from openpyxl.utils import column_index_from_string, get_column_letter

from workbook_gen.scene import load_scene
from workbook_gen.tabulate import evaluate
from workbook_gen.workbook import write_workbook

TEMPLATES = ("five_bar", "four_bar", "sewing_machine")
MIN_PT = 8.0  # smallest text size in print that an engineer reads without a lens


@pytest.fixture(scope="module")
def books(tmp_path_factory):
    """Each template's workbook and its evaluation (the quantities' output flags)."""
    out = tmp_path_factory.mktemp("wide")
    found = {}
    for name in TEMPLATES:
        scene = load_scene(f"templates/{name}.toml")
        found[name] = (write_workbook(scene, out), evaluate(scene))
    return found


def _part(path, name: str) -> str:
    with zipfile.ZipFile(path) as z:
        return z.read(name).decode()


def _defined(path, name: str, sheet_index: int) -> str | None:
    found = re.search(rf'<definedName name="{re.escape(name)}" localSheetId="{sheet_index}">'
                      r"([^<]*)</definedName>", _part(path, "xl/workbook.xml"))
    return found and found.group(1)


def _area_columns(area: str, sheet: str) -> set[int]:
    """1-based columns of a print area such as ``Table!$B$1:$C$38,Table!$J$1:$K$38``."""
    cols: set[int] = set()
    for part in area.split(","):
        m = re.fullmatch(rf"{sheet}!\$([A-Z]+)\$1:\$([A-Z]+)\$(\d+)", part)
        assert m, part
        cols.update(range(column_index_from_string(m.group(1)),
                          column_index_from_string(m.group(2)) + 1))
    return cols


def _headers(path, sheet: str, row: int) -> list[str]:
    ws = openpyxl.load_workbook(path, read_only=True)[sheet]
    return [c.value for c in next(ws.iter_rows(min_row=row, max_row=row))]


@pytest.mark.parametrize("name", TEMPLATES)
def test_table_prints_at_a_readable_scale_its_outputs_with_header_and_input_repeated(
        books, name):
    path, result = books[name]
    setup = re.search(r"<pageSetup [^>]*/>", _part(path, "xl/worksheets/sheet1.xml")).group(0)
    assert 'orientation="landscape"' in setup and 'paperSize="9"' in setup
    scale = int(re.search(r'scale="(\d+)"', setup).group(1))
    assert scale * 11 / 100 >= MIN_PT  # 11 pt text (Calibri, XlsxWriter's default)
    assert "fitTo" not in _part(path, "xl/worksheets/sheet1.xml")  # a fit would shrink it
    assert _defined(path, "_xlnm.Print_Titles", 0) == "Table!$A:$A,Table!$1:$1"
    # the print area: the input (as the title column), every output and the status; no
    # intermediate quantity
    printed = _area_columns(_defined(path, "_xlnm.Print_Area", 0), "Table") | {1}
    columns = result.model.columns
    outputs = {i for i, q in enumerate(columns, start=2) if q.output}
    status = len(columns) + 2
    assert printed == outputs | {1, status}
    assert any(not q.output for q in columns)  # (each of the three has helpers)
    headers = _headers(path, "Table", 1)
    assert headers[status - 1] == "status"
    assert all(headers[i - 1].split(" [")[0] in result.scene.outputs for i in outputs)


@pytest.mark.parametrize("name", TEMPLATES)
def test_checks_print_residuals_and_flags_never_the_terms(books, name):
    path, result = books[name]
    sheet = _part(path, "xl/worksheets/sheet3.xml")
    assert re.search(r'<pageSetup [^>]*scale="80"[^>]*orientation="landscape"', sheet)
    assert _defined(path, "_xlnm.Print_Titles", 2) == "Checks!$A:$A,Checks!$7:$7"
    area = _defined(path, "_xlnm.Print_Area", 2)
    headers = _headers(path, "Checks", 7)
    names = [c.name for c in result.model.checks]
    last = len(names) + 3  # input, residuals, "cannot assemble", "flagged"
    assert headers[1:last] == names + ["cannot assemble", "flagged"]
    assert area == f"Checks!$A$1:${get_column_letter(last)}${7 + result.rows}"
    if name != "five_bar":  # the five-bar's residuals share no term
        assert headers[last].startswith("term ")


def _lines(text: str, width: float) -> int:
    """The lines ``text`` needs in a column ``width`` characters wide, at one character
    (a digit's width) per unit, its spaces left out: fewer than it takes wrapped at
    words, about as many as most letters (narrower than digits) take."""
    return max(1, -(-len(text.replace(" ", "")) // int(width)))


def _width(ws, col: int) -> float:
    """Column ``col``'s width (1-based), from the <col> ranges openpyxl read."""
    for dim in ws.column_dimensions.values():
        if dim.min <= col <= dim.max and dim.width:
            return dim.width
    return 8.43  # Excel's default


@pytest.mark.parametrize("name", TEMPLATES)
def test_checks_headers_are_whole_on_screen_and_in_print(books, name):
    """Each header (row 7) fits its column's width or wraps in a row tall enough; each
    residual's description (row 3) has the rows it needs at its column's width."""
    path, result = books[name]
    ws = openpyxl.load_workbook(path)["Checks"]
    checks = result.model.checks
    line = 15.0  # points: a line of 11 pt text
    header_height = ws.row_dimensions[7].height or line
    description_height = ws.row_dimensions[3].height or line
    for col in range(2, len(checks) + 4):
        letter = get_column_letter(col)
        width = _width(ws, col)
        head = ws[f"{letter}7"].value
        words = head.split()
        assert max(map(len, words)) <= width, (head, width)  # no word cut in two
        assert header_height >= line * _lines(head, width), (head, width)
        if col <= len(checks) + 1:
            text = ws[f"{letter}3"].value
            assert text == checks[col - 2].description
            assert description_height >= line * _lines(text, width), (text, width)
    # the note above (C1) wraps within cells merged across the printed columns
    assert any(str(r).startswith("C1:") for r in ws.merged_cells.ranges)
    assert ws["C1"].alignment.wrap_text


# ----------------------------------------------------------------------------- the PDF

def _page_font_sizes(pdf: bytes) -> list[list[float]]:
    """Each page's text sizes (the operands of Tf), in page order."""
    objects = {int(m.group(1)): m.group(2)
               for m in re.finditer(rb"(\d+) 0 obj(.*?)endobj", pdf, re.S)}

    def stream(number: int) -> bytes:
        raw = re.search(rb"stream\r?\n(.*?)endstream", objects[number], re.S).group(1)
        return zlib.decompress(raw)

    def pages(number: int):
        body = objects[number]
        if re.search(rb"/Type\s*/Pages\b", body):
            kids = re.search(rb"/Kids\s*\[(.*?)\]", body, re.S).group(1)
            for kid in re.findall(rb"(\d+) 0 R", kids):
                yield from pages(int(kid))
        else:
            yield number

    root = next(n for n, body in objects.items()
                if re.search(rb"/Type\s*/Pages\b", body) and b"/Parent" not in body)
    sizes = []
    for page in pages(root):
        contents = re.search(rb"/Contents\s+(\d+) 0 R", objects[page])
        text = stream(int(contents.group(1))) if contents else b""
        sizes.append([float(v) for v in re.findall(rb"([\d.]+) Tf\b", text)])
    return sizes


@pytest.fixture(scope="module")
def pdfs(books, tmp_path_factory, libreoffice):
    """Each workbook's pages: (text, text sizes), after one LibreOffice run."""
    out = tmp_path_factory.mktemp("wide_pdf")
    copies = []
    for name, (path, _) in books.items():
        copies.append(out / f"{name}.xlsx")
        shutil.copyfile(path, copies[-1])
    subprocess.run([libreoffice, f"-env:UserInstallation={(out / 'profile').as_uri()}",
                    "--headless", "--norestore", "--convert-to", "pdf", "--outdir", str(out),
                    *map(str, copies)], check=True, capture_output=True, timeout=600)
    pdftotext = shutil.which("pdftotext")
    if pdftotext is None:
        pytest.fail("pdftotext (poppler-utils) is required: run bash "
                    "scripts/install-test-deps.sh", pytrace=False)
    found = {}
    for copy in copies:
        pdf = copy.with_suffix(".pdf")
        text = subprocess.run([pdftotext, "-layout", str(pdf), "-"], check=True,
                              capture_output=True, text=True).stdout.split("\f")[:-1]
        sizes = _page_font_sizes(pdf.read_bytes())
        count = len(re.findall(rb"/Type\s*/Page\b", pdf.read_bytes()))
        assert len(text) == len(sizes) == count
        found[copy.stem] = list(zip(text, sizes))
    return found


def _sheet_pages(pages, sheet: str):
    """The pages whose footer names ``sheet`` (its last line: the sheet, the page)."""
    return [(t, s) for t, s in pages
            if re.search(rf"^\s*{sheet}\s+page \d+\s*$", t.rstrip().rsplit("\n", 1)[-1])]


@pytest.mark.parametrize("name", TEMPLATES)
def test_pdf_prints_the_table_and_checks_readable_each_output_once(books, pdfs, name):
    path, result = books[name]
    pages = pdfs[name]
    table, checks = _sheet_pages(pages, "Table"), _sheet_pages(pages, "Checks")
    assert table and checks
    for text, sizes in table + checks:  # no page shrunk below a readable size
        assert sizes and min(sizes) >= MIN_PT, (name, min(sizes, default=0))
    for sheet in ("Parameters", "Summary", "About"):
        found = _sheet_pages(pages, sheet)
        assert found and all(min(s) >= MIN_PT for _, s in found), sheet
    spec = result.scene.template.input
    header_of = dict(zip(result.model.names, _headers(path, "Table", 1)))
    words = [t.split() for t, _ in table]
    for q in result.model.columns:
        # an output's name is printed once, on one page; a helper's on none
        seen = sum(ws.count(q.name) for ws in words)
        assert seen == (1 if q.output else 0), (q.name, seen, header_of[q.name])
    for text, _ in table:  # each page: the input's header and every row of the sweep
        assert text.split()[0] == spec.name
        assert len(re.findall(r"^\s*-?\d+\.\d+\s", text, re.M)) == result.rows
    # every row's status printed once (the whole sweep fits one page down)
    ok = int((result.status == "ok").sum())
    assert sum(len(re.findall(r"\bok\s*$", t, re.M)) for t, _ in table) == ok
    # the Checks: every residual's and flag's header, no term
    checks_words = [w for t, _ in checks for w in t.split()]
    assert all(c.name in checks_words for c in result.model.checks)
    assert "term" not in checks_words and "assemble" in checks_words
