"""The fast workbook evaluator: vector path against the scalar reference, cached values,
cycles, unsupported functions, long chains, defined names."""

from __future__ import annotations

import sys

import math

import openpyxl
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from workbook_gen.evaluator import evaluate_cells, expand_shared
from workbook_gen.formula import parse, render
from workbook_gen.xlerror import ExcelError

E = ExcelError


def same(a, b, rel=1e-15) -> bool:
    """Values equal to ``rel`` relative; errors, text and booleans identical."""
    if type(a) is float and type(b) is float:
        return a == b or abs(a - b) <= rel * max(abs(a), abs(b))
    return type(a) is type(b) and a == b


def assert_paths_agree(formulas, constants, names=None):
    fast = evaluate_cells(formulas, constants, names or {})
    slow = evaluate_cells(formulas, constants, names or {}, vectorize=False)
    assert slow.groups.vector_cells == 0
    for cell, text in formulas.items():
        assert same(fast.values[cell], slow.values[cell]), (cell, text, fast.values[cell],
                                                           slow.values[cell])
        assert same(fast.operands_scale[cell], slow.operands_scale[cell]), (cell, text)
    assert fast.unsupported == slow.unsupported
    return fast, slow


# -- generated workbooks --------------------------------------------------------------

def _cell_value(v):
    if isinstance(v, str) and ExcelError.from_text(v) is not None:
        return ExcelError.from_text(v)
    if isinstance(v, int) and not isinstance(v, bool):
        return float(v)
    return v


def read_xlsx(path):
    """Formulas, constants, defined names and cached values, read with openpyxl."""
    wb = openpyxl.load_workbook(path)
    cached_wb = openpyxl.load_workbook(path, data_only=True)
    formulas, constants, cached = {}, {}, {}
    for ws in wb.worksheets:
        for row in ws.iter_rows():
            for c in row:
                key = (ws.title, c.row, c.column)
                if isinstance(c.value, str) and c.value.startswith("="):
                    formulas[key] = c.value[1:]
                    cached[key] = _cell_value(cached_wb[ws.title].cell(c.row, c.column).value)
                elif c.value is not None:
                    constants[key] = _cell_value(c.value)
    names = {name: d.attr_text for name, d in wb.defined_names.items()}
    return formulas, constants, names, cached


@pytest.fixture(scope="module", params=["sewing_machine", "slider_crank"])
def generated(request, tmp_path_factory):
    from workbook_gen.scene import load_scene
    from workbook_gen.workbook import write_workbook

    scene = load_scene(f"templates/{request.param}.toml", step=5.0)
    path = write_workbook(scene, tmp_path_factory.mktemp(request.param))
    return read_xlsx(path)


def test_vector_and_scalar_paths_agree_on_generated_workbook(generated):
    formulas, constants, names, _ = generated
    fast, _ = assert_paths_agree(formulas, constants, names)
    # The Table's columns really went through the vector path.
    assert fast.groups.vector_cells > 0.9 * len(formulas)
    assert not fast.cycles and not fast.unsupported and not fast.syntax_errors


def _reads_range(text: str) -> bool:
    from workbook_gen.formula import RangeRef, walk

    return any(isinstance(n, RangeRef) for n in walk(parse(text)))


def _close_to_cached(value, cached, scale) -> bool:
    if cached is None:
        cached = ""  # openpyxl reads a cached empty text as None
    if type(value) is float and isinstance(cached, float):
        return abs(value - cached) <= 1e-13 * max(scale, abs(cached))
    return type(value) is type(cached) and value == cached


def test_recomputed_values_equal_cached_values(generated):
    formulas, constants, names, cached = generated
    result = evaluate_cells(formulas, constants, names)
    for cell, text in formulas.items():
        if _reads_range(text):
            continue  # checked one cell at a time below
        assert _close_to_cached(result.values[cell], cached[cell],
                                result.operands_scale[cell]), (cell, text)
    # Aggregates (MAX of residuals, the input where a maximum occurs) amplify the last-bit
    # differences of their inputs: each is recomputed from the cached values of its inputs.
    aggregates = {c: t for c, t in formulas.items() if _reads_range(t)}
    assert aggregates
    inputs = dict(constants)
    inputs.update({c: v for c, v in cached.items() if c not in aggregates})
    local = evaluate_cells(aggregates, inputs, names)
    for cell, text in aggregates.items():
        assert _close_to_cached(local.values[cell], cached[cell],
                                local.operands_scale[cell]), (cell, text)


# -- published Excel behaviour, per row of a vectorised column ------------------------

