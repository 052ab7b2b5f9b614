"""formula/printer.py: ``render(parse(f))`` gives back Excel's own text for every formula
without whitespace that Excel saved in four corpus workbooks; ``to_relative`` gives one
key to a formula and its copies, the copies made by openpyxl's Translator (which moves
the relative references of a formula as Excel's copy and paste does); sheet names are
quoted where Excel quotes them."""

from __future__ import annotations

import random

import pytest
from openpyxl.formula.translate import Translator, TranslatorError
from openpyxl.utils import get_column_letter

from workbook_gen.errors import FormulaSyntaxError
from workbook_gen.formula import parse
from workbook_gen.formula.printer import (column_letters, number_text, quote_sheet, render,
                                          to_relative)

from .test_tokenizer import FILES, formulas


# where the text differs, and why (each may only leave this list)
KNOWN = {
    "=[2]!A": "an external book's name is printed quoted: '[2]'!A",
    "=[1]Sheet1!$A$1+1": "an external book's sheet is printed quoted: '[1]Sheet1'!",
    "=[2]MISSING!A1": "as above",
    "=[1]Sheet1!$A$1+[1]Sheet1!$A$2": "as above",
    "=REF!#REF!": "a sheet-qualified #REF! is printed without its sheet",
}


def parses(f: str) -> bool:
    try:
        parse(f)
    except FormulaSyntaxError:   # (the parser's own tests cover what it refuses)
        return False
    return True


@pytest.mark.parametrize("name", FILES)
def test_excels_text_comes_back(name):
    texts = [f for f in formulas(name) if not any(c.isspace() for c in f) and parses(f)]
    assert texts
    differ = {f for f in texts if render(parse(f)) != f[1:]}
    assert not differ - set(KNOWN), sorted(differ - set(KNOWN))[:5]
    assert not (set(KNOWN) & set(texts)) - differ, "these come back now: leave KNOWN"


def cell(row: int, col: int) -> str:
    return f"{get_column_letter(col)}{row}"


@pytest.mark.parametrize("name", FILES[:2])
def test_copies_share_one_relative_key(name):
    rng = random.Random(name)
    texts = [f for f in formulas(name) if "!" not in f and "[" not in f and parses(f)][:400]
    for f in texts:
        r, c = rng.randint(30, 60), rng.randint(30, 60)
        r2, c2 = r + rng.randint(-20, 20), c + rng.randint(-20, 20)
        try:
            copy = Translator(f, origin=cell(r, c)).translate_formula(cell(r2, c2))
        except TranslatorError:
            continue   # a reference moved off the sheet
        assert to_relative(parse(f), r, c) == to_relative(parse(copy), r2, c2), (f, copy)


def test_a_copy_elsewhere_is_another_key():
    assert to_relative(parse("=B2*2"), 2, 3) == "RC[-1]*2"
    assert to_relative(parse("=$A$1+B3"), 2, 3) == "R1C1+R[1]C[-1]"
    assert to_relative(parse("=B2*2"), 2, 3) != to_relative(parse("=B2*2"), 3, 3)


def test_columns_numbers_and_sheet_names():
    for n in list(range(1, 800)) + [16383, 16384]:
        assert column_letters(n) == get_column_letter(n)
    assert number_text(2.0) == "2" and number_text(0.5) == "0.5"
    assert number_text(1e20) == "1E+20"
    assert quote_sheet("Table") == "Table"
    for needs_quotes in ["My Sheet", "A1", "R1C1", "R2", "C", "1abc", "It's", "a-b"]:
        assert quote_sheet(needs_quotes).startswith("'"), needs_quotes
    assert quote_sheet("It's") == "'It''s'"
