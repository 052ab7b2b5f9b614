"""formula/functions/numfmt/sections.py: which section of a format shows a value.

References: Microsoft's "Review guidelines for customizing a number format"
(support.microsoft.com: up to four sections, positive;negative;zero;text; with one
section it applies to all numbers; with two, the first to positive numbers and zeros);
KB 67469's conditional sections (the first two clauses the conditions, the third the
"else"; [>100]General;[<100](General) shows -5 as -(5), ...;[<0](General) as (5));
and LibreOffice recalculating TEXT over the unconditional section layouts (one soffice
run), read back with openpyxl."""

from __future__ import annotations

import openpyxl
import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.formula.functions.numfmt.sections import GENERAL, choose, is_text_section, split

from lo_sheet import recalculated_sheet


@pytest.mark.parametrize("fmt, expected", [
    ("0", (("0",), None)),
    ("0;(0)", (("0", "(0)"), None)),
    ("0;(0);-", (("0", "(0)", "-"), None)),
    ('0;(0);-;"t"@', (("0", "(0)", "-"), '"t"@')),
    ("0;(0);-;x", (("0", "(0)", "-"), "x")),       # a fourth section is text anyway
    ("0;@", (("0",), "@")),
    ("@", ((), "@")),
    ('"@";0', (('"@"', "0"), None)),               # a quoted @ is no text section
    ("@;0", None),                                 # text before the last: invalid
    ("0;0;0;0;0", None),                           # more than four
])
def test_split(fmt, expected):
    assert split(fmt) == expected


def test_is_text_section():
    assert is_text_section('"x"@') and is_text_section("@@")
    assert not is_text_section('"@"') and not is_text_section("\\@")


@pytest.mark.parametrize("sections, x, expected", [
    # Microsoft's guidelines: one section for all, a minus for the negative
    (["0"], 5.0, ("0", False)), (["0"], -5.0, ("0", True)), (["0"], 0.0, ("0", False)),
    # two: positive and zero / negative (without a sign of its own)
    (["P", "N"], 5.0, ("P", False)), (["P", "N"], 0.0, ("P", False)),
    (["P", "N"], -5.0, ("N", False)),
    # three: positive / negative / zero
    (["P", "N", "Z"], 0.0, ("Z", False)), (["P", "N", "Z"], -1e-300, ("N", False)),
    (["P", "N", "Z"], 1e-300, ("P", False)),
    # KB 67469
    (["[>100]General", "[<100](General)"], -5.0, ("[<100](General)", True)),
    (["[>100]General", "[<0](General)"], -5.0, ("[<0](General)", False)),
    (["[>1000]0.00E+00", "General", "0.00"], 999.0, ("0.00", False)),
    (["[>1000]0.00E+00", "General", "0.00"], 1001.0, ("[>1000]0.00E+00", False)),
    (["[>1000]0.00E+00", "General", "0.00"], -7.0, ("General", False)),
    # a number no section takes: General (NPOI's FormatChoiceTests.xlsx, Excel-saved)
    (['[<10]#" Wow"'], 10.0, (GENERAL, False)),
    (['[<10]#" Wow"'], -10.0, ('[<10]#" Wow"', True)),
    # the second, without a condition and without a third, takes every other number
    # (ssf's oddities.json: [<=9999999]###-####;(###) ###-####)
    (["[<=9999999]###-####", "(###) ###-####"], 2813308004.0,
     ("(###) ###-####", False)),
    # a condition on the second section that holds keeps the minus of a negative number
    (["[>0]0", "[<-5]0"], -7.0, ("[<-5]0", True)),
    (["[>0]0", "[<-5]0"], -3.0, (GENERAL, True)),
])
def test_choose(sections, x, expected):
    assert choose(sections, x) == expected


FORMATS = ["0.0", "0.0;(0.0)", '0.0;(0.0);"zero"', '0;-0;"z";"t"@', "0;[Red]0"]
NUMBERS = [3.25, -3.25, 0.0]


@pytest.fixture(scope="module")
def libreoffice_text(libreoffice, tmp_path_factory):
    cells, where = {}, {}
    for i, fmt in enumerate(FORMATS):
        for j, x in enumerate(NUMBERS):
            ref = f"{'ABC'[j]}{i + 1}"
            cells[ref] = f'=TEXT({x!r},"{fmt.replace(chr(34), chr(34) * 2)}")'
            where[(fmt, x)] = ref
    out = recalculated_sheet(tmp_path_factory.mktemp("sections"), "Sections", cells)
    ws = openpyxl.load_workbook(out, data_only=True)["Sections"]
    return {k: ws[ref].value for k, ref in where.items()}


def test_section_choice_agrees_with_libreoffice(libreoffice_text):
    for (fmt, x), want in libreoffice_text.items():
        quoted = fmt.replace('"', '""')
        got = evaluate(parse(f'=TEXT({x!r},"{quoted}")'), DictResolver({}))
        assert got == (want if want is not None else ""), (fmt, x)