EXCEL_CASES = [  # formula of column B over A (A1=0, A2=-8, A3=2, A4=7) -> expected per row
    ("ATAN2(A1,A1)", [E.DIV0, math.atan2(-8, -8), math.atan2(2, 2), math.atan2(7, 7)]),
    ("-A1^2", [0.0, 64.0, 4.0, 49.0]),
    ("A1^(1/3)", [0.0, E.NUM, 2 ** (1 / 3), 7 ** (1 / 3)]),
    ("MOD(-7,A1)", [E.DIV0, -7.0, 1.0, 0.0]),
    ("SQRT(A1)", [0.0, E.NUM, math.sqrt(2), math.sqrt(7)]),
    ("ACOS(A1/4)", [math.acos(0), E.NUM, math.acos(0.5), E.NUM]),
    ("IF(A1>0,1/A1,\"neg\")", ["neg", "neg", 0.5, 1 / 7]),
    ("IFERROR(1/A1,-1)", [-1.0, -0.125, 0.5, 1 / 7]),
    ("A1&\"x\"", ["0x", "-8x", "2x", "7x"]),
    ("A1%^2", [0.0, 0.0064, 0.0004, 0.0049]),
    ("AND(A1,TRUE)", [False, True, True, True]),
    ("A1=FALSE", [False, False, False, False]),
    ("MAX($A$1:$A$4)-A1", [7.0, 15.0, 5.0, 0.0]),
]


@pytest.mark.parametrize("formula, expected", EXCEL_CASES)
def test_vector_column_follows_excel(formula, expected):
    constants = {("S", r, 1): v for r, v in enumerate([0.0, -8.0, 2.0, 7.0], start=1)}
    node = parse(formula)
    from workbook_gen.formula import shift

    formulas = {("S", r, 2): render(shift(node, r - 1, 0)) for r in range(1, 5)}
    fast, _ = assert_paths_agree(formulas, constants)
    assert fast.groups.vector_groups == 1
    for r, want in enumerate(expected, start=1):
        got = fast.values[("S", r, 2)]
        assert same(got, want, 1e-15) or (type(got) is float and abs(got - want) < 1e-15), \
            (formula, r, got, want)


# -- every operator and function over a grid of awkward operands ------------------------

SPECIAL = [0.0, -0.5, 1.0, 2.0, -3.0, 7.25, 1e-3, -8.0, 2.0 ** 27, 1e3, 1 / 3, E.NA, E.DIV0]
AWKWARD = SPECIAL + ["txt", "", "12", True, False, None]
GRID_FORMULAS = (
    [f"{f}(A{{r}})" for f in ("SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "SQRT", "ABS",
                                "SIGN", "RADIANS", "DEGREES", "ISERROR", "NOT")]
    + [f"A{{r}}{op}B{{r}}" for op in ("+", "-", "*", "/", "^", "&", "=", "<>", "<", ">",
                                      "<=", ">=")]
    + [f"{f}(A{{r}},B{{r}})" for f in ("ATAN2", "MOD", "POWER", "IFERROR", "AND", "OR")]
    + ["-A{r}", "A{r}%", "IF(A{r}>B{r},A{r},B{r})", "IF(A{r},A{r})", "IFERROR(A{r}/B{r},\"x\")",
       "MIN(A{r},B{r},$A$1:$A$3)", "MAX(A{r},B{r})", "SUM(A{r},B{r},A{r})", "SUM(A{r})",
       "(A{r}>0)+B{r}", "A{r}<(B{r}>0)", "(A{r}>0)>=B{r}", "INDEX($B$1:$B$9,A{r})", "MATCH(A{r},$B$1:$B$20,0)"]
)


@pytest.mark.parametrize("grid", [SPECIAL, AWKWARD], ids=["numbers", "mixed"])
@pytest.mark.parametrize("formula", GRID_FORMULAS)
def test_every_function_on_awkward_operands_agrees_with_scalar(formula, grid):
    pairs = [(a, b) for a in grid for b in grid]
    constants = {}
    for r, (a, b) in enumerate(pairs, start=1):
        for c, v in ((1, a), (2, b)):
            if v is not None:
                constants[("S", r, c)] = v
    formulas = {("S", r, 3): formula.format(r=r) for r in range(1, len(pairs) + 1)}
    fast, _ = assert_paths_agree(formulas, constants)
    assert fast.groups.vector_cells == len(pairs)


# -- random formula columns ----------------------------------------------------------

