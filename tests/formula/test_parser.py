"""Tokenizer, parser, printer and reference transforms of the Excel formula language.

Stage table in the style of pycel's formula tests: formula -> tokens -> tree shape.
Tree shapes are written by hand from Excel's documented precedence (unary minus
above %, % above ^, ^ left-associative), not read off our own output.
"""

from __future__ import annotations

import pytest
from openpyxl.formula.tokenizer import Tokenizer as OpenpyxlTokenizer

from workbook_gen.errors import FormulaSyntaxError
from workbook_gen.formula import (
    Binary, CellRef, Name, Number, Paren, RangeRef, Unary, ast, parse, render, render_formula,
    shift, to_relative, tokenize,
)
from workbook_gen.formula.tokenizer import Tokenizer


def sexpr(node) -> str:
    """A compact, printer-independent shape of a tree."""
    if isinstance(node, ast.Number):
        return repr(node.value)
    if isinstance(node, ast.String):
        return '"' + node.value + '"'
    if isinstance(node, ast.Bool):
        return str(node.value).upper()
    if isinstance(node, ast.ErrorLit):
        return node.error.value
    if isinstance(node, ast.Missing):
        return "<missing>"
    if isinstance(node, ast.CellRef):
        row_abs, col_abs = ("$" if node.row_abs else ""), ("$" if node.col_abs else "")
        return f"<{node.sheet or ''}!R{node.row}{row_abs}C{node.col}{col_abs}>"
    if isinstance(node, ast.RangeRef):
        return f"<{node.sheet or ''}!{sexpr(node.first)}:{sexpr(node.last)}>"
    if isinstance(node, ast.Name):
        return f"name:{node.name}"
    if isinstance(node, ast.Func):
        return "(" + " ".join([node.name] + [sexpr(a) for a in node.args]) + ")"
    if isinstance(node, ast.Unary):
        return f"(u{node.op} {sexpr(node.operand)})"
    if isinstance(node, ast.Percent):
        return f"(% {sexpr(node.operand)})"
    if isinstance(node, ast.Binary):
        return f"({node.op} {sexpr(node.left)} {sexpr(node.right)})"
    if isinstance(node, ast.Paren):
        return f"[{sexpr(node.inner)}]"
    if isinstance(node, ast.RefOp):
        return f"('{node.op}' {sexpr(node.left)} {sexpr(node.right)})"
    raise TypeError(node)


def token_line(formula: str) -> str:
    return " | ".join(f"{t.kind} {t.text}" for t in tokenize(formula) if t.kind != "START")


