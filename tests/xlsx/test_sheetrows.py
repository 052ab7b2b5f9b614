"""xlsx/sheetrows.py: a worksheet part's <row> elements, in order, cut into batches of
whole rows. Reference: the same hand-made part parsed whole by ElementTree here (every
row's r and every cell's r, t, <v>, <f>), compared with what read_workbook made of the
rows _rows gave; for parts of more than one batch (over a megabyte), with a namespace
prefix, in the plain and unusual forms, and the parts it must refuse."""

from __future__ import annotations

import zipfile
from xml.etree.ElementTree import fromstring

import pytest

from tests.xlsx.test_reader import MAIN, _package
from workbook_gen.errors import WorkbookReadError
from workbook_gen.xlerror import ExcelError
from workbook_gen.xlsx import read_workbook, sheetrows
from workbook_gen.xlsx.limits import Package
from workbook_gen.xlsx.model import Sheet

PART = "xl/worksheets/s1.xml"


def _expected(path):
    """{ref: (value, formula)} of the part, by ElementTree over the whole part."""
    with zipfile.ZipFile(path) as z:
        root = fromstring(z.read(PART))
    out = {}
    for c in root.iter():
        if c.tag.rpartition("}")[2] != "c":
            continue
        kids = {k.tag.rpartition("}")[2]: k for k in c}
        v = kids["v"].text if "v" in kids else None
        t = c.get("t", "n")
        value = (None if v is None else float(v) if t == "n" else ExcelError.from_text(v)
                 if t == "e" else (v == "1") if t == "b" else v)
        if t == "inlineStr":
            value = "".join(x.text or "" for x in kids["is"].iter() if x.tag.endswith("}t"))
        out[c.get("r")] = (value, kids["f"].text if "f" in kids else None)
    return out


def _read(path):
    sheet = read_workbook(path).sheet("S")
    return {ref: (c.value, c.formula) for ref, c in sheet.cells.items()}, sheet


def _body(n, width=3):
    rows = []
    for r in range(1, n + 1):
        cells = "".join(f'<c r="{chr(65 + k)}{r}"><v>{r * 10 + k}.5</v></c>' for k in range(width))
        if r % 7 == 0:  # unusual rows among plain ones
            cells += f'<c r="E{r}" t="inlineStr"><is><t>x&amp;{r}</t></is></c>'
            cells += f'<c r="F{r}" t="e"><v>#N/A</v></c><c r="G{r}" t="b"><v>1</v></c>'
        if r % 5 == 0:
            cells += f'<c r="H{r}"><f>A{r}*2</f><v>{2 * (r * 10 + 0.5)}</v></c>'
        rows.append(f'<row r="{r}">{cells}</row>')
    return "".join(rows)


@pytest.fixture(scope="module")
def big(tmp_path_factory):
    """About 2.5 megabytes of rows: three batches."""
    path = _package(tmp_path_factory.mktemp("rows") / "big.xlsx", {"S": _body(22_000)})
    with zipfile.ZipFile(path) as z:
        assert z.getinfo(PART).file_size > 2 * sheetrows._BATCH
    return path


def test_rows_across_batches_are_read_whole_and_in_order(big):
    cells, sheet = _read(big)
    assert cells == _expected(big)
    assert sheet.max_row == 22_000


def test_the_rows_come_as_batches_and_apart_gives_each_row(big):
    with Package(big) as pkg:
        rows = list(sheetrows._rows(pkg, PART, Sheet("S", 0)))
        plain = [r for r in rows if isinstance(r, sheetrows.PlainRows)]
        # rows with an inline string or error are no plain batch: those come row by row
        count = sum(len(b.attributes) for b in plain) + len(rows) - len(plain)
        assert count == 22_000
        if plain:
            assert len(sheetrows.apart(pkg, PART, plain[0])) == len(plain[0].attributes)


def test_a_prefixed_namespace_and_the_dimension(tmp_path):
    body = _body(30).replace("<row", "<x:row").replace("</row>", "</x:row>")
    for tag in ("c", "v", "f", "is", "t"):
        body = body.replace(f"<{tag} ", f"<x:{tag} ").replace(f"<{tag}>", f"<x:{tag}>")
        body = body.replace(f"</{tag}>", f"</x:{tag}>")
    doc = (f'<?xml version="1.0"?><x:worksheet xmlns:x="{MAIN}"><x:dimension ref="A1:H30"/>'
           f"<x:sheetData>{body}</x:sheetData></x:worksheet>")
    path = _package(tmp_path / "p.xlsx", {"S": doc})
    cells, sheet = _read(path)
    assert cells == _expected(path) and len(cells) > 90
    assert sheet.dimension == "A1:H30"


def test_empty_and_unusual_parts(tmp_path):
    empty = _package(tmp_path / "e.xlsx", {"S": f'<worksheet xmlns="{MAIN}"><dimension '
                                                'ref="A1"/><sheetData/></worksheet>'})
    cells, sheet = _read(empty)
    assert cells == {} and sheet.dimension == "A1"
    cdata = _package(tmp_path / "c.xlsx", {"S": '<row r="1"><c r="A1" t="str"><f>"a"</f>'
                                                 "<v><![CDATA[a<b]]></v></c></row>"})
    assert _read(cdata)[0] == {"A1": ("a<b", '"a"')} == _expected(cdata)  # element by element


def test_broken_parts_are_refused_with_one_line(tmp_path):
    unended = _package(tmp_path / "u.xlsx", {"S": f'<worksheet xmlns="{MAIN}"><sheetData>'
                                                   '<row r="1"><c r="A1"><v>1</v></c></row>'})
    with pytest.raises(WorkbookReadError, match="broken XML"):
        read_workbook(unended)
    bad = _package(tmp_path / "b.xlsx", {"S": '<row r="1"><c r="A1"><v>1</v></row>'})
    with pytest.raises(WorkbookReadError, match="broken XML") as info:
        read_workbook(bad)
    assert "\n" not in str(info.value)
