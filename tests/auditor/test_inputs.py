"""auditor/inputs.py: what the audit reads off a workbook, checked against the values
planted with XlsxWriter (formulas with chosen cached values) and against openpyxl
reading the same file back (formulas, and cached values with data_only=True)."""

from __future__ import annotations

import openpyxl
import pytest

from workbook_gen.auditor.inputs import AuditInputs, read_inputs
from workbook_gen.errors import WorkbookReadError

from planted import planted_book


@pytest.fixture(scope="module")
def planted(tmp_path_factory):
    return planted_book(tmp_path_factory.mktemp("inputs") / "planted.xlsx")


@pytest.fixture(scope="module")
def inputs(planted) -> AuditInputs:
    return read_inputs(planted)


def test_formulas_and_cached_values_are_those_planted(inputs):
    assert inputs.formulas == {("S", 1, 2): "A1*3", ("S", 2, 2): "A2*3",
                               ("S", 3, 2): "A1+A2", ("S", 1, 4): "k*10",
                               ("T", 1, 2): "S!B1+1"}
    for key, value in {("S", 1, 2): 6, ("S", 2, 2): 9, ("S", 3, 2): 99, ("S", 1, 4): 20,
                       ("T", 1, 2): 7, ("S", 1, 3): 4, ("S", 2, 3): 6}.items():
        assert inputs.cached[key] == value, key
    assert inputs.constants[("S", 1, 1)] == 2 and inputs.constants[("S", 3, 1)] == "txt"
    assert inputs.book.defined_names["k"] == "S!$A$1"


def test_openpyxl_reads_the_same_file_alike(planted, inputs):
    texts = openpyxl.load_workbook(planted)
    values = openpyxl.load_workbook(planted, data_only=True)
    for (sheet, row, col), text in inputs.formulas.items():
        assert texts[sheet].cell(row, col).value == "=" + text
        assert values[sheet].cell(row, col).value == inputs.cached[(sheet, row, col)]
    array = texts["S"]["C1"].value  # openpyxl's ArrayFormula
    assert array.ref == "C1:C2" and array.text == "=A1:A2*2"


def test_an_array_formula_is_kept_apart_with_its_area(inputs):
    anchor, second = ("S", 1, 3), ("S", 2, 3)
    assert set(inputs.array_cells) == {anchor, second}
    assert inputs.arrays[anchor] == ("A1:A2*2", (2, 3))
    assert inputs.array_master == {anchor: anchor, second: anchor}
    assert inputs.text_of(second) == "{=A1:A2*2}" and inputs.text_of(("S", 1, 2)) == "A1*3"
    assert inputs.text_of(("S", 9, 9)) == ""
    assert inputs.is_formula(anchor) and not inputs.is_formula(second)
    assert not inputs.is_formula(("S", 1, 1))


def test_counts_names_and_references(inputs):
    assert inputs.formula_count == 6  # five plain formulas and the array, once
    assert AuditInputs.ref(("S", 2, 28)) == "AB2"
    assert inputs.cell_keys()["T!B1"] == ("T", 1, 2)
    assert inputs.uncheckable() == {}
    assert inputs._all_sheets() == ["S", "T"]


def test_grouping_and_a_missing_file(planted, tmp_path):
    grouped = read_inputs(planted, group=True)
    assert grouped.grouped is not None and grouped.formulas == read_inputs(planted).formulas
    with pytest.raises(WorkbookReadError, match="no such file"):
        read_inputs(tmp_path / "none.xlsx")
