"""What a generated workbook holds: sheets, names, formulas, cached values, charts."""

from __future__ import annotations

import hashlib
import zipfile

import numpy as np
import openpyxl
import pandas as pd

from workbook_gen.tabulate import compute, evaluate
from workbook_gen.expr.excel import row_template
from workbook_gen.formula import parse, render
from workbook_gen.names import name_problem
from workbook_gen.scene import load_scene, parse_scene
from workbook_gen.workbook import write_workbook
from workbook_gen.workbook.layout import TableLayout

SHEETS = ["Table", "Parameters", "Checks", "Summary", "Charts", "About"]


def test_sheets_in_order_with_frozen_header(sewing_workbook):
    book = openpyxl.load_workbook(sewing_workbook)
    assert book.sheetnames == SHEETS
    assert book["Table"].freeze_panes == "B2"
    assert book["Table"]["A1"].value == "theta_1 [deg]"
    headers = [c.value for c in book["Table"][1]]
    assert headers[-1] == "status" and {"y_C [mm]", "v_C [mm/s]", "alpha_5 [rad/s^2]"} <= set(headers)


def test_every_parameter_has_a_legal_defined_name(sewing_workbook):
    book = openpyxl.load_workbook(sewing_workbook)
    params = book["Parameters"]
    names = book.defined_names
    for row in params.iter_rows(min_row=2, values_only=True):
        name = row[0]
        assert name_problem(name) is None
        assert names[name].attr_text == f"Parameters!$B${[r[0].value for r in params.iter_rows()].index(name) + 1}"
    assert names["check_tol"].attr_text == "Checks!$B$1"


def test_openpyxl_reads_back_exactly_the_formula_text_written(sewing_workbook):
    scene = load_scene("templates/sewing_machine.toml")
    result = evaluate(scene)
    layout = TableLayout.of(result)
    table = openpyxl.load_workbook(sewing_workbook)["Table"]
    for col, quantity in enumerate(result.model.columns, start=2):
        template = row_template(quantity.expr, layout.local)
        for row in range(2, 2 + result.rows):
            assert table.cell(row, col).value == template.render(row)


def test_every_formula_parses_and_prints_back_to_the_same_text(sewing_workbook, generate):
    slider = generate("templates/slider_crank.toml")
    count = 0
    for path in (sewing_workbook, slider):
        for sheet in openpyxl.load_workbook(path).worksheets:
            for row in sheet.iter_rows():
                for cell in row:
                    if isinstance(cell.value, str) and cell.value.startswith("="):
                        assert "=" + render(parse(cell.value)) == cell.value
                        count += 1
    assert count > 2000


def test_pandas_sees_numbers_in_every_formula_column(sewing_workbook):
    frame = pd.read_excel(sewing_workbook, sheet_name="Table", engine="openpyxl")
    numeric = frame.drop(columns=["status", "theta_1 [deg]"])  # the input is not a formula
    assert all(pd.api.types.is_numeric_dtype(numeric[c]) for c in numeric.columns)
    assert not numeric.isna().any().any()
    assert set(frame["status"]) == {"ok"}
    checks = pd.read_excel(sewing_workbook, sheet_name="Checks", header=6, engine="openpyxl")
    assert pd.api.types.is_float_dtype(checks["rod_length"])


def test_compute_columns_are_exactly_the_table_headers(sewing_workbook):
    table = compute(load_scene("templates/sewing_machine.toml"))
    frame = pd.read_excel(sewing_workbook, sheet_name="Table", engine="openpyxl")
    assert list(table.columns) == list(frame.columns)
    numeric = [c for c in table.columns if c != "status"]
    np.testing.assert_array_equal(table[numeric].to_numpy(), frame[numeric].to_numpy())


def test_checks_pass_and_are_live_formulas(sewing_workbook):
    book = openpyxl.load_workbook(sewing_workbook, data_only=True)
    checks = book["Checks"]
    assert checks["B2"].value == "PASS"
    assert checks["A8"].value == 0
    formulas = openpyxl.load_workbook(sewing_workbook)["Checks"]
    assert formulas["B8"].value.startswith('=IF(Table!')


def test_same_scene_gives_byte_identical_files(tmp_path):
    scene = load_scene("templates/sewing_machine.toml")
    first = write_workbook(scene, tmp_path).read_bytes()
    second = write_workbook(scene, tmp_path, force=True).read_bytes()
    assert hashlib.sha256(first).digest() == hashlib.sha256(second).digest()


def test_scene_asking_for_y_C_alone_gets_only_what_y_C_needs(tmp_path):
    text = ('name = "needle"\nmechanism = "sewing_machine"\n'
            '[outputs]\nquantities = ["y_C"]\n')
    scene = parse_scene(text, "needle.toml")
    path = write_workbook(scene, tmp_path)
    book = openpyxl.load_workbook(path)
    headers = [c.value for c in book["Table"][1]]
    assert headers == ["theta_1 [deg]", "theta_1r [deg]", "y_B [mm]", "lm_BC [mm]", "lp_BC [mm]",
                       "h_BC [mm]", "y_C [mm]", "status"]
    assert len(book["Charts"]._charts) == 1
    checks = [c.value for c in book["Checks"][7]]
    assert checks == ["theta_1 [deg]", "rod_length", "cannot assemble", "flagged"]
    summary = [r[0] for r in book["Summary"].iter_rows(values_only=True) if r[0]]
    assert "y_C" in summary and "theta_5" not in summary and "lever swing (from the table)" not in summary


def test_full_scene_has_all_charts(sewing_workbook):
    book = openpyxl.load_workbook(sewing_workbook)
    assert len(book["Charts"]._charts) == 8
    with zipfile.ZipFile(sewing_workbook) as z:
        chart = z.read("xl/charts/chart1.xml").decode()
    # the first chart is the needle's displacement: y_C against theta_1 (column A)
    col = next(c.column_letter for c in book["Table"][1] if c.value == "y_C [mm]")
    assert "<c:f>Table!$A$2:$A$38</c:f>" in chart and f"<c:f>Table!${col}$2:${col}$38</c:f>" in chart


def test_about_names_the_audit_command(sewing_workbook):
    about = openpyxl.load_workbook(sewing_workbook)["About"]
    texts = [c.value for row in about.iter_rows() for c in row if c.value]
    assert any(str(t).startswith("workbook-gen audit ") for t in texts)
    assert 'mechanism = "sewing_machine"' in texts


def test_checks_sheet_has_maximum_and_verdict_for_every_check(sewing_workbook):
    book = openpyxl.load_workbook(sewing_workbook)
    formulas, values = book["Checks"], openpyxl.load_workbook(sewing_workbook, data_only=True)["Checks"]
    headers = [c.value for c in formulas[7][1:]]
    names = headers[:headers.index("cannot assemble")]
    assert len(names) == 12
    for col, _ in enumerate(names, start=2):
        assert formulas.cell(4, col).value.startswith("=MAX(MAX(")
        assert 0 <= values.cell(4, col).value <= 1e-12
        assert values.cell(5, col).value == "PASS"
        assert values.cell(6, col).value in ("position", "velocity", "acceleration")
