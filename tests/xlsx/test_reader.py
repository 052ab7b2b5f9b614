"""The xlsx reader against files written by XlsxWriter, openpyxl and LibreOffice.

Every file is also read by openpyxl (an independent implementation) and compared cell
by cell; expected values come from the test's own inputs, never from the reader.
Hostile packages (XML and zip bombs, external entities, broken files) must give a
one-line WorkbookReadError naming the file and the part.
"""

from __future__ import annotations

import io
import math
import struct
import subprocess
import zipfile
from pathlib import Path

import openpyxl
import pytest
import xlsxwriter
from openpyxl.formula.translate import Translator
from openpyxl.worksheet.formula import ArrayFormula

from workbook_gen.errors import WorkbookReadError
from workbook_gen.xlerror import ExcelError
from workbook_gen.xlsx import read_workbook
from workbook_gen.xlsx.limits import Package

MAIN = "http://schemas.openxmlformats.org/spreadsheetml/2006/main"
REL = "http://schemas.openxmlformats.org/officeDocument/2006/relationships"
PKG = "http://schemas.openxmlformats.org/package/2006/relationships"
L = 2.5
ROWS = range(2, 12)  # Table rows 2..11 hold x = row - 2


# ----------------------------------------------------------------- comparison with openpyxl

def _ours_as_openpyxl(sheet, cell):
    """Our formula text as openpyxl shows it: '=' + text, shared followers translated."""
    source = sheet.formula_source(cell)
    if source is None:
        return None
    text, origin = source
    if origin != cell.ref:
        return Translator("=" + text, origin=origin).translate_formula(cell.ref)
    return "=" + text


def assert_same_as_openpyxl(path: Path) -> None:
    book = read_workbook(path)
    with_formulas = openpyxl.load_workbook(path)
    with_values = openpyxl.load_workbook(path, data_only=True)
    assert book.sheet_names == [ws.title for ws in with_formulas.worksheets]
    for ws in with_formulas.worksheets:
        sheet, ws_values = book.sheet(ws.title), with_values[ws.title]
        theirs = set()
        for row in ws.iter_rows():
            for their in row:
                cached = ws_values[their.coordinate].value
                if their.value is None and cached is None:
                    continue
                theirs.add(their.coordinate)
                ours = sheet.cells[their.coordinate]
                assert (ours.row, ours.col) == (their.row, their.column)
                formula = their.value if their.data_type == "f" else None
                if isinstance(formula, ArrayFormula):
                    assert ours.is_array and ours.array_ref == formula.ref
                    formula = formula.text
                assert _ours_as_openpyxl(sheet, ours) == formula, their.coordinate
                _assert_same_value(ours, cached)
        extra = {ref for ref, c in sheet.cells.items() if not (c.value in (None, "")
                 and c.has_formula)}
        assert extra <= theirs, f"{ws.title}: cells openpyxl does not see: {extra - theirs}"


def _assert_same_value(ours, cached) -> None:
    if isinstance(ours.value, ExcelError):
        assert ours.value.value == cached, ours.ref
    elif isinstance(cached, bool) or isinstance(ours.value, bool):
        assert ours.value is cached, ours.ref
    elif isinstance(cached, (int, float)):
        assert isinstance(ours.value, float) and ours.value == cached, ours.ref
    elif cached is None and ours.value == "" and ours.has_formula:
        pass  # a formula that returned "": openpyxl says None, we keep the empty text
    else:
        assert ours.value == cached, ours.ref


# ----------------------------------------------------------------------------- fixtures

