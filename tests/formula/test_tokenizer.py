"""formula/tokenizer.py against openpyxl's formula tokenizer (an independent port of
E. W. Bachtal's Excel formula tokenizer): the same tokens, spaces aside, for every
formula of four Excel-saved corpus workbooks (about 9,700 formulas: every function of
Mac Excel 16, POI's evaluation sheet, SheetJS's stress test, structured references).

openpyxl keeps an array constant as its pieces and a chain of ranges ``A1:B2:C3:D4`` as
one operand; here an array constant is one token and the chain is the range operator
between references: both are compared in openpyxl's form."""

from __future__ import annotations

import html
import re
import zipfile

import pytest
from openpyxl.formula.tokenizer import Tokenizer

from corpus_audits import CORPUS
from workbook_gen.formula.tokenizer import is_cell_ref, split_sheet, tokenize

FILES = ["formulas__test.xlsx", "poi__FormulaEvalTestData_Copy.xlsx",
         "sheetjs__formula_stress_test.xlsx", "poi__StructuredRefs-lots-with-lookups.xlsx"]


def formulas(name: str) -> list[str]:
    out = []
    with zipfile.ZipFile(CORPUS / name) as z:
        for part in z.namelist():
            if part.startswith("xl/worksheets/") and part.endswith(".xml"):
                text = z.read(part).decode("utf-8")
                out += ["=" + html.unescape(m) for m in
                        re.findall(r"<f(?: [^>]*)?>([^<]+)</f>", text)]
    return out


def ours(formula: str) -> list[str]:
    texts: list[str] = []
    kinds: list[str] = []
    for t in tokenize(formula):
        if t.kind == "START" or not t.text.strip():
            continue
        if len(texts) >= 2 and texts[-1] == ":" and kinds[-2] == "REF":
            texts[-2:] = [texts[-2] + ":" + t.text.strip()]   # a chain of ranges: one operand
            kinds[-2:] = ["REF"]
            continue
        texts.append(t.text.strip())
        kinds.append(t.kind)
    return texts


def theirs(formula: str) -> list[str]:
    out, depth, array = [], 0, ""
    for t in Tokenizer(formula).items:
        if t.type == "WHITE-SPACE":
            continue
        if t.type == "ARRAY" and t.subtype == "OPEN":
            depth += 1
        if depth:
            array += t.value
            if t.type == "ARRAY" and t.subtype == "CLOSE":
                depth -= 1
                if not depth:
                    out.append(array)
                    array = ""
            continue
        out.append(t.value.strip())   # openpyxl keeps a line break's \r in the operand
    return out


@pytest.mark.parametrize("name", FILES)
def test_the_same_tokens_as_openpyxl(name):
    texts = formulas(name)
    assert len(texts) > 300
    differ = [(f, ours(f), theirs(f)) for f in texts if ours(f) != theirs(f)]
    assert not differ, differ[:5]


def test_cell_references_and_sheets():
    for text in ["A1", "$A$1", "XFD1048576", "a1", "$ab$12"]:
        assert is_cell_ref(text), text
    for text in ["A0", "XFE1", "A1048577", "1A", "A", "R1C1"]:
        assert not is_cell_ref(text), text
    assert split_sheet("'My Sheet'!B2") == ("My Sheet", "B2")
    assert split_sheet("'It''s'!B2") == ("It's", "B2")
    assert split_sheet("B2") == (None, "B2")
