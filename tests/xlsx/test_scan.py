"""The regular-expression row scanner (workbook_gen/xlsx/scan.py) reads exactly what
ElementTree reads: every sheet below is read twice, once as usual and once with the scanner
switched off, and the cells (every field), hidden rows and shared formulas, or the error,
must be the same. The plain rows must really go through the scanner, and rows it does not
recognise through ElementTree."""

from __future__ import annotations

import pytest

from tests.xlsx.test_reader import MAIN, _package
from workbook_gen.auditor.inputs import read_inputs
from workbook_gen.errors import WorkbookReadError
from workbook_gen.xlsx import read_workbook, scan, sheetdata
from workbook_gen.xlsx.model import Cell

SHEETS = {
    "plain": '<row r="1"><c r="A1" s="1"><v>1.5</v></c><c r="B1"><f>A1*2</f><v>3</v></c>'
             '<c r="C1" t="str"><f>"a"&amp;"b"</f><v>ab</v></c></row>'
             '<row r="2" spans="1:3" hidden="1"><c r="A2" t="b"><v>1</v></c>'
             '<c r="B2" t="e"><f>1/0</f><v>#DIV/0!</v></c><c r="C2" t="s"><v>1</v></c></row>',
    "entities and line ends": '<row r="1"><c r="A1" t="str"><f>IF(B1&lt;&gt;"x&#38;y",'
                              '"&#x41;&apos;&quot;","c\r\nd\re")</f><v>A\'"</v></c>'
                              '<c r="B1" t="str"><v>x&amp;y\r\n</v></c></row>',
    "empty formulas and values": '<row r="1"><c r="A1"><f></f><v>1</v></c><c r="B1"><f/></c>'
                                 '<c r="C1" t="str"><f>""</f><v></v></c>'
                                 '<c r="D1" t="str"><f>""</f></c><c r="E1" s="3"/>'
                                 '<c r="F1" t="n"><v></v></c><c r="G1" t="inlineStr">'
                                 '<is><t></t></is></c><c r="H1" t="inlineStr"><v>v</v></c></row>',
    "shared and array formulas": '<row r="1"><c r="A1"><f t="shared" ref="A1:A3" si="0">B1+1'
                                 '</f><v>2</v></c><c r="B1"><f t="array" ref="B1:B2">{1;2}</f>'
                                 '<v>1</v></c></row><row r="2"><c r="A2"><f t="shared" si="0"/>'
                                 '<v>3</v></c><c r="B2"><v>2</v></c></row>'
                                 '<row r="3"><c r="A3"><f t="shared" si="0"/><v>4</v></c></row>',
    "libreoffice spelling": '<row r="1" customFormat="false" ht="12.8" hidden="false" '
                            'customHeight="false" outlineLevel="0" collapsed="false">'
                            '<c r="A1" s="0" t="n"><f aca="false">1+1</f><v>2</v></c>'
                            '<c r="B1" s="0" t="inlineStr"><is><t xml:space="preserve"> a '
                            '</t></is></c><c r="C1" s="0" t="str"><f aca="false">'
                            'T(&quot;_x0007_&quot;)</f><v>_x0007_</v></c></row>',
    "unusual rows go to ElementTree": '<row r="1"><c r="a1"><v>1</v></c><c r="$B$1"><v>2</v>'
                                      '</c></row><row r="2"><c><v>7</v></c><c r="C2" '
                                      't="inlineStr"><is><r><t>ri</t></r><r><t>ch</t></r></is>'
                                      '</c></row><row><c r="A3"><v>3</v></c></row>',
    "plain cells in every spelling": '<row r="1"><c r="A1" s="3"/><c r="B1" t="e"><f>=1/0</f>'
                                     '<v>#DIV/0!</v></c><c r="C1" t="b"><v>0</v></c>'
                                     '<c r="D1" t="s"><v>0</v></c><c r="E1" t="n"><f aca='
                                     '"false">=A1&amp;"&#10;"</f></c><c r="F1" t="str"><f>'
                                     'T("")</f></c><c r="G1" s="2"><f>"=x"</f><v>0</v></c>'
                                     '</row><row r="2" hidden="true"><c r="A2"><v>2</v></c>'
                                     '</row><row r="3"><c r="A3" t="str"><v>_x0007_&lt;</v>'
                                     '</c><c r="B3" t="e"><v>#N/A</v></c></row>',
    "repeated refs": '<row r="1"><c r="A1"><v>1</v></c><c r="A1"><f>2+2</f><v>4</v></c>'
                     '<c r="B1"><f>A1</f><v>4</v></c></row><row r="2"><c r="A2"><v>5</v></c>'
                     '</row><row r="1"><c r="A1" t="inlineStr"><is><t>x</t></is></c></row>'
                     '<row r="3"><c r="A3"><v>1</v></c><c r="A2"><f>A3</f><v>1</v></c></row>',
    "row and cell numbers": '<row r="5"><c r="A5"><v>1</v></c><c r="XFD5"><v>2</v></c></row>'
                            '<row><c r="B6"><v>3</v></c></row>',
}
# a batch the scanner does not take as a whole: ElementTree reads all of it
UNSCANNED = {
    "self-closed row": '<row r="1"><c r="A1"><v>1</v></c></row><row r="4" />',
    "prefixed elements": '<x:row r="1"><x:c r="A1"><x:v>1</x:v></x:c></x:row>',
}
ERRORS = {
    "control character": '<row r="1"><c r="A1" t="str"><v>a\x01b</v></c></row>',
    "column beyond XFD": '<row r="1"><c r="XFE1"><v>1</v></c></row>',
    "row beyond Excel": '<row r="1"><c r="A1048577"><v>1</v></c></row>',
    "bad number": '<row r="1"><c r="A1"><v>1x</v></c></row>',
    "bad shared string": '<row r="1"><c r="A1" t="s"><v>7</v></c></row>',
    "unknown entity": '<row r="1"><c r="A1" t="str"><v>&nbsp;</v></c></row>',
    "unclosed cell": '<row r="1"><c r="A1"><v>1</v></row>',
    "non-character": '<row r="1"><c r="A1" t="str"><f>"a"</f><v>a\uffffb</v></c></row>',
    "]]> in text": '<row r="1"><c r="A1" t="str"><f>"a"</f><v>a]]&gt;b]]>c</v></c></row>',
}
STRINGS = "<si><t>zero</t></si><si><t>one</t></si>"