def _write_xlsxwriter(path: Path) -> Path:
    wb = xlsxwriter.Workbook(str(path))
    params = wb.add_worksheet("Parameters")
    params.write_row(0, 0, ["Name", "Value"])
    params.write_row(1, 0, ["L", L])
    wb.define_name("L", "=Parameters!$B$2")
    chart_sheet = wb.add_chartsheet("Chart")
    table = wb.add_worksheet("Table")
    other = wb.add_worksheet("My Sheet")
    wb.define_name("'My Sheet'!local", "='My Sheet'!$A$1")
    other.write("A1", "  padded <&> ünïcode  ")
    other.write_rich_string("A2", "plain ", wb.add_format({"bold": True}), "bold", " tail")
    table.write_row(0, 0, ["x", "x*L", "size", "x>3", "sqrt(x-5)", "flag"])
    for r in ROWS:
        x = r - 2
        table.write_number(r - 1, 0, x)
        table.write_formula(r - 1, 1, f"=A{r}*L", None, x * L)
        table.write_formula(r - 1, 2, f'=IF(A{r}>5,"big","small")', None,
                            "big" if x > 5 else "small")
        table.write_formula(r - 1, 3, f"=A{r}>3", None, x > 3)
        table.write_formula(r - 1, 4, f"=SQRT(A{r}-5)", None,
                            math.sqrt(x - 5) if x >= 5 else "#NUM!")
        table.write_boolean(r - 1, 5, x % 2 == 0)
    table.write_array_formula("G2:G4", "{=A2:A4*2}", None, 0)
    table.write_formula("H2", '=""', None, "")
    chart = wb.add_chart({"type": "scatter"})
    chart.add_series({"categories": "=Table!$A$2:$A$11", "values": "=Table!$B$2:$B$11"})
    chart_sheet.set_chart(chart)
    wb.close()
    return path


@pytest.fixture(scope="module")
def xw_file(tmp_path_factory) -> Path:
    return _write_xlsxwriter(tmp_path_factory.mktemp("xw") / "book.xlsx")


@pytest.fixture(scope="module")
def lo_file(tmp_path_factory, libreoffice) -> Path:
    """A filled-down column written by XlsxWriter, saved again by LibreOffice."""
    folder = tmp_path_factory.mktemp("lo")
    src = folder / "in" / "filled.xlsx"
    src.parent.mkdir()
    wb = xlsxwriter.Workbook(str(src))
    ws = wb.add_worksheet("Data")
    params = wb.add_worksheet("Parameters")
    params.write("B2", L)
    wb.define_name("L", "=Parameters!$B$2")
    for r in range(2, 41):
        ws.write_number(r - 1, 0, r)
        ws.write_formula(r - 1, 1, f"=A{r}*2+L", None, 2 * r + L)
        ws.write_formula(r - 1, 2, f"=B{r}-$A$2", None, 2 * r + L - 2)
    wb.close()
    out = folder / "out"
    profile = (folder / "profile").as_uri()
    subprocess.run([libreoffice, f"-env:UserInstallation={profile}", "--headless",
                    "--convert-to", "xlsx", "--outdir", str(out), str(src)],
                   check=True, capture_output=True, timeout=180)
    return out / "filled.xlsx"


def _package(path: Path, sheets: dict[str, str], *, shared_strings: str | None = None,
             workbook: str | None = None, extra: dict[str, bytes | str] | None = None,
             extra_rels: str = "") -> Path:
    """A minimal hand-made xlsx: sheet name -> <sheetData> inner XML (or a full document)."""
    names = "".join(f'<sheet name="{n}" sheetId="{i + 1}" r:id="rId{i + 1}"/>'
                    for i, n in enumerate(sheets))
    rels = "".join(f'<Relationship Id="rId{i + 1}" Type="{REL}/worksheet" '
                   f'Target="worksheets/s{i + 1}.xml"/>' for i in range(len(sheets)))
    rels += extra_rels
    if shared_strings is not None:
        rels += f'<Relationship Id="rIdS" Type="{REL}/sharedStrings" Target="sst.xml"/>'
    overrides = "".join(
        f'<Override PartName="/xl/worksheets/s{i + 1}.xml" ContentType="application/'
        'vnd.openxmlformats-officedocument.spreadsheetml.worksheet+xml"/>'
        for i in range(len(sheets)))
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("[Content_Types].xml",
                   '<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
                   '<Default Extension="rels" ContentType="application/vnd.openxmlformats-'
                   'package.relationships+xml"/><Override PartName="/xl/workbook.xml" '
                   'ContentType="application/vnd.openxmlformats-officedocument.spreadsheetml.'
                   f'sheet.main+xml"/>{overrides}</Types>')
        z.writestr("_rels/.rels", f'<Relationships xmlns="{PKG}"><Relationship Id="rId1" '
                   f'Type="{REL}/officeDocument" Target="xl/workbook.xml"/></Relationships>')
        z.writestr("xl/workbook.xml", workbook or
                   f'<workbook xmlns="{MAIN}" xmlns:r="{REL}"><sheets>{names}</sheets></workbook>')
        z.writestr("xl/_rels/workbook.xml.rels", f'<Relationships xmlns="{PKG}">{rels}'
                   "</Relationships>")
        if shared_strings is not None:
            z.writestr("xl/sst.xml", f'<sst xmlns="{MAIN}">{shared_strings}</sst>')
        for i, body in enumerate(sheets.values()):
            if not body.lstrip().startswith("<?") and "<worksheet" not in body:
                body = f'<worksheet xmlns="{MAIN}"><sheetData>{body}</sheetData></worksheet>'
            z.writestr(f"xl/worksheets/s{i + 1}.xml", body)
        for name, data in (extra or {}).items():
            z.writestr(name, data)
    return path


