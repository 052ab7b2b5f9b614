"""audit --annotate: a copy with every disagreement and finding filled and explained in a
cell comment, made by editing the package's XML so that every formula and cached value
stays byte for byte as it was."""

from __future__ import annotations

import re
import subprocess
import sys
import zipfile
from pathlib import Path

import openpyxl
import pytest
from openpyxl.comments import Comment

from workbook_gen import audit
from workbook_gen.auditor.annotate import annotate
from workbook_gen.auditor.notes import AUTHOR, FILLS
from workbook_gen.engines.libreoffice import recalculate

_CELL = re.compile(rb'<c\b([^>]*?)(?:/>|>(.*?)</c>)', re.S)


def cells(path: Path) -> dict[tuple[str, bytes], tuple[bytes, bytes | None]]:
    """{(sheet part, ref): (start tag attributes, the cell's content: <f>, <v>, <is>)}."""
    out = {}
    with zipfile.ZipFile(path) as z:
        for name in z.namelist():
            if name.startswith("xl/worksheets/") and name.endswith(".xml"):
                for m in _CELL.finditer(z.read(name)):
                    ref = re.search(rb'\br="([^"]*)"', m.group(1)).group(1)
                    out[(name, ref)] = (m.group(1), m.group(2))
    return out


def run_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "workbook_gen.cli", *args],
                          capture_output=True, text=True, timeout=600)


def _assert_only_styles_changed(original: Path, copy: Path, flagged: set[tuple[str, str]]):
    """Every cell's content identical; the start tags differ by ``s`` only, and only on
    the ``flagged`` cells (sheet part, ref)."""
    before, after = cells(original), cells(copy)
    assert before.keys() == after.keys()
    changed = set()
    for key, (attrs, content) in before.items():
        assert after[key][1] == content, key  # every <f>, <v> byte for byte
        if after[key][0] != attrs:
            assert re.sub(rb'\s*s="\d+"', b"", after[key][0]) == re.sub(rb'\s*s="\d+"', b"",
                                                                        attrs), key
            changed.add((key[0], key[1].decode()))
    assert changed == flagged


@pytest.fixture(scope="module")
def tampered(sewing_workbook, tmp_path_factory):
    """Our workbook with one y_C formula multiplied by 1.001 (and what follows it)."""
    folder = tmp_path_factory.mktemp("annotate")
    table = openpyxl.load_workbook(sewing_workbook)["Table"]
    col = next(c.column_letter for c in table[1] if c.value == "y_C [mm]")
    formula = table[f"{col}11"].value[1:]
    bad = folder / "tampered.xlsx"
    with zipfile.ZipFile(sewing_workbook) as zin, zipfile.ZipFile(bad, "w",
                                                                  zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            data = zin.read(item.filename)
            if item.filename == "xl/worksheets/sheet1.xml":
                data = data.replace(f"<f>{formula}</f>".encode(),
                                    f"<f>{formula}*1.001</f>".encode())
            zout.writestr(item, data)
    return bad, f"{col}11"


def test_disagreements_are_filled_and_explained_values_untouched(tampered, tmp_path):
    bad, cell = tampered
    report = audit(bad)
    assert not report.ok
    out = annotate(bad, report, tmp_path / "annotated.xlsx")
    parts = {name: f"xl/worksheets/sheet{i + 1}.xml"
             for i, name in enumerate(openpyxl.load_workbook(bad).sheetnames)}
    flagged = {(parts[m.cell.split("!")[0].strip("'")], m.cell.split("!")[1])
               for m in report.mismatches + report.findings}
    assert ("xl/worksheets/sheet1.xml", cell) in flagged
    _assert_only_styles_changed(bad, out, flagged)
    sheet = openpyxl.load_workbook(out)["Table"]
    assert sheet[cell].fill.fgColor.rgb == FILLS["disagree"]
    assert "disagrees" in sheet[cell].comment.text and AUTHOR in sheet[cell].comment.text
    assert sheet[cell].number_format == openpyxl.load_workbook(bad)["Table"][cell].number_format
    assert sheet["A11"].comment is None


def _book_with_comments(path: Path) -> Path:
    book = openpyxl.Workbook()
    ws = book.active
    ws.title = "Data Sheet"
    for r in range(1, 8):
        ws.cell(r, 1, r * 1.25)
        ws.cell(r, 2, f"=A{r}*2")
    ws["B4"] = 99.0                                   # constant_in_formula_run
    ws["B4"].comment = Comment("typed by hand, check", "Ann")
    ws["A1"].comment = Comment("input from the test bench", "Bob")
    book.save(path)
    return path


def test_existing_comments_are_kept_and_libreoffice_shows_ours(libreoffice, tmp_path):
    source = recalculate(_book_with_comments(tmp_path / "commented.xlsx"), tmp_path / "lo")
    report = audit(source)
    assert {f.cell for f in report.findings} == {"'Data Sheet'!B4"}
    out = annotate(source, report, tmp_path / "annotated.xlsx")
    _assert_only_styles_changed(source, out, {("xl/worksheets/sheet1.xml", "B4")})
    ws = openpyxl.load_workbook(out)["Data Sheet"]
    assert "typed by hand, check" in ws["B4"].comment.text
    assert "constant_in_formula_run" in ws["B4"].comment.text
    assert ws["A1"].comment.text.strip().endswith("input from the test bench")
    assert ws["B4"].fill.fgColor.rgb == FILLS["finding"]
    # LibreOffice reads the copy: its own save of it still has both comments
    again = openpyxl.load_workbook(recalculate(out, tmp_path / "lo2"))["Data Sheet"]
    assert "constant_in_formula_run" in again["B4"].comment.text
    assert "typed by hand" in again["B4"].comment.text
    assert "test bench" in again["A1"].comment.text


def test_cli_refuses_to_overwrite_without_force(tampered, tmp_path):
    bad, _ = tampered
    target = tmp_path / "out.xlsx"
    target.write_bytes(b"keep me")
    result = run_cli("audit", str(bad), "--annotate", str(target))
    assert result.returncode == 2 and len(result.stderr.strip().splitlines()) == 1
    assert "--force" in result.stderr and target.read_bytes() == b"keep me"
    result = run_cli("audit", str(bad), "--annotate", str(target), "--force")
    assert result.returncode == 1  # the audit's verdict; the copy is written
    assert zipfile.is_zipfile(target)
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]
    wrong = run_cli("audit", str(bad), "--annotate", str(tmp_path / "out.xlsm"))
    assert wrong.returncode == 2 and not (tmp_path / "out.xlsm").exists()
