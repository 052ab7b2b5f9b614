"""Blocks of rows written whole (workbook/rows.py) give the bytes XlsxWriter writes
cell by cell with write_formula / write_number."""

from __future__ import annotations

import io
import zipfile

import pytest
import xlsxwriter
from xlsxwriter import worksheet as xlsx_worksheet

from workbook_gen.expr import Var, eq, if_
from workbook_gen.expr.excel import ROW, Row, row_template
from workbook_gen.expr.tree import FUNCTIONS, Call, Num, Text
from workbook_gen.workbook.rows import Column, Sheet

VALUES = [0.1, -0.0, 1e-300, 6.123233995736766e-17, 12345678901234567.0, 3, True, False,
          "", "#NUM!", "#DIV/0!", "n/a", "a<b & c>d", "#VALUE!"]


def _columns(fmt):
    n = len(VALUES)
    shift = Row(-6)
    quoted = row_template(if_(eq(Var("x"), Text('say "{hi}" <&>')), Var("y") * 2, Var("x")),
                          lambda name: (("Table!B", shift) if name == "x" else ("C", ROW)))
    plain = row_template(Call("SQRT", (Var("x") + Num(1.5),)), lambda name: ("A", ROW))
    return [
        Column(0, [float(i) * 0.1 for i in range(n)]),
        Column(1, VALUES, plain),
        Column(2, list(reversed(VALUES)), quoted, fmt),
        Column(4, [1.0] * n, plain),
        Column(5, ["ok"] * n, quoted),
    ]


def _sheet_xml(fast: bool) -> bytes:
    stream = io.BytesIO()
    book = xlsxwriter.Workbook(stream, {"constant_memory": True})
    fmt = book.add_format({"num_format": "0.00"})
    col_fmt = book.add_format({"bold": True})
    sheet = book.add_worksheet("S", worksheet_class=Sheet)
    sheet.set_column(0, 1, 12, col_fmt)
    sheet.write_string(0, 0, "header")
    sheet.write_string(0, 3, "more")
    columns = _columns(fmt)
    if fast:
        sheet.write_rows(1, columns)
    else:
        for i in range(len(VALUES)):
            for c in columns:
                if c.formula is None:
                    sheet.write_number(1 + i, c.col, c.values[i], c.cell_format)
                else:
                    sheet.write_formula(1 + i, c.col, c.formula.render(2 + i), c.cell_format,
                                        c.values[i])
    sheet.write_string(len(VALUES) + 2, 1, "below")
    book.close()
    with zipfile.ZipFile(stream) as z:
        return z.read("xl/worksheets/sheet1.xml")


def test_write_rows_gives_the_bytes_of_write_formula_cell_by_cell():
    fast, slow = _sheet_xml(True), _sheet_xml(False)
    assert b"&lt;&amp;&gt;" in fast and b'Table!B' in fast and b't="e"' in fast
    assert fast == slow


def test_write_rows_refuses_rows_above_those_written():
    book = xlsxwriter.Workbook(io.BytesIO(), {"constant_memory": True})
    sheet = book.add_worksheet("S", worksheet_class=Sheet)
    sheet.write_string(5, 0, "x")
    sheet.write_string(6, 0, "y")
    with pytest.raises(ValueError, match="above rows already written"):
        sheet.write_rows(3, [Column(0, [1.0, 2.0])])
    book.close()


def test_no_tree_function_is_one_xlsxwriter_rewrites():
    """write_rows skips XlsxWriter's future/dynamic-array function handling: sound only
    while every function a tree can hold is a classic one."""
    for name in FUNCTIONS:
        formula = f"{name}(A1)"
        assert not xlsx_worksheet.re_dynamic_function.search(formula), name
        prepared = xlsxwriter.Workbook(io.BytesIO()).add_worksheet()._prepare_formula(
            formula, expand_future_functions=True)
        assert prepared == formula, name


def test_packaging_in_memory_or_through_files_gives_the_same_parts():
    """Small workbooks are packaged in memory, very large ones through XlsxWriter's
    temporary files (package.py): every part must be the same either way."""
    from workbook_gen.tabulate import evaluate
    from workbook_gen.scene import load_scene
    from workbook_gen.workbook import writer

    result = evaluate(load_scene("templates/slider_crank.toml", step=15.0))
    assert writer.in_memory(result)
    parts = []
    for memory in (True, False):
        stream = io.BytesIO()
        writer._build(stream, result, "x.xlsx", memory=memory)
        with zipfile.ZipFile(stream) as z:
            parts.append({name: z.read(name) for name in z.namelist()})
    assert parts[0].keys() == parts[1].keys() and len(parts[0]) > 10
    for name in parts[0]:
        assert parts[0][name] == parts[1][name], name