def _read_error(path: Path, **limits) -> str:
    with pytest.raises(WorkbookReadError) as info:
        read_workbook(path, **limits)
    message = str(info.value)
    assert "\n" not in message and str(path) in message
    return message


# ------------------------------------------------------------------------- real writers

def test_xlsxwriter_values_and_formulas_are_the_ones_written(xw_file):
    book = read_workbook(xw_file)
    assert book.sheet_names == ["Parameters", "Table", "My Sheet"]
    assert book.other_sheets == [("Chart", "chartsheet")]
    table = book.sheet("table")
    for r in ROWS:
        x = r - 2
        assert table[f"A{r}"].value == float(x) and not table[f"A{r}"].has_formula
        assert (table[f"B{r}"].formula, table[f"B{r}"].value) == (f"A{r}*L", x * L)
        assert table[f"C{r}"].value == ("big" if x > 5 else "small")
        assert table[f"D{r}"].value is (x > 3)
        assert table[f"E{r}"].value == (math.sqrt(x - 5) if x >= 5 else ExcelError.NUM)
        assert table.cell(r, 6).value is (x % 2 == 0)
    assert table["G2"].is_array and table["G2"].array_ref == "G2:G4"
    assert table["G2"].formula == "A2:A4*2"
    assert [table[ref].array_master for ref in ("G3", "G4")] == ["G2", "G2"]
    # XlsxWriter stores <f>""</f><v></v> without t="str": no cached value at all
    assert table["H2"].value is None and table["H2"].formula == '""'
    assert [c.ref for c in table.row(2)][:3] == ["A2", "B2", "C2"]
    assert [c.row for c in table.column(2)] == [1, *ROWS]


def test_rich_and_escaped_strings(xw_file):
    sheet = read_workbook(xw_file).sheet("My Sheet")
    assert sheet["A1"].value == "  padded <&> ünïcode  "
    assert sheet["A2"].value == "plain bold tail"


def test_defined_names_global_and_sheet_local(xw_file):
    book = read_workbook(xw_file)
    assert book.defined_names == {"L": "Parameters!$B$2"}
    assert book.sheet("My Sheet").defined_names == {"local": "'My Sheet'!$A$1"}
    assert book.sheet("Table").defined_names == {}
    assert book.resolve_name("l") == "Parameters!$B$2"
    assert book.resolve_name("LOCAL", sheet="My Sheet") == "'My Sheet'!$A$1"
    assert book.resolve_name("local", sheet="Table") is None


def test_xlsxwriter_file_matches_openpyxl(xw_file):
    assert_same_as_openpyxl(xw_file)


def test_sheet_parts_found_through_relationships_not_file_names(xw_file, tmp_path):
    """Swap the files of Parameters and Table and their rels targets: names must follow."""
    swapped = tmp_path / "swapped.xlsx"
    a, b = "xl/worksheets/sheet1.xml", "xl/worksheets/sheet2.xml"
    with zipfile.ZipFile(xw_file) as src, zipfile.ZipFile(swapped, "w") as dst:
        for info in src.infolist():
            data = src.read(info)
            name = {a: b, b: a}.get(info.filename, info.filename)
            if info.filename == "xl/_rels/workbook.xml.rels":
                data = (data.replace(b"worksheets/sheet1.xml", b"@@")
                        .replace(b"worksheets/sheet2.xml", b"worksheets/sheet1.xml")
                        .replace(b"@@", b"worksheets/sheet2.xml"))
            dst.writestr(name, data)
    book = read_workbook(swapped)
    assert book.sheet("Parameters")["B2"].value == L
    assert book.sheet("Table")["B3"].formula == "A3*L"
    assert_same_as_openpyxl(swapped)