def _read(path, monkeypatch, scanner: bool | str):
    """(cells as tuples, hidden rows, shared formulas) of sheet S, or the error's text;
    and the attributes of the rows the scanner read (a plain batch's rows marked "whole").
    ``scanner``: True, "rows" (no batch taken whole) or False (ElementTree only)."""
    used = []
    real_row, real_batch = sheetdata._scanned_row, sheetdata._plain_rows

    def counted(*args):
        used.append(args[0][0])
        return real_row(*args)

    def counted_batch(*args):
        out = real_batch(*args)
        used.extend(("whole", a) for a in args[0].attributes)
        return out

    with monkeypatch.context() as m:
        m.setattr(sheetdata, "_scanned_row", counted)
        m.setattr(sheetdata, "_plain_rows", counted_batch)
        if scanner == "rows":
            m.setattr(scan, "plain_rows", lambda text: None)
        elif not scanner:
            m.setattr(scan, "decoded", _refuse)
        try:
            sheet = read_workbook(path).sheet("S")
        except WorkbookReadError as exc:
            return str(exc), used
    cells = {ref: tuple(getattr(c, f) for f in Cell.__slots__) for ref, c in sheet.cells.items()}
    return (list(cells.items()), sorted(sheet.hidden_rows), sheet.shared_formulas,
            sheet.dimension), used


def _refuse(data):
    raise scan.Unrecognised


@pytest.mark.parametrize("body", SHEETS.values(), ids=SHEETS.keys())
def test_scanner_reads_what_elementtree_reads(tmp_path, monkeypatch, body):
    path = _package(tmp_path / "s.xlsx", {"S": body}, shared_strings=STRINGS)
    scanned, used = _read(path, monkeypatch, scanner=True)
    by_rows, used_rows = _read(path, monkeypatch, scanner="rows")
    parsed, none = _read(path, monkeypatch, scanner=False)
    assert scanned == parsed and by_rows == parsed and not none
    assert used and used_rows, "no row went through the scanner"
    assert not any(isinstance(u, tuple) for u in used_rows)


