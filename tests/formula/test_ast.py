"""formula/ast.py: ``shift`` moves a formula's relative references as Excel's copy does
(openpyxl's Translator, on the corpus's formulas: the printed texts agree), ``r1c1``
writes Excel's R1C1 notation, and ``walk``/``children`` reach every node."""

from __future__ import annotations

import random

import pytest
from openpyxl.formula.translate import Translator, TranslatorError
from openpyxl.utils import get_column_letter

from workbook_gen.formula import ast, parse
from workbook_gen.formula.printer import render

from .test_printer import parses
from .test_tokenizer import FILES, formulas


def cell(row: int, col: int) -> str:
    return f"{get_column_letter(col)}{row}"


@pytest.mark.parametrize("name", FILES[:3])
def test_shift_as_excels_copy(name):
    rng = random.Random(name)
    texts = [f for f in formulas(name) if "!" not in f and "[" not in f
             and not any(c.isspace() for c in f) and parses(f)][:500]
    compared = 0
    for f in texts:
        r, c = rng.randint(40, 80), rng.randint(40, 80)
        dr, dc = rng.randint(-30, 30), rng.randint(-30, 30)
        try:
            moved = Translator(f, origin=cell(r, c)).translate_formula(cell(r + dr, c + dc))
        except TranslatorError:
            continue
        if "#REF!" in moved:
            continue
        assert render(ast.shift(parse(f), dr, dc)) == moved[1:], (f, dr, dc)
        compared += 1
    assert compared > 100


def test_off_the_sheet_is_ref():
    assert render(ast.shift(parse("=A1+B2"), -1, 0)) == "#REF!+B1"
    assert render(ast.shift(parse("=SUM($A$1:A2)"), 5, 1)) == "SUM($A$1:B7)"
    assert render(ast.shift(parse("=XFD1"), 0, 1)) == "#REF!"


def test_r1c1_as_excel_writes_it():
    node = parse("=C5")
    assert isinstance(node, ast.CellRef)
    assert ast.r1c1(node, 5, 3) == "RC"
    assert ast.r1c1(node, 2, 7) == "R[3]C[-4]"
    assert ast.r1c1(parse("=$C$5"), 1, 1) == "R5C3"
    assert ast.r1c1(parse("=C$5"), 9, 1) == "R5C[2]"


def test_walk_reaches_every_reference():
    node = parse("=IF(SUM(A1:B2,C3)>0,D4*-E5%,F6)")
    refs = [render(n) for n in ast.walk(node) if isinstance(n, (ast.CellRef, ast.RangeRef))]
    assert sorted(refs) == ["A1:B2", "C3", "D4", "E5", "F6"]