def test_openpyxl_written_file(tmp_path):
    path = tmp_path / "op.xlsx"
    wb = openpyxl.Workbook()
    ws = wb.active
    ws.title = "Sheet One"
    ws.append(["x", "y", "flag"])
    for x in range(1, 6):
        ws.append([x, f"=A{x + 1}^2-'Sheet One'!$A$2", x > 2])
    ws["E1"] = ArrayFormula("E1:E2", "=A2:A3*10")
    ws["F1"] = "=SUM(A2:A6)/L"
    wb.create_sheet("Second")["A1"] = 1.5
    wb.save(path)
    book = read_workbook(path)
    sheet = book.sheet("Sheet One")
    assert sheet["B3"].formula == "A3^2-'Sheet One'!$A$2" and sheet["B3"].value is None
    assert sheet["C4"].value is True and sheet["A6"].value == 5.0
    assert sheet["E1"].array_ref == "E1:E2"
    assert book.sheet("Second")["A1"].value == 1.5
    assert_same_as_openpyxl(path)


def test_hidden_rows(tmp_path):
    """Rows written hidden (by hand or by a filter: both are <row hidden="1">) are listed
    per sheet, whether or not they hold cells; openpyxl, which wrote them, says which."""
    path = tmp_path / "hidden.xlsx"
    wb = openpyxl.Workbook()
    ws = wb.active
    for r in range(1, 8):
        ws.cell(r, 1, r)
    for r in (3, 5, 9):  # 9: a hidden row without cells
        ws.row_dimensions[r].hidden = True
    wb.create_sheet("Other")["A1"] = 1
    wb.save(path)
    book = read_workbook(path)
    expected = {r for r, dim in openpyxl.load_workbook(path).active.row_dimensions.items()
                if dim.hidden}
    assert book.sheets[0].hidden_rows == expected == {3, 5, 9}
    assert book.sheet("Other").hidden_rows == set()


def test_libreoffice_saved_file(lo_file):
    """LibreOffice 7.4 rewrites every attribute and style; formulas and values must survive.

    (Measured: LibreOffice 7.4 writes each formula of a filled-down column in full, no
    shared formulas, whether the input was xlsx, ods or csv; Excel's shared formulas are
    covered by test_excel_style_shared_formulas below.)
    """
    book = read_workbook(lo_file)
    data = book.sheet("Data")
    for r in range(2, 41):
        for col, written, value in (("B", f"=A{r}*2+L", 2 * r + L),
                                    ("C", f"=B{r}-$A$2", 2 * r + L - 2)):
            cell = data[f"{col}{r}"]
            assert _ours_as_openpyxl(data, cell) == written
            assert cell.value == value
    assert book.defined_names == {"L": "Parameters!$B$2"}
    assert_same_as_openpyxl(lo_file)


def _excel_style_shared(path: Path) -> Path:
    """Columns B and C filled down as Excel saves them: one master, followers with si only."""
    rows = []
    for r in range(2, 12):
        b = ('<f t="shared" ref="B2:B11" si="0">A2*2+$A$2+Sheet2!B$1</f>' if r == 2
             else '<f t="shared" si="0"/>')
        c = ('<f t="shared" ref="C2:D2" si="1">SUM($A2:A2)</f>' if r == 2 else "")
        d = '<f t="shared" si="1"/>' if r == 2 else ""
        cells = f'<c r="A{r}"><v>{r}</v></c><c r="B{r}">{b}<v>{2 * r + 2 + 1}</v></c>'
        if r == 2:
            cells += f'<c r="C2">{c}<v>2</v></c><c r="D2">{d}<v>4</v></c>'
        rows.append(f'<row r="{r}">{cells}</row>')
    return _package(path, {"Sheet1": "".join(rows), "Sheet2": '<row r="1"><c r="B1"><v>1</v>'
                                                             "</c></row>"})