# formula, tokens, tree
STAGES = [
    ("=-2^2", "PREFIX - | NUMBER 2 | INFIX ^ | NUMBER 2", "(^ (u- 2.0) 2.0)"),
    ("=-A1^2", "PREFIX - | REF A1 | INFIX ^ | NUMBER 2", "(^ (u- <!R1C1>) 2.0)"),
    ("=0-2^2", "NUMBER 0 | INFIX - | NUMBER 2 | INFIX ^ | NUMBER 2", "(- 0.0 (^ 2.0 2.0))"),
    ("=2^-2", "NUMBER 2 | INFIX ^ | PREFIX - | NUMBER 2", "(^ 2.0 (u- 2.0))"),
    ("=-2%^2", "PREFIX - | NUMBER 2 | POSTFIX % | INFIX ^ | NUMBER 2", "(^ (% (u- 2.0)) 2.0)"),
    ("=2^3^2", "NUMBER 2 | INFIX ^ | NUMBER 3 | INFIX ^ | NUMBER 2", "(^ (^ 2.0 3.0) 2.0)"),
    ("=2^-1+1", "NUMBER 2 | INFIX ^ | PREFIX - | NUMBER 1 | INFIX + | NUMBER 1",
     "(+ (^ 2.0 (u- 1.0)) 1.0)"),
    ("=1+2*3", "NUMBER 1 | INFIX + | NUMBER 2 | INFIX * | NUMBER 3", "(+ 1.0 (* 2.0 3.0))"),
    ("=(1+2)*3", "OPEN ( | NUMBER 1 | INFIX + | NUMBER 2 | CLOSE ) | INFIX * | NUMBER 3",
     "(* [(+ 1.0 2.0)] 3.0)"),
    ("=1-2-3", "NUMBER 1 | INFIX - | NUMBER 2 | INFIX - | NUMBER 3", "(- (- 1.0 2.0) 3.0)"),
    ("=8/4/2", "NUMBER 8 | INFIX / | NUMBER 4 | INFIX / | NUMBER 2", "(/ (/ 8.0 4.0) 2.0)"),
    ("=1+2&3", "NUMBER 1 | INFIX + | NUMBER 2 | INFIX & | NUMBER 3", "(& (+ 1.0 2.0) 3.0)"),
    ('="a"&"b"="AB"', 'STRING "a" | INFIX & | STRING "b" | INFIX = | STRING "AB"',
     '(= (& "a" "b") "AB")'),
    ("=A1<=B$2", "REF A1 | INFIX <= | REF B$2", "(<= <!R1C1> <!R2$C2>)"),
    ("=1<>2", "NUMBER 1 | INFIX <> | NUMBER 2", "(<> 1.0 2.0)"),
    ("=--1", "PREFIX - | PREFIX - | NUMBER 1", "(u- (u- 1.0))"),
    ("=+A1", "PREFIX + | REF A1", "(u+ <!R1C1>)"),
    ("=2*3%", "NUMBER 2 | INFIX * | NUMBER 3 | POSTFIX %", "(* 2.0 (% 3.0))"),
    ("=1E-05+.5+1e+3", "NUMBER 1E-05 | INFIX + | NUMBER .5 | INFIX + | NUMBER 1e+3",
     "(+ (+ 1e-05 0.5) 1000.0)"),
    ('="a""b"', 'STRING "a""b"', '"a"b"'),
    ("=TRUE", "BOOL TRUE", "TRUE"),
    ("=#DIV/0!", "ERROR #DIV/0!", "#DIV/0!"),
    ("=#N/A", "ERROR #N/A", "#N/A"),
    ("=#NAME?", "ERROR #NAME?", "#NAME?"),
    ("=$A$2:$A$38", "REF $A$2:$A$38", "<!<!R2$C1$>:<!R38$C1$>>"),
    ("=Table!B2", "REF Table!B2", "<Table!R2C2>"),
    ("='Other Sheet'!A1", "REF 'Other Sheet'!A1", "<Other Sheet!R1C1>"),
    ("='It''s'!A1", "REF 'It''s'!A1", "<It's!R1C1>"),
    ("=Table!A2:A38", "REF Table!A2:A38", "<Table!<!R2C1>:<!R38C1>>"),
    ("=XFD1048576", "REF XFD1048576", "<!R1048576C16384>"),
    ("=XFE1", "NAME XFE1", "name:XFE1"),
    ("=A1048577", "NAME A1048577", "name:A1048577"),
    ("=l_AB*omega_1", "NAME l_AB | INFIX * | NAME omega_1", "(* name:l_AB name:omega_1)"),
    ("=_x+check_tol", "NAME _x | INFIX + | NAME check_tol", "(+ name:_x name:check_tol)"),
    ("=PI()", "FUNC PI( | CLOSE )", "(PI)"),
    ("=LOG10(100)", "FUNC LOG10( | NUMBER 100 | CLOSE )", "(LOG10 100.0)"),
    ("=_xlfn.ATAN2(1,2)", "FUNC _xlfn.ATAN2( | NUMBER 1 | SEP , | NUMBER 2 | CLOSE )",
     "(ATAN2 1.0 2.0)"),
    ("=IF(A1,,2)", "FUNC IF( | REF A1 | SEP , | SEP , | NUMBER 2 | CLOSE )",
     "(IF <!R1C1> <missing> 2.0)"),
    ("=SUM(MAX(1,2),-MIN(3))",
     "FUNC SUM( | FUNC MAX( | NUMBER 1 | SEP , | NUMBER 2 | CLOSE ) | SEP , | PREFIX - "
     "| FUNC MIN( | NUMBER 3 | CLOSE ) | CLOSE )",
     "(SUM (MAX 1.0 2.0) (u- (MIN 3.0)))"),
]


@pytest.mark.parametrize("formula,tokens,tree", STAGES, ids=[s[0] for s in STAGES])
def test_stage_tokens_and_tree(formula, tokens, tree):
    assert token_line(formula) == tokens
    assert sexpr(parse(formula)) == tree