def _deflated_size(data: bytes, level: int) -> int:
    import zlib
    packer = zlib.compressobj(level, zlib.DEFLATED, -15)
    return len(packer.compress(data) + packer.flush())


def test_package_is_deflated_at_our_level_and_other_workbooks_at_xlsxwriters():
    """package.py sets the zlib level of our workbooks' archive (COMPRESSLEVEL); any
    other XlsxWriter workbook in the process keeps zlib's default, and XlsxWriter's
    module its ZipFile (no process-wide patch)."""
    from workbook_gen.scene import load_scene
    from workbook_gen.workbook import workbook_bytes
    from workbook_gen.workbook.package import COMPRESSLEVEL

    ours = workbook_bytes(load_scene("templates/slider_crank.toml"), "x.xlsx")
    assert ours == workbook_bytes(load_scene("templates/slider_crank.toml"), "x.xlsx")
    plain = io.BytesIO()
    book = xlsxwriter.Workbook(plain)
    book.add_worksheet().write_column(0, 0, [f"row {i} " * 20 for i in range(300)])
    book.close()
    assert xlsxwriter.workbook.ZipFile is zipfile.ZipFile
    for data, level in ((ours, COMPRESSLEVEL), (plain.getvalue(), 6)):
        with zipfile.ZipFile(io.BytesIO(data)) as z:
            big = max(z.infolist(), key=lambda i: i.file_size)
            assert big.compress_size == _deflated_size(z.read(big), level), level
            assert big.compress_size != _deflated_size(z.read(big), 9 - level)


class _NoRowMemo(Sheet):
    """Sheet with XlsxWriter's own cell methods and row XML."""
    _write_single_row = xlsx_worksheet.Worksheet._write_single_row
    write_string = xlsx_worksheet.Worksheet.write_string
    write_number = xlsx_worksheet.Worksheet.write_number
    write_formula = xlsx_worksheet.Worksheet.write_formula


def _cells_xml(sheet_class, swap_formats: bool) -> bytes:
    """Rows written cell by cell: the same cells twice in one sheet, formats first used
    in either order (their xf indices differ), row and column formats, typed values."""
    stream = io.BytesIO()
    book = xlsxwriter.Workbook(stream, {"constant_memory": True,
                                        "nan_inf_to_errors": True})
    bold, num, italic = (book.add_format(s) for s in
                         ({"bold": True}, {"num_format": "0.000"}, {"italic": True}))
    sheet = book.add_worksheet("S", worksheet_class=sheet_class)
    sheet.set_column(2, 2, 10, italic)
    sheet.write_string(0, 5, "first", num if swap_formats else bold)
    for block in (1, 11):
        sheet.set_row(block + 1, 30, num)
        sheet.write_string(block, 0, "name", bold)
        sheet.write_string(block, 2, " padded ")
        sheet.write_string(block + 1, 0, "row format")
        sheet.write_formula(block + 1, 1, "=1+1", None, True)
        sheet.write_formula(block + 2, 1, "=1+1", None, 1)
        sheet.write_formula(block + 3, 1, "=0*-1", None, -0.0)
        sheet.write_formula(block + 4, 1, "=0*-1", None, 0.0)
        sheet.write_number(block + 5, 2, 2.5)
        sheet.write_blank(block + 5, 3, None, num)
        sheet.write_formula(block + 6, 1, "=1/0", bold, "#DIV/0!")
        sheet.write_string(block + 7, 1, "a<b & c")
        sheet.write_string(block + 7, 2, "tab\there _x0041_ \x01")   # control characters
        sheet.write_number(block + 8, 0, -0.0)
        sheet.write_formula(block + 8, 1, "=A1&\"<\"", None, "x<y")   # text result, escaped
        sheet.write_formula(block + 8, 2, '=""', None, "")
        sheet.set_row(block + 9, None, None, {"hidden": True, "level": 1})
        sheet.write_string(block + 9, 0, "hidden, outline level 1")
        sheet.write_number(block + 9, 1, 7)                          # an int
        sheet.write_number(block + 9, 2, float("nan"))               # XlsxWriter's error
        sheet.write_string(block + 10, 1, "long " * 4000)            # > half the limit
        sheet.write_formula(f"B{block + 12}", "=SUM(A1:A2)", bold, 3)   # A1 notation
        sheet.write_string(block + 11, 3, "above", bold)
        sheet.write_formula(block + 11, 4, "=LEN(A1)")               # no value given
    book.close()
    with zipfile.ZipFile(stream) as z:
        return z.read("xl/worksheets/sheet1.xml")


