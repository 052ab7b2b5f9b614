"""base: what a template is.  Hand-derived values: options' acceptance, the headers,
the n/a text and the speed scale evaluated at 50 digits (mpmath), the construction's
reference check (a column may use only the parameters and the columns before it), and
option configuration done once per (template, options)."""

from __future__ import annotations

import mpmath
import pytest

from workbook_gen.expr import Num, Param, Text, Var
from workbook_gen.expr.precise import compile_mpmath
from workbook_gen.mechanisms.base import (Check, Condition, InputSpec, OptionSpec, ParamSpec,
                                          Quantity, Template, only_if, quantity_vars,
                                          slide_charts, speed_scale, symbols, turn_charts)


def test_option_problems():
    text = OptionSpec("branch", "open", "", choices=("open", "crossed"))
    assert text.problem("crossed") is None
    assert text.problem("x") == "must be one of open, crossed"
    flag = OptionSpec("balance", False, "")
    assert flag.problem(True) is None and flag.problem(1) == "must be true or false"
    count = OptionSpec("iterations", 8, "", minimum=1, maximum=20)
    assert count.problem(1) is None and count.problem(20) is None
    assert count.problem(0) == "must be >= 1" and count.problem(21) == "must be <= 20"
    assert count.problem(True) == "must be an integer"   # bool is an int in Python
    assert count.problem(2.0) == "must be an integer"
    assert OptionSpec("n", 3, "").problem(-10**6) is None  # no bounds


def test_header_and_symbols():
    assert Quantity("y_C", "mm", Num(0), "").header == "y_C [mm]"
    assert Quantity("status", "", Num(0), "").header == "status"
    a, b = symbols("l_AB l_BC")
    assert a == Param("l_AB") and b == Param("l_BC")
    assert quantity_vars("x y") == (Var("x"), Var("y"))


def _ev(node, values=None, params=None):
    with mpmath.workdps(50):
        return compile_mpmath(node)(values or {}, params or {})


def test_only_if_gives_the_text_where_the_condition_fails():
    node = only_if(Param("k") * 2, Var("ok"), "balance = true")
    assert _ev(node, {"ok": True}, {"k": mpmath.mpf(3)}) == 6
    assert _ev(node, {"ok": False}, {"k": mpmath.mpf(3)}) == "n/a: needs balance = true"


def test_speed_scale_is_one_at_zero_speed():
    s = speed_scale(Param("omega"))
    assert _ev(s, params={"omega": mpmath.mpf(0)}) == 1
    assert _ev(s, params={"omega": mpmath.mpf("-2.5")}) == mpmath.mpf("-2.5")


def test_charts_units():
    s, v, a = slide_charts("needle", "theta", ("y_C", "v_C", "a_C"), unit="m")
    assert (s.y_title, v.y_title, a.y_title) == ("y_C [m]", "v_C [m/s]", "a_C [m/s^2]")
    assert s.title == "needle displacement" and s.x == "theta" and s.ys == ("y_C",)
    t, w, al = turn_charts("lever", "theta", ("th", "om", "al"))
    assert (t.y_title, w.y_title, al.y_title) == ("th [deg]", "om [rad/s]", "al [rad/s^2]")


def _template(quantities, checks=(), conditions=(), configure=None, options=()):
    kw = {"configure": configure} if configure else {}
    return Template("t", "T", "d", InputSpec("x", "deg", ""), (ParamSpec("k", 2.0, "mm", ""),),
                    tuple(quantities), Text("ok"), checks=tuple(checks),
                    conditions=tuple(conditions), options=tuple(options), **kw)


def test_a_column_may_use_only_earlier_columns_and_known_parameters():
    fine = _template([Quantity("a", "mm", Param("k") * Var("x"), ""),
                      Quantity("b", "mm", Var("a") + 1, "", output=False)])
    assert fine.outputs == ("a",) and fine.defaults == {"k": 2.0}
    assert fine.quantity("b").output is False
    with pytest.raises(KeyError):
        fine.quantity("c")
    with pytest.raises(ValueError, match=r"template t: a refers to unknown \['b'\]"):
        _template([Quantity("a", "mm", Var("b"), ""), Quantity("b", "mm", Num(1), "")])
    with pytest.raises(ValueError, match=r"unknown \['q'\]"):
        _template([Quantity("a", "mm", Param("q"), "")])
    with pytest.raises(ValueError, match=r"c1 refers to unknown \['zz'\]"):
        _template([Quantity("a", "mm", Num(1), "")], checks=[Check("c1", "position",
                                                                   Var("zz"), "")])
    # a condition is over the parameters alone: no column
    with pytest.raises(ValueError, match=r"cond refers to unknown \['a'\]"):
        _template([Quantity("a", "mm", Num(1), "")],
                  conditions=[Condition("cond", "kg*m", Var("a"), Num(1), "")])


def test_options_configure_once_with_defaults_filled_in():
    calls = []

    def configure(template, options):
        calls.append(dict(options))
        return template
    t = _template([Quantity("a", "mm", Num(1), "")], configure=configure,
                  options=[OptionSpec("n", 3, ""), OptionSpec("m", "p", "", choices=("p", "q"))])
    assert t.option_defaults == {"n": 3, "m": "p"}
    assert t.with_options({"m": "q"}) is t
    t.with_options({"m": "q", "n": 3})  # the same configuration: not configured again
    assert calls == [{"n": 3, "m": "q"}]
    t.with_options({})
    assert calls[-1] == {"n": 3, "m": "p"} and len(calls) == 2