def test_a_batch_of_plain_rows_is_taken_whole(tmp_path, monkeypatch):
    body = SHEETS["plain cells in every spelling"] + SHEETS["row and cell numbers"]
    path = _package(tmp_path / "s.xlsx", {"S": body}, shared_strings=STRINGS)
    (cells, hidden, *_), used = _read(path, monkeypatch, scanner=True)
    assert [u for u in used if u[0] != "whole"] == []
    assert [a for _, a in used] == [' r="1"', ' r="2" hidden="true"', ' r="3"', ' r="5"', ""]
    assert hidden == [2] and [ref for ref, _ in cells][-3:] == ["A5", "XFD5", "B6"]
    assert (cells, hidden) == _read(path, monkeypatch, scanner=False)[0][:2]


@pytest.mark.parametrize("body", SHEETS.values(), ids=SHEETS.keys())
def test_audit_inputs_of_plain_columns_are_those_of_cells(tmp_path, monkeypatch, body):
    """The audit takes the scanner's plain cells as columns (Sheet.parts): the formulas,
    cached values and constants it reads are those of the Cell objects ElementTree makes,
    in the same order."""
    path = _package(tmp_path / "s.xlsx", {"S": body}, shared_strings=STRINGS)

    def inputs():
        got = read_inputs(path)
        return [list(d.items()) for d in (got.formulas, got.cached, got.constants)]

    scanned = inputs()
    with monkeypatch.context() as m:
        m.setattr(scan, "decoded", _refuse)
        parsed = inputs()
    assert scanned == parsed


def test_plain_cells_stay_columns_until_asked_for(tmp_path):
    body = '<row r="1"><c r="A1" s="1"><v>1</v></c><c r="B1"><f>A1*2</f><v>2</v></c></row>'
    sheet = read_workbook(_package(tmp_path / "s.xlsx", {"S": body})).sheet("S")
    assert sheet.chunks and not sheet._cells and sheet.max_row == 1 and sheet.max_col == 2
    assert [c.ref for c in sheet.row_cells(1)] == ["A1", "B1"] and sheet.chunks
    assert sheet.cells["B1"] == Cell("B1", 1, 2, 2.0, "A1*2", "normal")
    assert not sheet.chunks


@pytest.mark.parametrize("body", UNSCANNED.values(), ids=UNSCANNED.keys())
def test_batches_the_scanner_does_not_take_are_parsed_whole(tmp_path, monkeypatch, body):
    if body.startswith("<x:"):
        body = (f'<?xml version="1.0"?><x:worksheet xmlns:x="{MAIN}"><x:sheetData>{body}'
                '</x:sheetData></x:worksheet>')
    path = _package(tmp_path / "s.xlsx", {"S": body}, shared_strings=STRINGS)
    scanned, used = _read(path, monkeypatch, scanner=True)
    parsed, _ = _read(path, monkeypatch, scanner=False)
    assert scanned == parsed and scanned[0] and not used


def test_plain_rows_are_scanned_and_unusual_ones_parsed(tmp_path, monkeypatch):
    body = ('<row r="1"><c r="a1"><v>1</v></c></row><row r="2"><c r="B2"><v>2</v></c></row>'
            '<row r="3"><c><v>3</v></c></row><row r="4"><c r="D4"><f>B2</f><v>2</v></c></row>')
    path = _package(tmp_path / "s.xlsx", {"S": body})
    (cells, *_), used = _read(path, monkeypatch, scanner=True)
    assert used == [' r="2"', ' r="4"']  # the plain rows only, one by one
    assert [ref for ref, _ in cells] == ["A1", "B2", "A3", "D4"]


@pytest.mark.parametrize("body", ERRORS.values(), ids=ERRORS.keys())
def test_scanner_leaves_errors_to_elementtree(tmp_path, monkeypatch, body):
    path = _package(tmp_path / "s.xlsx", {"S": body}, shared_strings=STRINGS)
    scanned, _ = _read(path, monkeypatch, scanner=True)
    parsed, _ = _read(path, monkeypatch, scanner=False)
    assert isinstance(scanned, str) and scanned == parsed


def test_xml_text_is_what_a_parser_returns():
    assert scan.xml_text("a\r\nb\rc&lt;&gt;&amp;&quot;&apos;&#65;&#x42;") == 'a\nb\nc<>&"\'AB'
    with pytest.raises(scan.Unrecognised):
        scan.xml_text("&nbsp;")
    with pytest.raises(scan.Unrecognised):
        scan.xml_text("&#1;")
