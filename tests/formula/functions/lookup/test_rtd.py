"""formula/functions/lookup/rtd.py: RTD answered from the real-time data a file caches.

References: Microsoft's RTD page (support.microsoft.com, "RTD function": RTD(ProgID,
server, topic1, [topic2], ...), the server "" for the local computer); the corpus's
openxmlsdk__VolTypes.xlsx, saved by Excel with =RTD(1223,XL11, 1) caching #N/A, audited
against that cached value; and hand-built caches ({ProgID: {(server, topics...): value}}
as xlsx/topics.py reads xl/volatileDependencies.xml)."""

from __future__ import annotations

from pathlib import Path

import pytest

from workbook_gen import audit
from workbook_gen.formula import DictResolver, evaluate, parse
from workbook_gen.formula.functions.registry import Unanswered
from workbook_gen.xlerror import ExcelError

CORPUS = Path("/work/shared/corpus/xlsx")
TOPICS = {"my.server": {("", "IBM", "Last"): 42.5, ("", "IBM", "Status"): "open",
                        ("srv", "flag"): True, ("", "1", "TRUE"): 7.0},
          "1223": {("", "1"): ExcelError.NA}}


class _Book(DictResolver):
    def topics(self, progid):
        return TOPICS.get(progid.casefold())


def ev(text, cells=None):
    return evaluate(parse(text), _Book(cells or {}))


@pytest.mark.parametrize("formula, expected", [
    ('=RTD("My.Server","","IBM","Last")', 42.5),
    ('=RTD("MY.SERVER","","IBM","Status")', "open"),   # the ProgID in any case
    ('=RTD("my.server","srv","flag")', True),
    ('=RTD("my.server","",1,TRUE)', 7.0),              # topics as text: "1", "TRUE"
    ('=RTD(1223,"",1)', ExcelError.NA),                # a cached error is the value
    ('=RTD(1223,B9,1)', ExcelError.NA),                # an empty cell is "" (the corpus)
    ('=RTD("my.server",#REF!,"IBM")', ExcelError.REF), # an error argument: the error
    ('=RTD("my.server","",1/0)', ExcelError.DIV0),
    ('=RTD("my.server","IBM")', ExcelError.VALUE),     # fewer than 3 arguments
])
def test_calls_the_cache_holds(formula, expected):
    assert ev(formula) == expected


@pytest.mark.parametrize("formula", [
    '=RTD("my.server","","IBM","Bid")',   # a topic the cache lacks
    '=RTD("my.server","other","IBM","Last")',
    '=RTD("none.server","","IBM","Last")',  # a ProgID the cache lacks
])
def test_a_call_the_cache_lacks_is_unanswered_never_guessed(formula):
    with pytest.raises(Unanswered, match="RTD"):
        ev(formula)


def test_without_real_time_data_nothing_is_answered():
    with pytest.raises(Unanswered):
        evaluate(parse('=RTD("my.server","","IBM","Last")'), DictResolver({}))


def test_the_excel_saved_file_agrees():
    report = audit(CORPUS / "openxmlsdk__VolTypes.xlsx")
    assert report.formula_cells == report.cells_checked == 1   # Sheet1!A2, the RTD call
    assert report.mismatches == [] and report.not_checked == {}
