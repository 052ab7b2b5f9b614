"""formula/functions/numfmt/tokens.py: a number format cut into tokens and sections, by the
format-code syntax of Microsoft's "Number format codes" page (support.microsoft.com:
sections separated by semicolons; text in double quotes; a character escaped with a
backslash; ``_x`` a space the width of x; ``*x`` repeats x to fill the cell; colours and
conditions in square brackets, ``[Red]``, ``[<=100]``; ``[$€-407]`` a currency symbol
and locale) and KB 67469 (conditions with =, <>, <, >, <=, >=), hand-derived."""

from __future__ import annotations

import pytest

from workbook_gen.formula.functions.numfmt.tokens import (condition, is_exponent, is_literal,
                                                          literal, split_sections, tokens,
                                                          unclosed_quote)


@pytest.mark.parametrize("section, expected", [
    ("#,##0.00", ("#", ",", "#", "#", "0", ".", "0", "0")),
    ('0" kg"', ("0", '" kg"')),
    ("0\\-0", ("0", "\\-", "0")),
    ("_(0_)", ("_(", "0", "_)")),
    ("*-0", ("*-", "0")),
    ("[Red][<=100]0", ("[Red]", "[<=100]", "0")),
    ("0.00E+00", ("0", ".", "0", "0", "E+", "0", "0")),
    ("0.0e-0", ("0", ".", "0", "e-", "0")),
    ("General", ("General",)),
    ("general", ("general",)),
    ("h:mm AM/PM", ("h", ":", "m", "m", " ", "AM/PM")),
    ("h a/p", ("h", " ", "a/p")),
    ("[h]:mm", ("[h]", ":", "m", "m")),
    ("[$€-407]0", ("[$€-407]", "0")),
    ('"open', ('"open',)),            # an unclosed quote runs to the end
    ("@", ("@",)),
    ("E", ("E",)),                   # an E without its sign is a character
])
def test_tokens(section, expected):
    assert tokens(section) == expected


@pytest.mark.parametrize("fmt, expected", [
    ("0", ("0",)),
    ("0;(0)", ("0", "(0)")),
    ("0;-0;;@", ("0", "-0", "", "@")),
    ('"a;b";0', ('"a;b"', "0")),       # a quoted ; is text
    ("0\\;0;0", ("0\\;0", "0")),       # so is an escaped one
    ("[<0;]0;0", ("[<0;]0", "0")),     # and one in brackets
    ("", ("",)),
])
def test_split_sections(fmt, expected):
    assert split_sections(fmt) == expected


def test_unclosed_quote():
    assert unclosed_quote('0" kg')
    assert unclosed_quote('"')
    assert not unclosed_quote('0" kg"')
    assert not unclosed_quote("0\\\"")      # an escaped quote opens nothing


@pytest.mark.parametrize("tok, printed", [
    ('" kg"', " kg"), ('"open', "open"), ('"', ""), ('""', ""),
    ("\\x", "x"), ("\\\\", "\\"), ("_)", " "), ("*-", ""),
    ("[Red]", ""), ("[<=100]", ""), ("[$€-407]", "€"), ("[$USD]", "USD"),
    ("[$-409]", ""), ("[$£-809]", "£"), ("-", "-"), ("/", "/"),
])
def test_literal(tok, printed):
    assert literal(tok) == printed


def test_is_literal_and_is_exponent():
    assert all(is_literal(t) for t in ('"x"', "\\x", "*x", "_x"))
    assert not any(is_literal(t) for t in ("0", "#", "[Red]", "E+"))
    assert is_exponent("E+") and is_exponent("e-")
    assert not is_exponent("E") and not is_exponent("E0") and not is_exponent("x+")


@pytest.mark.parametrize("section, x, holds", [
    ("[<10]0", 9.999, True), ("[<10]0", 10.0, False),
    ("[<=10]0", 10.0, True), ("[>10]0", 10.0, False), ("[>=10]0", 10.0, True),
    ("[=0]0", 0.0, True), ("[=0]0", 1e-300, False), ("[<>0]0", 0.0, False),
    ("[Red][>-1.5]0", -1.0, True), ("[>-1.5]0", -2.0, False),
    ("[< 1e3]0", 999.0, True), ("[>+.5]0", 0.6, True),
])
def test_condition(section, x, holds):
    assert condition(section)(x) is holds


def test_no_condition_and_the_negative_default():
    assert condition("[Red]0.00") is None
    assert condition('"[<10]"0') is None            # quoted: text, no condition
    assert condition("[<0]0").is_negative_default
    assert not condition("[<=0]0").is_negative_default
    assert not condition("[<1]0").is_negative_default
