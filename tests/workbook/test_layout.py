"""Printing (issue 12 item 11, issue 22 item 17): the Table and the Checks landscape on A4
at a fixed 80 %, header row and input column repeated (tests/workbook/test_layout_wide.py has
more); the Charts two rows of two per page with page breaks between them.  The settings are read from the XML; one LibreOffice run
exports two workbooks to PDF and poppler's pdftotext splits the pages."""

from __future__ import annotations

import re
import shutil
import subprocess
import zipfile

import pytest

from workbook_gen.scene import load_scene
from workbook_gen.workbook import write_workbook

TITLES = ["Needle bar displacement", "Needle bar velocity", "Needle bar acceleration",
          "Take-up lever angle", "Take-up lever angular velocity",
          "Take-up lever angular acceleration", "Path of E", "Path of G"]


@pytest.fixture(scope="module")
def workbooks(tmp_path_factory):
    out = tmp_path_factory.mktemp("print")
    coarse = write_workbook(load_scene("templates/sewing_machine.toml"), out / "coarse")
    fine = write_workbook(load_scene("templates/sewing_machine.toml", step=1.0), out / "fine")
    return coarse, fine


def _part(path, name: str) -> str:
    with zipfile.ZipFile(path) as z:
        return z.read(name).decode()


def test_table_prints_landscape_at_a_fixed_scale_with_header_and_input_repeated(workbooks):
    coarse, _ = workbooks
    table = _part(coarse, "xl/worksheets/sheet1.xml")
    setup = re.search(r"<pageSetup [^>]*/>", table).group(0)
    assert 'orientation="landscape"' in setup and 'paperSize="9"' in setup
    assert 'scale="80"' in setup and "fitTo" not in table  # issue 22 item 17: was 1 page wide
    names = _part(coarse, "xl/workbook.xml")
    assert re.search(r'<definedName name="_xlnm.Print_Titles" localSheetId="0">'
                     r"Table!\$A:\$A,Table!\$1:\$1</definedName>", names)
    assert re.search(r'<definedName name="_xlnm.Print_Titles" localSheetId="2">'
                     r"Checks!\$A:\$A,Checks!\$7:\$7</definedName>", names)


def test_charts_print_at_a_fixed_scale_with_a_break_after_every_second_row(workbooks):
    coarse, _ = workbooks
    charts = _part(coarse, "xl/worksheets/sheet5.xml")
    assert "fitToPage" not in charts  # Excel ignores manual page breaks when fitting
    assert re.search(r'<pageSetup [^>]*scale="65"[^>]*orientation="landscape"', charts)
    assert '<brk id="40" max="16383" man="1"/>' in charts


def _pdf_pages(libreoffice: str, paths, out_dir) -> dict[str, list[str]]:
    """Each workbook's PDF pages as text, by the name of its folder (one soffice run)."""
    profile = out_dir / "profile"
    copies = [out_dir / f"{path.parent.name}.xlsx" for path in paths]
    for path, copy in zip(paths, copies):
        shutil.copyfile(path, copy)
    subprocess.run([libreoffice, f"-env:UserInstallation={profile.as_uri()}", "--headless",
                    "--norestore", "--convert-to", "pdf", "--outdir", str(out_dir),
                    *map(str, copies)], check=True, capture_output=True, timeout=600)
    pdftotext = shutil.which("pdftotext")
    if pdftotext is None:
        pytest.fail("pdftotext (poppler-utils) is required: run bash "
                    "scripts/install-test-deps.sh", pytrace=False)
    pages = {}
    for path, copy in zip(paths, copies):
        pdf = copy.with_suffix(".pdf")
        text = subprocess.run([pdftotext, "-layout", str(pdf), "-"], check=True,
                              capture_output=True, text=True).stdout
        pages[path.parent.name] = text.split("\f")[:-1]
    return pages


def test_pdf_export_prints_the_table_across_the_page_and_each_chart_whole(
        libreoffice, workbooks, tmp_path):
    coarse, fine = workbooks
    pages = _pdf_pages(libreoffice, [coarse, fine], tmp_path)
    # the Table: its pages are those with the Table's footer
    for name, rows in (("coarse", 37), ("fine", 361)):
        table = [p for p in pages[name] if re.search(r"^\s*Table\s+page \d+\s*$", p, re.M)]
        assert table, name
        # every Table page starts with the header (repeated) and the input column
        assert all(p.split()[0] == "theta_1" for p in table), name
        assert all(re.search(r"^\s*theta_1\s+\S+ \[", p, re.M) for p in table), name
        printed = sum(len(re.findall(r"\bok\s*$", p, re.M)) for p in table)
        assert printed == rows, name
        assert not any("dh_BC" in p for p in table)  # an intermediate column: not printed
    coarse_table = [p for p in pages["coarse"] if re.search(r"^\s*Table\s+page", p, re.M)]
    # each page one strip of columns, the whole coarse sweep down it (was one page at 3 pt)
    assert all(len(re.findall(r"^\s*\d+\.\d+\s", p, re.M)) == 37 for p in coarse_table)
    # the Charts: two pages (four charts each at 65 %), right after the Summary and
    # right before the About sheet: a chart wider than the page would add pages
    coarse_pages = pages["coarse"]
    summary = max(i for i, p in enumerate(coarse_pages) if "rows that cannot be assembled" in p)
    about = min(i for i, p in enumerate(coarse_pages) if "scene as given" in p)
    charts = coarse_pages[summary + 1:about]
    assert len(charts) == 2
    assert all(any(t in p for t in TITLES) for p in charts)


def test_every_chart_lies_within_one_printed_page(workbooks):
    """The charts' anchors (drawing1.xml): each within one page's rows (a break after
    every 40 rows) and within the print area's 18 columns."""
    coarse, _ = workbooks
    drawing = _part(coarse, "xl/drawings/drawing1.xml")
    anchors = re.findall(r"<xdr:from><xdr:col>(\d+)</xdr:col><xdr:colOff>-?\d+</xdr:colOff>"
                         r"<xdr:row>(\d+)</xdr:row>.*?<xdr:to><xdr:col>(\d+)</xdr:col>"
                         r"<xdr:colOff>-?\d+</xdr:colOff><xdr:row>(\d+)</xdr:row>", drawing,
                         re.S)
    assert len(anchors) == len(TITLES)
    for col0, row0, col1, row1 in ((int(v) for v in a) for a in anchors):
        assert row0 // 40 == row1 // 40 and col1 < 18, (col0, row0, col1, row1)


def test_a_scene_without_charted_outputs_gets_no_print_area(tmp_path):
    """Rows 1..0 are no range: `Charts!$A$1:$R$0` made openpyxl warn and is not a legal
    print area; the sheet says why it is empty instead."""
    import warnings

    import openpyxl
    scene = tmp_path / "one.toml"
    scene.write_text('name = "one"\nmechanism = "four_bar"\n[outputs]\nquantities = ["theta_3"]\n')
    path = write_workbook(load_scene(str(scene)), tmp_path / "out")
    names = _part(path, "xl/workbook.xml")
    assert "Charts!" not in names
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        book = openpyxl.load_workbook(path)
    assert book["Charts"]["A1"].value.startswith("No chart")