def test_rows_kept_by_what_decides_them_give_xlsxwriters_bytes():
    for swap in (False, True, False, True):   # the kept rows are reused from the 2nd on
        assert _cells_xml(Sheet, swap) == _cells_xml(_NoRowMemo, swap)
    assert _cells_xml(Sheet, False) != _cells_xml(Sheet, True)


def test_parts_deflated_once_per_process_give_zlibs_bytes():
    """FastZipFile keeps the deflated bytes of small parts (the same for every variant):
    a workbook packaged from kept parts is the one packaged from scratch, and every
    entry's data is zlib's at our level."""
    from workbook_gen.scene import load_scene
    from workbook_gen.workbook import package, workbook_bytes, xlsxwriter_internals

    scene = load_scene("templates/four_bar.toml", step=20.0)
    xlsxwriter_internals.DEFLATED.clear()
    fresh = workbook_bytes(scene, "x.xlsx")
    assert xlsxwriter_internals.DEFLATED   # small parts were kept
    assert workbook_bytes(scene, "x.xlsx") == fresh   # now from the kept parts
    with zipfile.ZipFile(io.BytesIO(fresh)) as z:
        for info in z.infolist():
            assert info.compress_size == _deflated_size(z.read(info), package.COMPRESSLEVEL)


def test_drawings_kept_per_process_give_the_fresh_bytes():
    """package.py keeps a drawing part's XML by its anchors, sizes and kinds: scenes of
    different chart layouts written in turn give what each gives from scratch."""
    from workbook_gen.scene import load_scene
    from workbook_gen.workbook import package, workbook_bytes

    scenes = [load_scene(f"templates/{n}.toml", step=30.0)
              for n in ("slider_crank", "four_bar", "slider_crank")]
    fresh = []
    for scene in scenes:
        package._DRAWING_XML.clear()
        fresh.append(workbook_bytes(scene, "x.xlsx"))
    kept = [workbook_bytes(scene, "x.xlsx") for scene in scenes]
    assert len(package._DRAWING_XML) == 2 and kept == fresh


def test_charts_kept_per_thread_give_the_fresh_bytes():
    """charts.py keeps the chart objects by position and key: workbooks of scenes with
    different charts, written in turn in one thread and then in another, give what each
    gives from scratch (nothing of one workbook leaks into the next)."""
    import threading
    from workbook_gen.scene import load_scene
    from workbook_gen.workbook import charts, workbook_bytes

    scenes = [load_scene(f"templates/{n}.toml", step=30.0, overrides=o)
              for n, o in (("slider_crank", {}), ("four_bar", {}),
                           ("slider_crank", {"l_BC": 45.0, "e": 10.0}))]
    fresh = []
    for scene in scenes:
        charts._KEPT.charts, charts._KEPT.xml = {}, {}
        fresh.append(workbook_bytes(scene, "x.xlsx"))
    assert charts._KEPT.charts   # kept for the next workbook
    kept = [workbook_bytes(scene, "x.xlsx") for scene in scenes + scenes]
    other = []
    thread = threading.Thread(target=lambda: other.extend(
        workbook_bytes(scene, "x.xlsx") for scene in scenes))
    thread.start()
    thread.join()
    assert kept == fresh + fresh and other == fresh


def test_entries_written_by_package_are_zipfiles_bytes():
    """FastZipFile writes the in-memory parts itself: the archive is byte for byte
    what zipfile writes for the same parts, names, dates and level (twice: the second
    time from the kept deflated parts)."""
    from workbook_gen.scene import load_scene
    from workbook_gen.workbook import package, workbook_bytes

    for _ in range(2):
        ours = workbook_bytes(load_scene("templates/five_bar.toml", step=15.0), "x.xlsx")
        theirs = io.BytesIO()
        with zipfile.ZipFile(io.BytesIO(ours)) as source, \
                zipfile.ZipFile(theirs, "w", zipfile.ZIP_DEFLATED) as target:
            assert len(source.infolist()) > 10
            for info in source.infolist():
                entry = zipfile.ZipInfo(info.filename, (1980, 1, 1, 0, 0, 0))
                entry.compress_type = zipfile.ZIP_DEFLATED
                target.writestr(entry, source.read(info),
                                compresslevel=package.COMPRESSLEVEL)
        assert ours == theirs.getvalue()
