"""formula/functions/text.py against Python's str on random texts: LEN, LEFT, RIGHT, MID,
FIND (case-sensitive) and SEARCH (case-insensitive, wildcards), SUBSTITUTE (all or the
n-th), REPLACE, REPT, EXACT, CONCAT/TEXTJOIN, CODE/CHAR and UNICODE/UNICHAR; Excel's
errors for out-of-range arguments."""

from __future__ import annotations

import fnmatch
import random

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)
ALPHABET = "abcAB c.-é1"


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def q(s: str) -> str:
    return '"' + s.replace('"', '""') + '"'


def texts(n=150):
    return ["".join(RNG.choice(ALPHABET) for _ in range(RNG.randint(0, 15))) for _ in range(n)]


def test_lengths_and_slices():
    for s in texts():
        k, m = RNG.randint(0, 20), RNG.randint(1, 20)
        assert ev(f"=LEN({q(s)})") == len(s)
        assert ev(f"=LEFT({q(s)},{k})") == s[:k]
        assert ev(f"=RIGHT({q(s)},{k})") == (s[-k:] if k else "")
        assert ev(f"=MID({q(s)},{m},{k})") == s[m - 1:m - 1 + k]
        assert ev(f"=LEFT({q(s)})") == s[:1]                      # one character by default
    assert ev('=LEFT("abc",-1)') == ExcelError.VALUE
    assert ev('=MID("abc",0,1)') == ExcelError.VALUE


def test_find_and_search():
    for s in texts():
        needle = s[RNG.randint(0, len(s)):][:RNG.randint(1, 3)] or "a"
        start = RNG.randint(1, max(1, len(s)))
        i = s.find(needle, start - 1)
        assert ev(f"=FIND({q(needle)},{q(s)},{start})") == (i + 1 if i >= 0 else ExcelError.VALUE)
        j = s.lower().find(needle.lower(), start - 1)
        assert ev(f"=SEARCH({q(needle)},{q(s)},{start})") == (j + 1 if j >= 0 else ExcelError.VALUE)
    # wildcards: ? one character, * any run, ~ escapes (as fnmatch's, bar the escape)
    for s in texts(60):
        hits = [i for i in range(len(s)) if fnmatch.fnmatchcase(s[i:i + 3].lower(), "a?c")
                and len(s[i:i + 3]) == 3]
        assert ev(f'=SEARCH("a?c",{q(s)})') == (hits[0] + 1 if hits else ExcelError.VALUE)
    assert ev('=SEARCH("~?","a?b")') == 2
    assert ev('=FIND("","abc")') == 1


def test_substitute_replace_rept_exact():
    for s in texts():
        old, new = RNG.choice(["a", "b", "c", "ab", " "]), RNG.choice(["", "X", "yy"])
        assert ev(f"=SUBSTITUTE({q(s)},{q(old)},{q(new)})") == s.replace(old, new)
        n = RNG.randint(1, 3)
        parts = s.split(old)
        want = s if len(parts) <= n else old.join(parts[:n]) + new + old.join(parts[n:])
        assert ev(f"=SUBSTITUTE({q(s)},{q(old)},{q(new)},{n})") == want
        start, count = RNG.randint(1, 10), RNG.randint(0, 5)
        assert ev(f"=REPLACE({q(s)},{start},{count},{q(new)})") == \
            s[:start - 1] + new + s[start - 1 + count:]
        assert ev(f"=REPT({q(s)},{n})") == s * n
        assert ev(f"=EXACT({q(s)},{q(s.upper())})") is (s == s.upper())


def test_joins_and_codes():
    words = texts(6)
    assert ev("=CONCAT(" + ",".join(map(q, words)) + ")") == "".join(words)
    assert ev('=TEXTJOIN("-",TRUE,' + ",".join(map(q, words + [""])) + ")") == \
        "-".join(w for w in words if w)
    assert ev('=TEXTJOIN("-",FALSE,"a","","b")') == "a--b"
    for c in list(range(32, 127)):
        assert ev(f"=CODE(CHAR({c}))") == c and ev(f"=CHAR({c})") == chr(c)
    for c in (65, 233, 0x20AC, 0x1F600):
        assert ev(f"=UNICHAR({c})") == chr(c) and ev(f"=UNICODE({q(chr(c))})") == c
    assert ev("=CHAR(0)") == ExcelError.VALUE and ev('=CODE("")') == ExcelError.VALUE
