"""evaluator.calls: which calls of a formula cannot be evaluated, and whether a cell's
evaluation reaches one. References: [MS-XLSX] 2.2.2 and Microsoft's page on the _xlfn.
prefix (a future function stored without it is #NAME? in Excel:
https://support.microsoft.com/en-us/office/issue-an-xlfn-prefix-is-displayed-in-front-of-a-formula-882f1ef7-68fb-4fcd-8d54-9fbb77fd5025),
and IF's documented laziness (only the branch taken is evaluated:
https://support.microsoft.com/en-us/office/if-function-69aed7c9-4e8a-4755-a9bc-aa8bbff73be2).
PHONETIC and JIS are functions of the standard the evaluator lacks; MYUDF is no
function of Excel's (a VBA or add-in one)."""

from __future__ import annotations

from workbook_gen.evaluator.calls import (avoids, bare_future, guarded, unknown_reason,
                                          unsupported)
from workbook_gen.evaluator.store import Names, Store
from workbook_gen.formula import parse

NAMES = Names({"Twice": "LAMBDA(x, x*2)", "Kana": "LAMBDA(x, PHONETIC(x))",
               "Deep": "LAMBDA(x, Kana(x))", "Self": "LAMBDA(x, Self(x))"})


def _unsupported(text, stored=False, dialect="excel"):
    return unsupported(parse(text), NAMES, "S", dialect, stored)


def test_unsupported_names_the_functions_the_evaluator_lacks():
    assert _unsupported("SUM(1,2)+SQRT(4)") == set()
    assert _unsupported("PHONETIC(A1)&JIS(A2)") == {"PHONETIC", "JIS"}
    assert _unsupported("MYUDF(1)+1") == {"MYUDF"}


def test_a_future_function_stored_without_its_prefix_is_unavailable_in_excel_only():
    text = 'MINIFS(A1:A2,B1:B2,">0")'
    assert _unsupported(text, stored=True) == {"MINIFS"}
    assert _unsupported("_xlfn." + text, stored=True) == set()
    assert _unsupported(text, stored=False) == set()  # as a person types it
    assert _unsupported(text, stored=True, dialect="libreoffice") == set()
    assert bare_future(parse(text)) and not bare_future(parse("_xlfn." + text))


def test_a_named_lambda_is_looked_into():
    assert _unsupported("Twice(3)") == set()
    assert _unsupported("Kana(3)") == {"PHONETIC"}
    assert _unsupported("Deep(3)") == {"PHONETIC"}
    # a named LAMBDA may call itself (recursion, as Microsoft's LAMBDA page shows): its
    # own name is no unsupported function
    assert _unsupported("Self(3)") == set()


def test_unknown_reason_only_when_every_bad_call_is_unknown_to_excel():
    node = parse("MYUDF(1)+OTHER(2)")
    reason = unknown_reason(node, ["MYUDF", "OTHER"], "excel", False)
    assert reason == ("unknown function MYUDF, OTHER: #NAME? unless an add-in or a macro "
                      "defines it")
    assert unknown_reason(parse("MYUDF(1)+PHONETIC(2)"), ["MYUDF", "PHONETIC"], "excel",
                          False) is None
    assert unknown_reason(node, [], "excel", False) is None
    bare = parse('MAXIFS(A1:A2,B1:B2,">0")')
    assert "MAXIFS (stored without its _xlfn. prefix)" in unknown_reason(
        bare, ["MAXIFS"], "excel", True)


def test_guarded_needs_a_lazy_function_and_a_bad_call():
    assert guarded(parse("IF(A1>0,PHONETIC(A1),0)"))
    assert guarded(parse("IFERROR(MYUDF(1),0)"))
    assert not guarded(parse("PHONETIC(A1)+1"))
    assert not guarded(parse("IF(A1>0,1,0)"))
    assert guarded(parse('IF(A1,MINIFS(A1:A2,B1:B2,">0"),0)'))  # bare future


def test_avoids_follows_the_branch_the_cell_takes():
    store = Store(["S"])
    store.put_constants({("S", 1, 1): 5.0, ("S", 2, 1): -5.0})
    node = parse("IF(A1>0,1,PHONETIC(A1))")
    assert avoids(node, ("S", 1, 2), store, NAMES, "excel")       # A1 = 5: the 1
    node2 = parse("IF(A2>0,1,PHONETIC(A2))")
    assert not avoids(node2, ("S", 2, 2), store, NAMES, "excel")  # A2 < 0: PHONETIC
    # CHOOSE evaluates only the value it picks
    assert avoids(parse("CHOOSE(2,MYUDF(1),7)"), ("S", 3, 2), store, NAMES, "excel")
    assert not avoids(parse("CHOOSE(1,MYUDF(1),7)"), ("S", 3, 2), store, NAMES, "excel")