def test_excel_style_shared_formulas(tmp_path):
    path = _excel_style_shared(tmp_path / "shared.xlsx")
    sheet = read_workbook(path).sheet("Sheet1")
    master, follower = sheet["B2"], sheet["B7"]
    assert (master.formula, master.shared_master, master.shared_index) == (
        "A2*2+$A$2+Sheet2!B$1", "B2", 0)
    assert (follower.formula, follower.shared_master, follower.shared_index) == (None, "B2", 0)
    assert sheet.formula_source(follower) == ("A2*2+$A$2+Sheet2!B$1", "B2")
    assert sheet.shared_formulas[0].ref == "B2:B11"
    assert sheet["D2"].shared_master == "C2" and follower.has_formula
    # expanded by openpyxl's translator, the texts an engineer would have typed:
    assert _ours_as_openpyxl(sheet, follower) == "=A7*2+$A$2+Sheet2!B$1"
    assert _ours_as_openpyxl(sheet, sheet["D2"]) == "=SUM($A2:B2)"
    assert_same_as_openpyxl(path)


def test_hand_made_cell_types(tmp_path):
    sheet = (
        '<row r="1"><c r="A1" t="inlineStr"><is><t>inline</t></is></c>'
        '<c r="B1" t="inlineStr"><is><r><t>ri</t></r><r><rPr><b/></rPr><t>ch</t></r></is></c>'
        '<c r="C1" t="s"><v>0</v></c><c r="D1" t="s"><v>1</v></c>'
        '<c r="E1" t="e"><f>1/0</f><v>#DIV/0!</v></c><c r="F1" t="str"><f>"a"&amp;"b"</f>'
        '<v>ab</v></c><c r="G1" t="b"><v>0</v></c><c r="H1"><v>1e-3</v></c>'
        '<c r="I1" s="3"/><c r="J1" t="n"><v></v></c></row>'
        '<row r="3"><c><v>7</v></c><c><f>A3+1</f><v>8</v></c></row>'
        '<row><c><v>9</v></c></row>'
    )
    strings = ('<si><t>line_x000D_break</t></si>'
               '<si><r><t>run1 </t></r><r><t>run2</t></r><rPh sb="0" eb="1"><t>phon</t></rPh></si>')
    path = _package(tmp_path / "hand.xlsx", {"S": sheet}, shared_strings=strings)
    s = read_workbook(path).sheet("S")
    assert [s[r].value for r in ("A1", "B1", "C1", "D1")] == ["inline", "rich", "line\rbreak",
                                                              "run1 run2"]
    assert s["E1"].value is ExcelError.DIV0 and s["E1"].formula == "1/0"
    assert s["F1"].value == "ab" and s["G1"].value is False and s["H1"].value == 0.001
    assert "I1" not in s.cells and "J1" not in s.cells
    assert (s["A3"].value, s["B3"].formula, s["B3"].value) == (7.0, "A3+1", 8.0)
    assert s["A4"].value == 9.0 and (s["A4"].row, s["A4"].col) == (4, 1)


def test_shared_formula_follower_before_master_is_resolved(tmp_path):
    sheet = ('<row r="1"><c r="B1"><f t="shared" si="4"/><v>2</v></c></row>'
             '<row r="2"><c r="B2"><f t="shared" si="4" ref="B1:B2">A2*2</f><v>4</v></c></row>')
    s = read_workbook(_package(tmp_path / "sh.xlsx", {"S": sheet})).sheet("S")
    assert s["B1"].shared_master == "B2" and s.formula_source("B1") == ("A2*2", "B2")


def test_shared_formula_without_master_is_an_error(tmp_path):
    path = _package(tmp_path / "orphan.xlsx",
                    {"S": '<row r="1"><c r="B1"><f t="shared" si="0"/><v>1</v></c></row>'})
    assert "si=0 has no master" in _read_error(path)


