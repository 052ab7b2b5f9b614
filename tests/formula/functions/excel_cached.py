"""Formulas of formulas__test.xlsx (saved by Microsoft Macintosh Excel) recomputed from the
file's own inputs and compared with Excel's cached values, a whole spill at a time: shared
by the tests of the functions Excel 365 added (GROUPBY, PIVOTBY, TRIMRANGE, PERCENTOF)."""

from __future__ import annotations

import re
import zipfile
from functools import lru_cache
from pathlib import Path

import openpyxl
import pytest

from workbook_gen.cellref import column_letters
from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula.arrays import evaluate_array
from workbook_gen.xlerror import ExcelError

PATH = Path("/work/shared/corpus/xlsx/formulas__test.xlsx")
_CELL = re.compile(r'<c r="([A-Z]+)(\d+)"(?:[^>/]|/(?!>))*>(?:(?!</c>).)*?'
                   r'<f t="array" ref="([A-Z0-9:]+)"[^>]*>([^<]*)</f>', re.S)


@lru_cache(maxsize=1)
def book():
    if not PATH.is_file():
        pytest.fail(f"corpus file missing: {PATH}")
    return openpyxl.load_workbook(PATH, data_only=True, read_only=True)


def value(v):
    if isinstance(v, str) and v.startswith("#") and ExcelError.from_text(v) is not None:
        return ExcelError.from_text(v)
    return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else v


@lru_cache(maxsize=4)
def resolver(sheets: tuple[str, ...], first: int, last: int) -> DictResolver:
    """The cached values of rows ``first``..``last`` of ``sheets`` (the first unqualified)."""
    cells = {}
    for sheet in sheets:
        for r, row in enumerate(book()[sheet].iter_rows(min_row=first, max_row=last,
                                                         values_only=True), first):
            for c, v in enumerate(row, 1):
                if v is not None:
                    cells[f"'{sheet}'!{column_letters(c)}{r}"] = value(v)
    return DictResolver(cells, sheet=sheets[0])


def array_formulas(sheet_xml: str, pattern: str) -> list[tuple[str, str, str]]:
    """``(anchor, ref, formula)`` of the array formulas of a sheet part matching ``pattern``."""
    with zipfile.ZipFile(PATH) as z:
        text = z.read(f"xl/worksheets/{sheet_xml}.xml").decode()
    out = []
    for m in _CELL.finditer(text):
        formula = (m.group(4).replace("&quot;", '"').replace("&amp;", "&")
                   .replace("&lt;", "<").replace("&gt;", ">"))
        if re.search(pattern, formula):
            out.append((m.group(1) + m.group(2), m.group(3), formula))
    return out


def cached_rows(sheet: str, ref: str) -> list[list]:
    rows = book()[sheet][ref]
    if not isinstance(rows, tuple):
        rows = ((rows,),)
    elif rows and not isinstance(rows[0], tuple):
        rows = (rows,)
    return [[value(c.value) for c in row] for row in rows]


def recomputed(formula: str, res: DictResolver):
    value = evaluate_array(parse(formula), res, "excel", None)
    return [list(r) for r in value.rows] if hasattr(value, "rows") else [[value]]


def same(got, cached) -> bool:
    """One cell: "" is an empty cached text (openpyxl reads it as None)."""
    if cached is None:
        return got in ("", None)
    if isinstance(cached, float) and isinstance(got, float):
        return got == pytest.approx(cached, rel=1e-13, abs=1e-300)
    return got == cached


def assert_spill(formula: str, ref: str, sheet: str, res: DictResolver) -> None:
    """The array formula's area as Excel fills it: the result where it reaches, a single
    row or column repeated, #N/A beyond; an empty cell spills as 0."""
    cached = cached_rows(sheet, ref)
    got = recomputed(formula, res)
    if len(cached) > 1 or len(cached[0]) > 1:  # (a one-cell area shows the top-left value)
        assert len(got) <= len(cached) and len(got[0]) <= len(cached[0]), (formula, got)

    def at(i, j):
        gi = i if i < len(got) else 0 if len(got) == 1 else None
        gj = j if j < len(got[0]) else 0 if len(got[0]) == 1 else None
        v = ExcelError.NA if gi is None or gj is None else got[gi][gj]
        return 0.0 if v is None else v
    for i, c_row in enumerate(cached):
        for j, c in enumerate(c_row):
            assert same(at(i, j), c), (formula, got, cached)