ROUND_TRIP = [s[0] for s in STAGES] + [
    "=l_AB*SIN(RADIANS(A2))-POWER(l_BC^2-(l_AB*COS(RADIANS(A2)))^2,0.5)",
    '=IF(Table!$AB2="ok",SQRT((Table!B2-x_F)^2+(Table!C2-y_F)^2)-l_FG,"")',
    "=INDEX(Table!$A$2:$A$38,MATCH(B2,Table!C$2:C$38,0))",
    "=DEGREES(ATAN2(-x_F,-y_F)+ATAN2(-x_F*(H2-x_F)-y_F*(I2-y_F),-x_F*(I2-y_F)+y_F*(H2-x_F)))",
    "=IFERROR(ACOS((l_AB^2+l_BC^2-D2^2)/(2*l_AB*l_BC)),#NUM!)",
    "=IF(AND(ABS(B2)<=check_tol,NOT(ISERROR(C2))),\"PASS\",\"FAIL\")",
    "=MOD(DEGREES(ATAN2(E2-x_A,F2-y_A))+360,360)",
    "=-SIGN(l_AB)*PI()/180*omega_1%",
    "=MAX(Checks!B2:B38)&\" mm\"",
    "='Other Sheet'!$A$1+'It''s'!B$3-'2019'!C4",
    "=_xlfn.ATAN2(1,1)",
    "=(((1)))",
    "=A1>=B1",
    "=\"\"",
]
# references and constants of foreign workbooks (openpyxl's tokenizer splits some otherwise)
FOREIGN = [
    "=SUM(A:A)+SUM($D:$E)-SUM(2:2)+SUM($3:$4)",
    "=SUM(Sheet1:Sheet3!A1)+SUM('My Sheet:Other'!B2:C3)",
    "=SUM(INDEX(A1:A5,2):INDEX(A1:A5,4))",
    "=SUM(A1:C3 B2:D4)",
    "=SUM((A1,B1:B3,C2))",
    '={1,-2.5;"a",TRUE}',
    "=SUM(Table1[Amount])+Table1[[#This Row],[x]]*[@y]+SUM(Table1[#All])",
    "=IFERROR(#SPILL!,#CALC!)",
    "=vaPr\u00fcfzeit+_2\u00e8me_x+PDOC\\10_1.x",
]


@pytest.mark.parametrize("formula", ROUND_TRIP + FOREIGN)
def test_render_gives_back_the_formula(formula):
    node = parse(formula)
    assert render(node) == formula[1:]
    assert render_formula(node) == formula
    assert parse(render(node)) == node


def test_render_of_long_generated_formula():
    terms = "+".join(f"(Table!B{r}-x_F)^2*SIN(RADIANS($A{r}))" for r in range(2, 200))
    formula = f"=SQRT({terms})-l_FG"
    assert render(parse(formula)) == formula[1:]


@pytest.mark.parametrize("formula", ROUND_TRIP + FOREIGN + [
    "= SUM( A1 , 'It''s'!B2:C3 ) +\n1",
    "=  -2 ^ 2 % ",
    '=IF( A1 = "a  b" , 1 , 2 )',
])
def test_tokenizer_is_lossless_with_whitespace(formula):
    assert Tokenizer(formula).render() == formula
    assert "".join(t.text for t in tokenize(formula)) == formula


def test_whitespace_does_not_change_the_tree():
    assert parse("= SUM( A1 , 'It''s'!B2:C3 ) +\n1") == parse("=SUM(A1,'It''s'!B2:C3)+1")
    assert parse("=  -2 ^ 2 % ") == parse("=-2^2%")


@pytest.mark.parametrize("formula", [f for f in ROUND_TRIP if "''" not in f] + [
    "=SUM(A1:B2)+1", "=-2%^2"])
def test_token_texts_agree_with_openpyxl(formula):
    """openpyxl's tokenizer (an independent implementation) splits the same way."""
    theirs = [t.value for t in OpenpyxlTokenizer(formula).items]
    ours = [t.text for t in tokenize(formula) if t.kind != "START"]
    assert ours == theirs


# formula, message
SYNTAX_ERRORS = [
    ("=SQRT(B2^2+C2^2))", "unexpected ')' at position 16 in '=SQRT(B2^2+C2^2))'"),
    ("=1+*2", "unexpected '*' at position 3 in '=1+*2'"),
    ("=1+", "unexpected end of formula in '=1+'"),
    ("=SUM(1,2", "unclosed 'SUM(' at position 1 in '=SUM(1,2'"),
    ("=(1+2", "unclosed '(' at position 1 in '=(1+2'"),
    ("=SUM(A1:)", "unexpected ')' at position 8"),
    ("={1,A1}", "an array constant holds only numbers, text, TRUE/FALSE and errors"),
    ("={1,2;3}", "array constant rows differ in length"),
    ("=[1]+1", "external reference (to another workbook)"),  # ([1]Sheet1!A1 parses)
    ('="abc', "unterminated string at position 1"),
    ("=#FOO!", "unknown error literal at position 1"),
    ("=1;2", "unexpected ';'"),
    ("=", "empty formula"),
    ("=A1:", "unexpected end of formula"),
]


