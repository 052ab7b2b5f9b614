"""formula/functions/xlookup.py: XMATCH and XLOOKUP against a plain Python search over
random numeric columns: exact, next smaller, next larger and wildcard matches, from the
first or the last, binary searches over sorted data; if_not_found; Microsoft's
example."""

from __future__ import annotations

import fnmatch
import random

import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.xlerror import ExcelError

RNG = random.Random(23)


def ev(text: str):
    return evaluate(parse(text), DictResolver({}))


def col(values) -> str:
    return "{" + ";".join(repr(float(v)) if not isinstance(v, str) else f'"{v}"'
                          for v in values) + "}"


def search(values, x, match: int, last: bool):
    """1-based position per XMATCH's match_mode, scanning from the first or the last."""
    order = range(len(values) - 1, -1, -1) if last else range(len(values))
    if match == 0:
        hits = [i for i in order if values[i] == x]
        return hits[0] + 1 if hits else ExcelError.NA
    exact = [i for i in order if values[i] == x]
    if exact:
        return exact[0] + 1
    if match == -1:
        below = [values[i] for i in order if values[i] < x]
        if not below:
            return ExcelError.NA
        best = max(below)
    else:
        above = [values[i] for i in order if values[i] > x]
        if not above:
            return ExcelError.NA
        best = min(above)
    return next(i for i in order if values[i] == best) + 1


@pytest.mark.parametrize("seed", range(20))
def test_xmatch_and_xlookup_as_a_search(seed):
    rng = random.Random(seed)
    values = [float(rng.randint(0, 30)) for _ in range(rng.randint(1, 15))]
    returns = [float(rng.randint(100, 999)) for _ in values]
    for _ in range(10):
        x = float(rng.randint(-2, 32))
        for match in (0, -1, 1):
            for mode, last in ((1, False), (-1, True)):
                want = search(values, x, match, last)
                assert ev(f"=XMATCH({x},{col(values)},{match},{mode})") == want, \
                    (values, x, match, mode)
                got = ev(f'=XLOOKUP({x},{col(values)},{col(returns)},"none",{match},{mode})')
                assert got == (returns[want - 1] if isinstance(want, int) else "none")
        ordered = sorted(set(values))
        want = search(ordered, x, 0, False)
        assert ev(f"=XMATCH({x},{col(ordered)},0,2)") == want            # binary, ascending
        assert ev(f"=XMATCH({x},{col(ordered[::-1])},0,-2)") == \
            (len(ordered) + 1 - want if isinstance(want, int) else want)  # binary, descending


def test_wildcards():
    words = ["apple", "apricot", "banana", "Avocado", "a?x", "grape"]
    for pattern in ("ap*", "*an*", "a?x", "?????", "a~?x", "z*"):
        translated = pattern.replace("~?", "[?]")
        hits = [i for i, w in enumerate(words) if fnmatch.fnmatchcase(w.lower(), translated)]
        want = hits[0] + 1 if hits else ExcelError.NA
        assert ev(f'=XMATCH("{pattern}",{col(words)},2)') == want, pattern


def test_microsofts_example():
    # XMATCH("Gra?",{"Apple";"Grape";"Pear";"Banana";"Cherry"},1): "Grape", next larger
    fruits = col(["Apple", "Grape", "Pear", "Banana", "Cherry"])
    assert ev(f'=XMATCH("Gra?",{fruits},1)') == 2
    assert ev(f'=XLOOKUP("x",{fruits},{fruits})') == ExcelError.NA
