"""formula/functions/cube/core.py: CUBEMEMBER, CUBEVALUE and CUBEMEMBERPROPERTY answered
from the OLAP cache a file keeps.

References: the corpus's openxmlsdk__Connection.xlsx, saved by Excel: its CUBEMEMBER
cells (column A, D1) and CUBEVALUE cells (column D) are recomputed here from the file's
OLAP cache alone (each CUBEVALUE reading the members its row's CUBEMEMBER gave, never a
cell's cached value) and compared with what Excel cached; Microsoft's CUBEMEMBER page
(support.microsoft.com: "caption ... displayed in the cell instead of the caption, if one
is defined, from the cube"); and a hand-built cache for the rules of the module's
docstring (errors in argument order, what the cache lacks is Unanswered, never a guess)."""

from __future__ import annotations

import re
from functools import lru_cache
from pathlib import Path

import openpyxl
import pytest

from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.formula.functions.cube.core import CubeMember
from workbook_gen.formula.functions.registry import Unanswered
from workbook_gen.xlerror import ExcelError
from workbook_gen.xlsx import read_workbook
from workbook_gen.xlsx.olap import OlapCache, OlapField

PATH = Path("/work/shared/corpus/xlsx/openxmlsdk__Connection.xlsx")


class _Book(DictResolver):
    def __init__(self, cells, olap):
        super().__init__(cells)
        self._olap = olap

    def olap(self, connection):
        return self._olap.get(connection.casefold())


@lru_cache(maxsize=1)
def corpus():
    """(olap caches, {cell: formula}, {cell: Excel's cached value}) of Sheet1."""
    olap = read_workbook(PATH).olap
    formulas = openpyxl.load_workbook(PATH)["Sheet1"]
    cached = openpyxl.load_workbook(PATH, data_only=True)["Sheet1"]
    text, values = {}, {}
    for row in formulas.iter_rows():
        for c in row:
            if isinstance(c.value, str) and c.value.startswith("="):
                text[c.coordinate] = c.value
                values[c.coordinate] = cached[c.coordinate].value
    return olap, text, values


def test_cubemember_and_cubevalue_agree_with_excels_cache():
    olap, text, cached = corpus()
    members = {ref: f for ref, f in text.items() if f.startswith("=CUBEMEMBER(")}
    book = _Book({}, olap)
    got = {}
    for ref, formula in members.items():
        value = evaluate(parse(formula), book)
        assert isinstance(value, CubeMember) and value == cached[ref], ref
        got[ref] = value
    book = _Book(got, olap)              # the members, as the cells hold them
    values = {ref: f for ref, f in text.items() if f.startswith("=CUBEVALUE(")}
    answered = 0
    for ref, formula in values.items():
        row = int(re.sub(r"\D", "", ref))
        try:
            got = evaluate(parse(formula), book, cell=("Sheet1", row, 4))
        except Unanswered:  # a tuple the cache lacks (the grand total rows)
            continue
        assert got == pytest.approx(cached[ref], rel=1e-15), ref
        answered += 1
    assert len(members) > 50 and answered > 50


def test_a_property_the_cache_lacks_is_unanswered():
    """Excel cached #N/A for the file's CUBEMEMBERPROPERTY cells (the server's answer); the
    cache holds no such property, so the cell is not checked rather than guessed."""
    olap, text, _ = corpus()
    formula = next(f for f in text.values() if f.startswith("=CUBEMEMBERPROPERTY("))
    with pytest.raises(Unanswered, match="CUBEMEMBERPROPERTY"):
        evaluate(parse(formula), _Book({}, olap))


# -- a hand-built cache ---------------------------------------------------------------------