@pytest.mark.parametrize("formula,message", SYNTAX_ERRORS)
def test_syntax_error_says_what_and_where(formula, message):
    with pytest.raises(FormulaSyntaxError) as info:
        parse(formula)
    assert message in str(info.value)


@pytest.mark.parametrize("formula,tree", [
    ("=A1:A3 B2:C2", "(' ' <!<!R1C1>:<!R3C1>> <!<!R2C2>:<!R2C3>>)"),
    ("=-A1:INDEX(B1:B3,2)", "(u- (':' <!R1C1> (INDEX <!<!R1C2>:<!R3C2>> 2.0)))"),
    ("=(A1,B1)", "[(',' <!R1C1> <!R1C2>)]"),
])
def test_reference_operators_bind_tighter_than_signs(formula, tree):
    assert sexpr(parse(formula)) == tree


def test_whole_columns_and_rows_span_the_sheet_and_keep_their_text():
    col = parse("=$B:C")
    assert (col.first.row, col.last.row, col.whole) == (1, 1_048_576, "col")
    row = parse("=2:$3")
    assert (row.first.col, row.last.col, row.whole) == (1, 16_384, "row")
    assert render(shift(parse("=SUM(B:B)"), 5, 1)) == "SUM(C:C)"
    assert render(shift(parse("=SUM(2:2)"), 1, 4)) == "SUM(3:3)"


def test_r1c1_key_groups_a_column_of_formulas():
    keys = {to_relative(parse(f"=INDEX(Table!$A$2:$A$38,MATCH(B{r},Table!C$2:C$38,0))"), r, 4)
            for r in range(2, 39)}
    assert keys == {"INDEX(Table!R2C1:R38C1,MATCH(RC[-2],Table!R2C[-1]:R38C[-1],0))"}


@pytest.mark.parametrize("formula,row,col,key", [
    ("=B2*2", 2, 3, "RC[-1]*2"),
    ("=B3*2", 3, 3, "RC[-1]*2"),
    ("=$A$1", 7, 7, "R1C1"),
    ("=A$1+$A5", 5, 3, "R1C[-2]+RC1"),
    ("=C4", 2, 1, "R[2]C[2]"),
])
def test_to_relative_uses_excel_r1c1(formula, row, col, key):
    assert to_relative(parse(formula), row, col) == key


def test_to_relative_differs_when_absolute_rows_differ():
    assert to_relative(parse("=A$2"), 3, 2) != to_relative(parse("=A$3"), 4, 2)


@pytest.mark.parametrize("formula,drow,dcol,expected", [
    ("=A2+$B$2+C$2+$D2", 1, 0, "A3+$B$2+C$2+$D3"),
    ("=A2+$B$2+C$2+$D2", 0, 1, "B2+$B$2+D$2+$D2"),
    ("=SUM(Table!B2:C3)", 2, 0, "SUM(Table!B4:C5)"),
    ("=A1", -1, 0, "#REF!"),
    ("=SUM(A1:B2)", 0, -1, "SUM(#REF!)"),
])
def test_shift_moves_only_relative_parts(formula, drow, dcol, expected):
    assert render(shift(parse(formula), drow, dcol)) == expected


def test_printer_adds_parentheses_missing_from_built_trees():
    one, two, three = Number(1.0), Number(2.0), Number(3.0)
    assert render(Binary("*", Binary("+", one, two), three)) == "(1+2)*3"
    assert render(Binary("-", one, Binary("-", two, three))) == "1-(2-3)"
    assert render(Binary("^", Binary("^", two, three), two)) == "2^3^2"
    assert render(Binary("^", two, Binary("^", three, two))) == "2^(3^2)"
    assert render(Unary("-", Binary("^", two, two))) == "-(2^2)"
    assert render(Binary("*", Paren(Binary("+", one, two)), three)) == "(1+2)*3"


