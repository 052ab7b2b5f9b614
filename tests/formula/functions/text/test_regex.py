"""REGEXTEST, REGEXEXTRACT and REGEXREPLACE (formula/functions/regex.py) against Python's
``re`` on random texts, and Microsoft's documented return modes, occurrences, case
sensitivity and ``$n`` replacements."""

from __future__ import annotations

import random
import re

import pytest

from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula.arrays import evaluate_array
from workbook_gen.xlerror import ExcelError

PATTERNS = [r"[0-9]+", r"[A-Z][a-z]+", r"\b\w{3}\b", r"(ab|ba)+", r"x?y", r"\d{2,3}"]


def ev(text: str):
    value = evaluate_array(parse(text), DictResolver({}), "excel", None)
    return [x for row in value.rows for x in row] if hasattr(value, "rows") else value


def quoted(s: str) -> str:
    return '"' + s.replace('"', '""') + '"'


def texts(n: int = 30) -> list[str]:
    rng = random.Random(23)
    alphabet = "abAByxz0123 45_"
    return ["".join(rng.choice(alphabet) for _ in range(rng.randint(0, 24))) for _ in range(n)]


@pytest.mark.parametrize("pattern", PATTERNS)
def test_test_extract_and_replace_as_re(pattern):
    for text in texts():
        args = f"{quoted(text)},{quoted(pattern)}"
        assert ev(f"=REGEXTEST({args})") is (re.search(pattern, text) is not None)
        assert ev(f"=REGEXTEST({args},1)") is (re.search(pattern, text, re.I) is not None)
        found = [m.group(0) for m in re.finditer(pattern, text)]
        first = ev(f"=REGEXEXTRACT({args})")
        assert first == (found[0] if found else ExcelError.NA), (text, pattern)
        assert ev(f"=REGEXEXTRACT({args},1)") == (found or ExcelError.NA), (text, pattern)
        assert ev(f'=REGEXREPLACE({args},"<$0>")') == re.sub(pattern, r"<\g<0>>", text)


def test_microsofts_examples():
    assert ev('=REGEXEXTRACT("10 apples, 12 oranges","[0-9]+")') == "10"
    assert ev('=REGEXEXTRACT("10 apples, 12 oranges","[0-9]+",1)') == ["10", "12"]
    assert ev(r'=REGEXEXTRACT("O my Luve red rose","O my (\w+) red (\w+)",2)') == \
        ["Luve", "rose"]
    assert ev(r'=REGEXREPLACE("Sonia Rees","(\w+) (\w+)","$2, $1")') == "Rees, Sonia"
    assert ev('=REGEXREPLACE("aaa","a","b",2)') == "aba"        # the 2nd occurrence only
    assert ev('=REGEXREPLACE("aaa","a","b",-1)') == "aab"       # counted from the end
    assert ev('=REGEXREPLACE("AbA","a","x",0,1)') == "xbx"      # case-insensitive
    assert ev('=REGEXTEST("abc","[")') == ExcelError.VALUE      # a pattern that cannot compile
    assert ev('=REGEXTEST("abc","a",2)') == ExcelError.VALUE    # case_sensitivity 0 or 1