A, B, M = ("f", 0, 0), ("f", 0, 1), ("f", 1, 0)
CACHE = OlapCache(
    "Conn",
    fields=[OlapField("[P].[Cat]", 0, 1, False,
                      [("[P].[Cat].&[1]", "Bikes", (0,)), ("[P].[Cat].&[2]", "Parts", (1,))]),
            OlapField("[Measures]", 1, 0, False, [("[Measures].[Sales]", "Sales", ())]),
            OlapField("[P].[Cat].[Colour]", 0, 1, True, [("Red", "Red", ()),
                                                          ("Blue", "Blue", ())])],
    queries={"[P].[Cat].&[1]": frozenset({A}), "[P].[Cat].&[2]": frozenset({B}),
             "[Measures].[Sales]": frozenset({M})},
    entries={frozenset({A, M}): 10.5, frozenset({B, M}): 4.0, frozenset({A}): 99.0},
)


def ev(formula, cells=None):
    return evaluate(parse(formula), _Book(cells or {}, {"conn": CACHE}))


def test_cubemember_caption_and_members():
    got = ev('=CUBEMEMBER("Conn","[P].[Cat].&[1]")')
    assert got == "Bikes" and got.members == frozenset({A})
    got = ev('=CUBEMEMBER("conn","[P].[Cat].&[1]","My caption")')   # any case
    assert got == "My caption" and got.members == frozenset({A})
    tuple_ = ev('=CUBEMEMBER("Conn",{"[P].[Cat].&[2]","[Measures].[Sales]"})')
    assert tuple_ == "Sales" and tuple_.members == frozenset({B, M})  # the last's caption


def test_cubevalue_reads_members_from_text_cells_and_ranges():
    assert ev('=CUBEVALUE("Conn","[P].[Cat].&[1]","[Measures].[Sales]")') == 10.5
    assert ev('=CUBEVALUE("Conn","[P].[Cat].&[1]")') == 99.0
    cells = {"A1": CubeMember("Parts", frozenset({B})),
             "B1": CubeMember("Sales", frozenset({M}))}
    assert ev('=CUBEVALUE("Conn",A1,B1)', cells) == 4.0
    assert ev('=CUBEVALUE("Conn",A1:B1)', cells) == 4.0


def test_errors_in_argument_order():
    assert ev('=CUBEVALUE(#REF!,"x")') is ExcelError.REF
    assert ev('=CUBEVALUE("Conn",#N/A,"[Measures].[Sales]")') is ExcelError.NA
    assert ev('=CUBEMEMBER("Conn","[P].[Cat].&[1]",#DIV/0!)') is ExcelError.DIV0
    assert ev('=CUBEMEMBER(#NUM!,#N/A)') is ExcelError.NUM


@pytest.mark.parametrize("formula", [
    '=CUBEVALUE("Other","[P].[Cat].&[1]")',                    # no cache for it
    '=CUBEVALUE("Conn","[P].[Cat].&[9]")',                     # a query it lacks
    '=CUBEVALUE("Conn","[P].[Cat].&[2]")',                     # a tuple it lacks
    '=CUBEVALUE("Conn",5)',                                    # not a member expression
    '=CUBEMEMBERPROPERTY("Conn","[P].[Cat].&[1]","Weight")',   # a property it lacks
    '=CUBEMEMBERPROPERTY("Conn","[Measures].[Sales]","Colour")',  # no property holders
])
def test_what_the_cache_lacks_is_unanswered(formula):
    with pytest.raises(Unanswered):
        ev(formula)


def test_cubememberproperty_from_the_property_field():
    assert ev('=CUBEMEMBERPROPERTY("Conn","[P].[Cat].&[1]","[P].[Cat].[Colour]")') == "Red"
    assert ev('=CUBEMEMBERPROPERTY("Conn","[P].[Cat].&[2]","[p].[cat].[colour]")') == "Blue"


def test_a_cube_member_survives_pickling():
    import pickle
    m = CubeMember("Bikes", frozenset({A}))
    back = pickle.loads(pickle.dumps(m))
    assert back == "Bikes" and back.members == m.members and isinstance(back, CubeMember)