def test_external_links_are_reported_not_followed(tmp_path):
    wb_xml = (f'<workbook xmlns="{MAIN}" xmlns:r="{REL}"><sheets><sheet name="S" sheetId="1" '
              'r:id="rId1"/></sheets><externalReferences><externalReference r:id="rId9"/>'
              "</externalReferences></workbook>")
    link = (f'<externalLink xmlns="{MAIN}" xmlns:r="{REL}"><externalBook r:id="rId1">'
            '<sheetNames><sheetName val="Prices"/></sheetNames></externalBook></externalLink>')
    link_rels = (f'<Relationships xmlns="{PKG}"><Relationship Id="rId1" Type="{REL}/'
                 'externalLinkPath" Target="file:///C:/other.xlsx" TargetMode="External"/>'
                 "</Relationships>")
    path = _package(tmp_path / "ext.xlsx", {"S": '<row r="1"><c r="A1"><f>[1]Prices!A1</f>'
                                                 "<v>3</v></c></row>"}, workbook=wb_xml,
                    extra={"xl/externalLinks/externalLink1.xml": link,
                           "xl/externalLinks/_rels/externalLink1.xml.rels": link_rels},
                    extra_rels=f'<Relationship Id="rId9" Type="{REL}/externalLink" '
                               'Target="externalLinks/externalLink1.xml"/>')
    book = read_workbook(path)
    [ext] = book.external_links
    assert (ext.index, ext.target, ext.sheet_names) == (1, "file:///C:/other.xlsx", ["Prices"])
    assert book.sheet("S")["A1"].formula == "[1]Prices!A1"


# ---------------------------------------------------------------------- hostile packages

BILLION_LAUGHS = ('<?xml version="1.0"?><!DOCTYPE lolz [<!ENTITY lol "lol">'
                  + "".join(f'<!ENTITY lol{i} "{("&lol" + str(i - 1) + ";") * 10}">'
                            for i in range(1, 10)).replace("&lol0;", "&lol;")
                  + f']><worksheet xmlns="{MAIN}"><sheetData><row r="1"><c r="A1" t="str">'
                  "<v>&lol9;</v></c></row></sheetData></worksheet>")


def test_xml_bomb_is_refused(tmp_path):
    message = _read_error(_package(tmp_path / "bomb.xlsx", {"S": BILLION_LAUGHS}))
    assert "xl/worksheets/s1.xml" in message and "DOCTYPE" in message


def test_external_entity_is_refused(tmp_path):
    xxe = ('<?xml version="1.0"?><!-- harmless <a> comment --><!DOCTYPE w [<!ENTITY xxe '
           f'SYSTEM "file:///etc/passwd">]><workbook xmlns="{MAIN}"><sheets>&xxe;</sheets>'
           "</workbook>")
    message = _read_error(_package(tmp_path / "xxe.xlsx", {"S": ""}, workbook=xxe))
    assert "xl/workbook.xml" in message and "DOCTYPE" in message


def test_doctype_in_utf16_is_refused(tmp_path):
    doc = BILLION_LAUGHS.replace('version="1.0"', 'version="1.0" encoding="UTF-16"')
    for n, encoded in enumerate((doc.encode("utf-16"), doc.encode("utf-16-le"))):
        path = _package(tmp_path / f"u16_{n}.xlsx", {"S": ""},
                        extra={"xl/worksheets/s2.xml": encoded})
        with Package(path) as pkg, pytest.raises(WorkbookReadError, match="DOCTYPE"):
            list(pkg.iter_xml("xl/worksheets/s2.xml"))


