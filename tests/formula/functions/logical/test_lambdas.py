"""LAMBDA, LET and the functions that call a LAMBDA (SCAN, REDUCE, MAP, BYROW, BYCOL,
MAKEARRAY), with ``_xleta.SUM`` for a function passed by name; the dynamic-array functions
that shape arrays (CHOOSECOLS, TAKE, EXPAND, ...) and TEXTBEFORE/TEXTAFTER/ARRAYTOTEXT.

LibreOffice 7.4 has none of them, so the reference is Excel itself: the corpus's
formulas__test.xlsx was saved by Excel 365 with a table of cases per function (ordinary
and error arguments); every such cell must be recomputed and agree with Excel's value.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from workbook_gen.formula.functions.logical import lambdas
from workbook_gen.formula.parser import parse
from workbook_gen.formula.scalar import DictResolver, evaluate

CORPUS = Path("/work/shared/corpus/xlsx/formulas__test.xlsx")
FAMILY = ("LAMBDA(", "LET(", "SCAN(", "REDUCE(", "MAP(", "BYROW(", "BYCOL(", "MAKEARRAY(")
SHAPING = ("CHOOSECOLS(", "CHOOSEROWS(", "TOCOL(", "TOROW(", "TAKE(", "DROP(", "EXPAND(",
           "VSTACK(", "HSTACK(", "WRAPROWS(", "WRAPCOLS(", "SEQUENCE(", "TEXTBEFORE(",
           "TEXTAFTER(", "ARRAYTOTEXT(", "VALUETOTEXT(", "FILTER(", "SORT(", "SORTBY(", "TEXTSPLIT(",
           "REGEXTEST(", "REGEXEXTRACT(", "REGEXREPLACE(")


@pytest.fixture(scope="module")
def report(corpus_audits):
    return corpus_audits[CORPUS.name].report


@pytest.fixture(scope="module")
def texts():
    """{cell as the report names it: formula text} of formulas__test.xlsx."""
    from workbook_gen.auditor.inputs import read_inputs
    inputs = read_inputs(CORPUS)
    return {name: inputs.text_of(key).upper() for name, key in inputs.cell_keys().items()}


def test_lambda_cells_saved_by_excel_are_recomputed_and_agree(report, texts):
    cells = {name for name, text in texts.items() if any(f in text for f in FAMILY)}
    assert len(cells) >= 100
    disagree = {m.cell for m in report.mismatches} & cells
    assert disagree == set(), sorted(disagree)[:10]
    # left: a LAMBDA called inline (``LAMBDA(x, x+1)(2)``: the parser does not read a call
    # of a call) and a workbook-defined LAMBDA name (MYLAMBDA)
    unchecked = {c: r for c, r in report.not_checked.items() if c in cells}
    assert len(unchecked) <= 3, unchecked
    assert not any("_xlpm." in f.message for f in report.findings)


def test_array_shaping_cells_saved_by_excel_are_recomputed_and_agree(report, texts):
    cells = {name for name, text in texts.items() if any(f in text for f in SHAPING)}
    assert len(cells) >= 200
    assert {m.cell for m in report.mismatches} & cells == set()
    assert not any(c in cells for c in report.not_checked)


@pytest.mark.parametrize("formula, value", [
    ("_xlfn.LET(_xlpm.x,5,_xlpm.y,_xlpm.x*2,_xlpm.x+_xlpm.y)", 15.0),
    ("_xlfn.REDUCE(0,{1,2,3},_xlfn.LAMBDA(_xlpm.a,_xlpm.b,_xlpm.a+_xlpm.b^2))", 14.0),
    ("SUM(_xlfn.MAKEARRAY(2,3,_xlfn.LAMBDA(_xlpm.r,_xlpm.c,_xlpm.r*_xlpm.c)))", 18.0),
    ("SUM(_xlfn.BYROW({1,2;3,4},_xleta.MAX))", 6.0),
    ("SUM(_xlfn.MAP({1,2},{3,4},_xlfn.LAMBDA(_xlpm.a,_xlpm.b,_xlpm.a*_xlpm.b)))", 11.0),
    ("_xlfn.LAMBDA(_xlpm.a,_xlpm.a)", lambdas.ExcelError.CALC),     # a LAMBDA left uncalled
    ("_xlfn.REDUCE(0,{1,2},_xlfn.LAMBDA(_xlpm.a,_xlpm.a))", lambdas.ExcelError.VALUE),  # arity
    ("SUM(_xlfn.TAKE(_xlfn.SEQUENCE(4,3),-2,2))", 4 + 5 + 7 + 8 + 10 + 11 - 4 - 5),
    ("SUM(_xlfn.CHOOSECOLS(_xlfn.SEQUENCE(2,3),-1,1))", 3 + 6 + 1 + 4),
    ("ROWS(_xlfn.VSTACK({1,2},{3;4;5}))", 4.0),
    ('_xlfn.TEXTAFTER("a-b-c","-",-1)', "c"),
    ('_xlfn.TEXTBEFORE("a-b-c","-",2)', "a-b"),
    ('_xlfn.ARRAYTOTEXT({1,"x";TRUE,2},1)', '{1,"x";TRUE,2}'),
    ("SUM(_xlfn._xlws.FILTER({1,2,3,4},{1,0,1,0}))", 4.0),
    ('_xlfn._xlws.FILTER({1,2},{0,0},"none")', "none"),
    ('INDEX(_xlfn._xlws.SORT({3;"a";1;TRUE}),2)', 3.0),
    ('ROWS(_xlfn.UNIQUE({"a";"A";"b";1;1}))', 3.0),
    ('COLUMNS(_xlfn.TEXTSPLIT("a,b,,c",","))', 4.0),
    ("INDEX(_xlfn.SORTBY({10;20;30},{2;3;1}),1)", 30.0),
    ("INDEX(_xlfn.SORTBY({10;20;30},{1;1;2},-1,{3;2;1},1),2)", 20.0),
    ('COLUMNS(_xlfn.TEXTSPLIT("a,b,,c",",",,TRUE))', 3.0),
    ('_xlfn.REGEXREPLACE("2024-01-31","(\\d+)-(\\d+)-(\\d+)","$3/$2/$1")', "31/01/2024"),
    ('_xlfn.REGEXEXTRACT("ab12cd345","[0-9]+")', "12"),
    ('_xlfn.REGEXTEST("Hello","^h",1)', True),
    ('_xlfn.REGEXTEST("Hello","(")', lambdas.ExcelError.VALUE),
])
def test_lambda_family_by_hand(formula, value):
    assert evaluate(parse(formula), DictResolver({})) == value