numbers = st.one_of(
    st.floats(-1e3, 1e3, allow_nan=False).map(lambda x: float(x)),
    st.sampled_from([0.0, -0.5, 1.0, 2.0, -3.0]),
    st.sampled_from([E.NA, E.DIV0, E.NUM]),
)
values = st.one_of(   # numbers, errors, text, booleans and empties
    numbers,
    st.sampled_from(["txt", "", "12", " 2.5 ", "TRUE", "OK"]),
    st.booleans(), st.none(),
    st.sampled_from([E.NA, E.DIV0, E.NUM, E.VALUE]),
)
REFS = ["A{r}", "B{r}", "C{r}", "D{r}", "A{n}", "$B$1", "C$2", "k", "Sheet1!D{r}"]
LEAVES = st.one_of(
    st.sampled_from(REFS),
    st.sampled_from(["0", "2", "0.5", "1E-3", "\"ok\"", "\"\"", "TRUE", "FALSE", "#N/A", "PI()"]),
)
F1 = ["SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "SQRT", "ABS", "SIGN", "RADIANS",
      "DEGREES", "ISERROR", "NOT"]
F2 = ["ATAN2", "MOD", "POWER", "IFERROR"]
OPS = ["+", "-", "*", "/", "^", "&", "=", "<>", "<", ">", "<=", ">="]


def _tree(children):
    return st.one_of(
        st.tuples(st.sampled_from(OPS), children, children).map(lambda t: f"({t[1]}{t[0]}{t[2]})"),
        children.map(lambda a: f"-{a}"),
        children.map(lambda a: f"{a}%"),
        st.tuples(st.sampled_from(F1), children).map(lambda t: f"{t[0]}({t[1]})"),
        st.tuples(st.sampled_from(F2), children, children).map(lambda t: f"{t[0]}({t[1]},{t[2]})"),
        st.tuples(children, children, children).map(lambda t: f"IF({t[0]},{t[1]},{t[2]})"),
        st.tuples(children, children).map(lambda t: f"IF({t[0]},{t[1]})"),
        st.tuples(st.sampled_from(["AND", "OR", "MIN", "MAX", "SUM"]),
                  st.lists(st.one_of(children, st.just("$A$1:$B$3")), min_size=1, max_size=3))
        .map(lambda t: f"{t[0]}({','.join(t[1])})"),
        children.map(lambda a: f"INDEX($A$1:$A$4,{a})"),
        children.map(lambda a: f"MATCH({a},$C$1:$C$5,0)"),
    )


formulas_text = st.recursive(LEAVES, _tree, max_leaves=12)
numeric_formulas = st.recursive(
    st.one_of(st.sampled_from(REFS), st.sampled_from(["0", "2", "0.5", "1E-3", "TRUE", "PI()"])),
    _tree, max_leaves=12)
ROWS = 6


def _check_random_column(formula, data, k):
    constants = {("Sheet1", r, c): data[(r - 1) * 4 + c - 1]
                 for r in range(1, ROWS + 2) for c in range(1, 5)}
    constants = {key: v for key, v in constants.items() if v is not None}
    constants[("P", 1, 1)] = k
    formulas = {("Sheet1", r, 6): formula.format(r=r, n=r + 1) for r in range(1, ROWS + 1)}
    fast, _ = assert_paths_agree(formulas, constants, {"k": "P!$A$1"})
    assert fast.groups.vector_groups + fast.groups.scalar_cells >= 1


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(formula=formulas_text,
       data=st.lists(values, min_size=4 * (ROWS + 1), max_size=4 * (ROWS + 1)),
       k=values)
def test_random_formula_columns_agree_with_scalar(formula, data, k):
    _check_random_column(formula, data, k)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(formula=numeric_formulas,
       data=st.lists(numbers, min_size=4 * (ROWS + 1), max_size=4 * (ROWS + 1)),
       k=numbers)
def test_random_numeric_columns_agree_with_scalar(formula, data, k):
    """Numbers and errors only: the numpy kernels, not the per-element fallback."""
    _check_random_column(formula, data, k)


# -- graph: cycles, chains, names ---------------------------------------------------------

def test_cycle_is_reported_once_and_not_looped_on():
    formulas = {("S", 1, 1): "B1", ("S", 1, 2): "A1+1", ("S", 1, 3): "A1*2", ("S", 2, 1): "7"}
    result = evaluate_cells(formulas, {}, {})
    assert result.cycles == [[("S", 1, 1), ("S", 1, 2)]]
    # Excel with iteration off: 0 on the cycle and in what reads it
    assert result.values[("S", 1, 1)] == 0.0 and result.values[("S", 1, 2)] == 0.0
    assert result.values[("S", 1, 3)] == 0.0   # reads a cell of the cycle
    assert result.values[("S", 2, 1)] == 7.0


def test_self_reference_is_a_cycle():
    result = evaluate_cells({("S", 1, 1): "A1+1"}, {}, {})
    assert result.cycles == [[("S", 1, 1)]]