def test_reference_nodes_print_with_quoted_sheets():
    cell = CellRef("Other Sheet", 2, 3, col_abs=True)
    assert render(cell) == "'Other Sheet'!$B3"
    assert render(CellRef("A1", 1, 1)) == "'A1'!A1"
    assert render(RangeRef("Table", CellRef(None, 1, 2), CellRef(None, 1, 38))) == "Table!A2:A38"
    assert render(Name("l_AB")) == "l_AB"


def test_long_operator_chain_parses_prints_and_shifts_without_recursion_limit():
    formula = "=" + "+".join(f"A{r}" for r in range(1, 3001))
    node = parse(formula)
    assert render(node) == formula[1:]
    assert render(shift(node, 1, 0)) == "+".join(f"A{r}" for r in range(2, 3002))


def test_nesting_too_deep_is_a_syntax_error_not_a_crash():
    with pytest.raises(FormulaSyntaxError, match="nested deeper than"):
        parse("=" + "(" * 1000 + "1" + ")" * 1000)
    assert render(parse("=" + "SIN(" * 64 + "1" + ")" * 64)) == "SIN(" * 64 + "1" + ")" * 64


def test_a_deleted_reference_on_a_named_sheet_is_ref_error():
    """Excel keeps the sheet of a deleted reference: 'OP LTR'!#REF! (closedxml__tdf111974)."""
    from workbook_gen.formula import ast as _ast
    from workbook_gen.xlerror import ExcelError as _E
    for text in ("'OP LTR'!#REF!", "Sheet1!#REF!"):
        assert parse(text) == _ast.ErrorLit(_E.REF)


def test_name_character_classes_are_the_documented_ranges_on_the_bmp():
    """The tokenizer's and printer's classes are spelled negated (cheap to compile); on
    the Basic Multilingual Plane each is exactly the range it stands for, and beyond it
    the tokenizer may only take more (a name), the printer only less (then it quotes)."""
    import re

    from workbook_gen.formula import printer, tokenizer

    word = tokenizer._WORD_RE.pattern
    plain = printer._PLAIN_SHEET.pattern
    cut = plain.index("]") + 1
    cases = [  # (the range spelling, the class used, beyond the BMP: "more" | "less" | "same")
        (r"[A-Za-z_\\\u00a1-\uffff]", tokenizer._FIRST, "same"),
        (r"[\w.\u00a1-\uffff]", tokenizer._NEXT, "more"),
        (r"[\w.(!\[\u00a1-\uffff]", tokenizer._END[3:-1], "more"),
        (r"[\w.?\\\u00a1-\uffff]", word[word.rindex("[^"):-1], "more"),
        (r"[A-Za-z_\u00a1-\uffff]", plain[:cut], "same"),
        (r"[\w.\u00a1-\uffff]", plain[cut:-1], "less"),
    ]
    beyond = "".join(map(chr, (0x10000, 0x1D465, 0x1F600, 0x20000, 0x10FFFF)))
    for spelled, used, outside in cases:
        want, got = re.compile(spelled), re.compile(used)
        bmp = "".join(map(chr, range(0x10000)))
        assert [m.start() for m in want.finditer(bmp)] == \
            [m.start() for m in got.finditer(bmp)], used
        for ch in beyond:
            w, g = bool(want.fullmatch(ch)), bool(got.fullmatch(ch))
            assert {"same": g == w, "more": g >= w, "less": g <= w}[outside], (used, ch)


@pytest.mark.parametrize("formula, texts", [
    ("Größe*2", ["Größe", "*", "2"]),
    ("'Größe'!A1+Δx", ["'Größe'!A1", "+", "Δx"]),
    ("Лист1!B2:C3", ["Лист1!B2:C3"]),
    ("名前.一&x\\y?", ["名前.一", "&", "x\\y?"]),
    ("A1é", ["A1é"]),  # a name, not A1 followed by a letter
])
def test_names_of_any_script_tokenize(formula, texts):
    assert [t.text for t in tokenize(formula)] == texts


@pytest.mark.parametrize("formula", ["A1:B2 B1:C2 B2:C3", "SUM( A1:B2  B1:C2 B2:C3 )",
                                     "AREAS((E4:H4 J4:K4 L4:O4))"])
def test_intersections_chain_left_to_right(formula):
    """Each space between references is the intersection operator, however many in a row
    (a space the operator's right operand ended on was lost before)."""
    node = parse(formula)
    found = [n for n in ast.walk(node) if isinstance(n, ast.RefOp) and n.op == " "]
    assert len(found) == 2
    outer = found[0]
    assert isinstance(outer.left, ast.RefOp) and outer.left.op == " "  # (a b) c
