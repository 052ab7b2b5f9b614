"""formula/functions/callables.py: a LAMBDA's Closure and a worksheet function named where a
LAMBDA is expected, called directly and through formulas, against Microsoft's documented
behaviour (support.microsoft.com, "LAMBDA function" and "MAP function": "an incorrect
number of parameters returns a #VALUE! error"; "BYROW function": an eta-reduced lambda such
as BYROW(A1:C2, SUM) calls the function on each row) and hand-derived values. (A LAMBDA
called inline, LAMBDA(x,y,x+y)(1,2), is not read by the parser: its calls are made here
through MAP.)"""

from __future__ import annotations

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.formula.functions.callables import Closure, Function
from workbook_gen.formula.scalar import Evaluator
from workbook_gen.formula.values import Range
from workbook_gen.xlerror import ExcelError


def evaluator():
    return Evaluator(DictResolver({}), "excel", None)


def test_a_closure_binds_its_parameters_over_its_environment():
    ev = evaluator()
    body = parse("X*10+Y+Z")
    f = Closure(["X", "Y"], body, ev, {"Z": 100.0, "Y": -1.0})
    assert f(2.0, 3.0) == 123.0              # the parameter Y hides the outer Y
    assert f(0.0, 0.0) == 100.0
    assert getattr(ev, "bound", None) is None  # restored after the call


def test_a_closure_restores_the_names_bound_before_it():
    ev = evaluator()
    ev.bound = {"W": 5.0}
    f = Closure(["X"], parse("X+1"), ev, {})
    assert f(1.0) == 2.0
    assert ev.bound == {"W": 5.0}


def test_a_closure_called_with_the_wrong_count_is_value_error():
    f = Closure(["X", "Y"], parse("X+Y"), evaluator(), {})
    assert f(1.0) is ExcelError.VALUE
    assert f(1.0, 2.0, 3.0) is ExcelError.VALUE


def test_a_named_function_is_called_with_the_values():
    ev = evaluator()
    assert Function("SUM", ev)(Range.of([[1.0, 2.0, 3.0]])) == 6.0
    assert Function("MAX", ev)(4.0, 9.0, 2.0) == 9.0
    assert Function("NOSUCHFN", ev)(1.0) is ExcelError.NAME
    assert Function("IF", ev)(True, 1.0, 2.0) is ExcelError.VALUE   # lazy: not as a value


@pytest.mark.parametrize("formula, expected", [
    ("=SUM(_xlfn.MAP({1,2},{10,20},_xlfn.LAMBDA(_xlpm.x,_xlpm.y,_xlpm.x+_xlpm.y)))", 33.0),
    # too few parameters (MAP's page: "an incorrect number of parameters returns #VALUE!")
    ("=INDEX(_xlfn.MAP({1,2},_xlfn.LAMBDA(_xlpm.x,_xlpm.y,_xlpm.x+_xlpm.y)),1)",
     ExcelError.VALUE),
    # k bound where the LAMBDA was written
    ("=INDEX(_xlfn.LET(_xlpm.k,10,_xlfn.MAP({1,2},_xlfn.LAMBDA(_xlpm.x,_xlpm.x*_xlpm.k))),2)",
     20.0),
    ("=SUM(BYROW(A1:C2,_xleta.SUM))", 21.0),              # eta-reduced: row sums 6 and 15
    ("=INDEX(BYROW(A1:C2,_xleta.MAX),2)", 6.0),
])
def test_through_formulas(formula, expected):
    book = DictResolver({"A1": 1.0, "B1": 2.0, "C1": 3.0, "A2": 4.0, "B2": 5.0, "C2": 6.0})
    assert evaluate(parse(formula), book) == expected