def test_unsupported_function_is_reported_by_cell_and_gives_name_error():
    formulas = {("S", r, 2): f"WEBSERVICE(A{r},$A$1:$A$3,1)+1" for r in (1, 2, 3)}
    formulas[("S", 1, 3)] = "NOW()"
    formulas[("S", 2, 3)] = "IF(A2>0,1,RAND())"
    constants = {("S", r, 1): float(r) for r in (1, 2, 3)}
    result = evaluate_cells(formulas, constants, {})
    for r in (1, 2, 3):
        assert result.unsupported[("S", r, 2)] == ["WEBSERVICE"]
        assert result.values[("S", r, 2)] is ExcelError.NAME
    assert result.volatile == {("S", 1, 3): ["NOW"], ("S", 2, 3): ["RAND"]}
    assert result.values[("S", 2, 3)] == 1.0   # IF evaluates only the branch it takes


def test_external_reference_and_syntax_error_are_reported():
    formulas = {("S", 1, 1): "[1]Sheet1!A1+1", ("S", 2, 1): "'[2]Data'!B2*2",
                ("S", 3, 1): "SQRT(A1))"}
    result = evaluate_cells(formulas, {}, {})
    assert result.external == [("S", 1, 1), ("S", 2, 1)]
    assert list(result.syntax_errors) == [("S", 3, 1)]
    assert "unexpected ')'" in result.syntax_errors[("S", 3, 1)]


@pytest.mark.parametrize("vectorize", [True, False])
def test_a_chain_far_deeper_than_the_recursion_limit_does_not_crash(vectorize):
    n = 25_000  # each cell needs the one above: no recursion, no stack to overflow
    assert n > 20 * sys.getrecursionlimit()
    formulas = {("S", r, 1): f"A{r - 1}+1" for r in range(2, n + 1)}
    result = evaluate_cells(formulas, {("S", 1, 1): 1.0}, {}, vectorize=vectorize)
    assert result.values[("S", n, 1)] == float(n)
    assert not result.cycles


def test_columns_chaining_each_other_down_the_rows():
    # Euler steps: x[r] = x[r-1] + v[r-1]*h, v[r] = v[r-1] - x[r]*h. The two columns
    # depend on each other (a cycle of runs), the cells do not.
    n, h = 50, 0.1
    formulas = {}
    for r in range(2, n + 1):
        formulas[("S", r, 1)] = f"A{r - 1}+B{r - 1}*h"
        formulas[("S", r, 2)] = f"B{r - 1}-A{r}*h"
    result = evaluate_cells(formulas, {("S", 1, 1): 1.0, ("S", 1, 2): 0.0, ("P", 1, 1): h},
                            {"h": "P!$A$1"})
    x, v = 1.0, 0.0
    for r in range(2, n + 1):
        x = x + v * h
        v = v - x * h
        assert result.values[("S", r, 1)] == x and result.values[("S", r, 2)] == v
    assert not result.cycles


def test_whole_workbook_with_names():
    constants = {("Parameters", 2, 2): 3.0, ("Parameters", 3, 2): 4.0,
                 ("Data", 1, 1): 1.0, ("Data", 2, 1): 5.0, ("Data", 3, 1): -2.0}
    names = {"a": "Parameters!$B$2", "b": "'Parameters'!$B$3", "half": "0.5",
             "data": "Data!$A$1:$A$3", "twice_a": "2*a"}
    constants.update({("Table", r, 3): float(r) for r in range(1, 4)})
    formulas = {("Table", r, 1): f"SQRT(a^2+b^2)*half*C{r}" for r in range(1, 4)}
    formulas[("Table", 1, 2)] = "MAX(data)+SUM(data)+twice_a"
    formulas[("Table", 2, 2)] = "INDEX(data,MATCH(MIN(data),data,0))*A2"
    formulas[("Table", 3, 2)] = "nowhere+1"
    result = evaluate_cells(formulas, constants, names)
    assert [result.values[("Table", r, 1)] for r in (1, 2, 3)] == [2.5, 5.0, 7.5]
    assert result.values[("Table", 1, 2)] == 5.0 + 4.0 + 6.0
    assert result.values[("Table", 2, 2)] == -2.0 * 5.0
    assert result.values[("Table", 3, 2)] is ExcelError.NAME
    assert result.operands_scale[("Table", 2, 1)] == 4.0   # a, b, half, 2, C2 -> 4
    assert result.groups.vector_groups == 1


def test_expand_shared_follower_from_master():
    assert expand_shared("A2*$B$1+C2", 2, 4, 5, 5) == "B5*$B$1+D5"