def test_not_a_zip(tmp_path):
    text = tmp_path / "text.xlsx"
    text.write_text("Name,Value\nL,2.5\n")
    assert "not a zip" in _read_error(text)
    ole = tmp_path / "legacy.xlsx"
    ole.write_bytes(b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1" + bytes(600))
    assert "OLE2" in _read_error(ole)
    assert "no such file" in _read_error(tmp_path / "missing.xlsx")


def test_truncated_zip(xw_file, tmp_path):
    data = xw_file.read_bytes()
    for cut in (len(data) // 2, len(data) - 30):
        path = tmp_path / f"cut{cut}.xlsx"
        path.write_bytes(data[:cut])
        _read_error(path)


def test_missing_workbook_part(tmp_path):
    path = tmp_path / "empty.xlsx"
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("hello.txt", "no workbook here")
    assert "xl/workbook.xml" in _read_error(path)


def test_broken_xml_names_the_part(tmp_path):
    path = _package(tmp_path / "broken.xlsx", {"Good": '<row r="1"><c r="A1"><v>1</v></c></row>',
                                               "Bad": '<row r="1"><c r="A1"><v>1</v></row>'})
    message = _read_error(path)
    assert "xl/worksheets/s2.xml" in message and "broken XML" in message


def test_zip_bomb_member_refused_before_inflating(tmp_path):
    padding = b" " * (64 << 20)  # 64 MiB that deflate to about 64 KiB
    body = f'<worksheet xmlns="{MAIN}"><sheetData/>'.encode() + padding + b"</worksheet>"
    path = _package(tmp_path / "zbomb.xlsx", {"S": body.decode()})
    message = _read_error(path)
    assert "compression ratio" in message and "xl/worksheets/s1.xml" in message
    with Package(path) as pkg, pytest.raises(WorkbookReadError):
        pkg.read_bytes("xl/worksheets/s1.xml")
    assert pkg.inflated == 0
    assert "max_uncompressed" in _read_error(path, max_ratio=1e9, max_uncompressed=1 << 20)


def test_member_lying_about_its_size(tmp_path):
    """Central directory and local header say 100 bytes; the data inflate to 8 MiB."""
    path = _package(tmp_path / "liar.xlsx", {"S": "<row r='1'/>" * (700_000)})
    data = bytearray(path.read_bytes())
    name = b"xl/worksheets/s1.xml"
    for signature, size_at in ((b"PK\x03\x04", 22), (b"PK\x01\x02", 24)):
        start = 0
        while (at := data.find(signature, start)) >= 0:
            name_at = at + (30 if signature == b"PK\x03\x04" else 46)
            if data[name_at:name_at + len(name)] == name:
                struct.pack_into("<I", data, at + size_at, 100)
            start = at + 4
    path.write_bytes(bytes(data))
    assert "xl/worksheets/s1.xml" in _read_error(path)


def test_too_many_cells(tmp_path):
    path = tmp_path / "many.xlsx"
    wb = xlsxwriter.Workbook(str(path))
    for name in ("A", "B"):
        ws = wb.add_worksheet(name)
        for r in range(30):
            ws.write_row(r, 0, [1.0] * 10)
    wb.close()
    assert read_workbook(path, max_cells=600).n_cells == 600
    message = _read_error(path, max_cells=599)
    assert "max_cells" in message and "(B)" in message


def test_rows_beyond_excel_limit(tmp_path):
    path = _package(tmp_path / "far.xlsx", {"S": '<row r="1048577"><c><v>1</v></c></row>'})
    assert "1048576" in _read_error(path)


def test_in_memory_zip_with_bad_crc(xw_file, tmp_path):
    buf = io.BytesIO()
    with zipfile.ZipFile(xw_file) as src, zipfile.ZipFile(buf, "w", zipfile.ZIP_STORED) as dst:
        for info in src.infolist():
            dst.writestr(info.filename, src.read(info))
    data = bytearray(buf.getvalue())
    at = data.find(b"<sheetData>")
    data[at + 1] ^= 0x20  # flip a byte inside a stored sheet: the CRC no longer matches
    path = tmp_path / "crc.xlsx"
    path.write_bytes(bytes(data))
    assert "corrupt" in _read_error(path)


def test_strict_ooxml_namespaces(tmp_path):
    """ISO strict files use purl.oclc.org namespaces and relationship types."""
    plain = _package(tmp_path / "plain.xlsx", {"S": '<row r="1"><c r="A1"><f>1+1</f><v>2</v>'
                                                    '</c><c r="B1" t="inlineStr"><is><t>s</t>'
                                                    "</is></c></row>"})
    strict = tmp_path / "strict.xlsx"
    with zipfile.ZipFile(plain) as src, zipfile.ZipFile(strict, "w") as dst:
        for info in src.infolist():
            dst.writestr(info.filename, src.read(info).replace(
                MAIN.encode(), b"http://purl.oclc.org/ooxml/spreadsheetml/main").replace(
                REL.encode(), b"http://purl.oclc.org/ooxml/officeDocument/relationships"))
    sheet = read_workbook(strict).sheet("S")
    assert (sheet["A1"].formula, sheet["A1"].value, sheet["B1"].value) == ("1+1", 2.0, "s")
