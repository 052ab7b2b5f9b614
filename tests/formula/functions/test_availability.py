"""formula/functions/availability.py against two independent lists: openpyxl's list of the
functions of the standard (ECMA-376 Part 1, 18.17.7; ``openpyxl.utils.formulas.FORMULAE``)
and XlsxWriter's list of the future functions it writes with their ``_xlfn.`` prefix
(``Worksheet._prepare_formula``, after [MS-XLSX] 2.2.2); ``unavailable`` and ``known`` by
the rules of the module's docstring (Excel reads MINIFS stored without its prefix as an
unknown name, LibreOffice computes it)."""

from __future__ import annotations

import inspect
import re

import openpyxl.utils.formulas
import pytest
import xlsxwriter.worksheet

from workbook_gen.formula.functions import availability as av
from workbook_gen.formula.functions.registry import REGISTRY

STANDARD = openpyxl.utils.formulas.FORMULAE


def xlsxwriter_future() -> dict[str, str]:
    """name -> prefix of each function XlsxWriter's _prepare_formula prefixes."""
    source = inspect.getsource(xlsxwriter.worksheet.Worksheet._prepare_formula)
    return {m.group(2): m.group(1) for m in
            re.finditer(r'"(_xlfn\.(?:_xlws\.)?)([A-Z0-9._]+)\(', source)}


def test_xlsxwriters_future_functions_are_future_here():
    theirs = xlsxwriter_future()
    assert len(theirs) > 150
    assert set(theirs) <= av.FUTURE, sorted(set(theirs) - av.FUTURE)
    # and FILTER/SORT are the _xlws. ones, as the module says
    assert theirs["FILTER"] == theirs["SORT"] == "_xlfn._xlws."


def test_future_and_standard_are_apart_and_cover_the_registry():
    assert not av.FUTURE & STANDARD
    # Microsoft's "Add-in and Automation functions" are no prefix either, though openpyxl's
    # list leaves them out
    assert av.STANDARD_UNIMPLEMENTED - STANDARD == {"CALL", "EUROCONVERT", "REGISTER.ID",
                                                    "SQL.REQUEST"}
    assert STANDARD <= set(REGISTRY) | av.STANDARD_UNIMPLEMENTED
    assert not av.STANDARD_UNIMPLEMENTED & set(REGISTRY)  # "does not implement" is true
    assert set(REGISTRY) - STANDARD <= av.FUTURE


@pytest.mark.parametrize("name, prefix, dialect, stored, expected", [
    ("MINIFS", "", "excel", True, True),           # stored without its prefix: #NAME?
    ("MINIFS", "_xlfn.", "excel", True, False),
    ("MINIFS", "", "excel", False, False),         # typed as a person types it
    ("MINIFS", "", "libreoffice", True, False),    # LibreOffice computes it
    ("FILTER", "", "excel", True, True),
    ("SUM", "", "excel", True, False),             # of the standard: no prefix needed
    ("RTD", "", "excel", True, False),
])
def test_unavailable(name, prefix, dialect, stored, expected):
    assert av.unavailable(name, prefix, dialect, stored) is expected


def test_known():
    implemented = set(REGISTRY)
    assert av.known("SUM", implemented)
    assert av.known("CUBEVALUE", implemented)        # the standard's, implemented
    assert av.known("CUBESET", implemented)          # the standard's, not implemented
    assert av.known("STOCKHISTORY", implemented)     # a future function
    assert not av.known("CRAPNAME", implemented)
    assert av.known("CUBESET", set())                # known whatever is implemented
    assert av.known("MYADDIN", {"MYADDIN"})
