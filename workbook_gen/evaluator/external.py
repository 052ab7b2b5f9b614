"""References to other workbooks (``[1]Sheet1!A1``, ``'[1]My sheet'!A1:B3``, ``[1]!Name``),
read from what the file caches of them.

Excel keeps the last values it read of another workbook's cells in the file's
externalLink part (ECMA-376 Part 1, 18.14: ``externalBook/sheetDataSet/sheetData
sheetId/row/cell``); a recalculation without that workbook open uses them. ``[n]`` is the
n-th ``externalReference`` of xl/workbook.xml; the sheet is found by name among the
link's ``sheetNames`` (``sheetId`` is its position there). A cell the cache does not
hold (or a sheet, or a workbook the file does not list) is not guessed as empty: the
formula reading it raises :class:`~workbook_gen.formula.functions.Unanswered` and is not
checked. The other workbook's defined names (``definedNames``) point into its sheets.
"""

from __future__ import annotations

import dataclasses
import re

from workbook_gen.errors import FormulaSyntaxError
from workbook_gen.formula import ast
from workbook_gen.formula.functions import Unanswered
from workbook_gen.formula.parser import parse
from workbook_gen.cellref import column_letters
from workbook_gen.formula.values import Range

_BOOK = re.compile(r"\[(\d+)\](.*)", re.S)


class ExternalBooks:
    """The cached cells of the workbooks a file links to (``xlsx.model.ExternalLink``)."""

    def __init__(self, links=()):
        self.links = {link.index: link for link in links}

    def _sheet(self, sheet: str):
        """(link, sheet position, sheet name) of a ``[n]Sheet`` qualifier."""
        m = _BOOK.fullmatch(sheet)
        link = self.links.get(int(m.group(1))) if m else None
        if link is None:  # ([n] past the file's links, or a path: 'C:\dir\[Book.xlsx]Sheet1')
            raise Unanswered(f"external reference: the file lists no such workbook: {sheet}")
        name = m.group(2)
        folded = [s.casefold() for s in link.sheet_names]
        if name.casefold() not in folded:
            raise Unanswered(f"external reference: no such sheet in the file's cache of "
                             f"{self.book(link)}: {sheet}")
        position = folded.index(name.casefold())
        if position not in link.cells:
            raise Unanswered(f"external reference: the file caches no cell of the sheet: {sheet} "
                             f"({self.book(link)})")
        return link, position, link.sheet_names[position]

    @staticmethod
    def book(link) -> str:
        return (link.target or f"workbook {link.index}").rsplit("/", 1)[-1]

    def cell(self, sheet: str, row: int, col: int):
        link, position, _ = self._sheet(sheet)
        cells = link.cells[position]
        if (row, col) not in cells:
            raise Unanswered(f"external reference: a cell not in the file's cache of "
                             f"{self.book(link)}: {sheet}!{column_letters(col)}{row}")
        return cells[(row, col)]

    def rect(self, sheet: str, r1: int, c1: int, r2: int, c2: int) -> Range:
        link, position, _ = self._sheet(sheet)
        cells = link.cells[position]
        if (r2 - r1 + 1) * (c2 - c1 + 1) > len(cells):
            raise Unanswered(f"external reference: a cell not in the file's cache of "
                             f"{self.book(link)}: {sheet}!{column_letters(c1)}{r1}:"
                             f"{column_letters(c2)}{r2}")
        return Range.of([[self.cell(sheet, r, c) for c in range(c1, c2 + 1)]
                         for r in range(r1, r2 + 1)])

    def name(self, qualifier: str, name: str) -> ast.Node:
        """The tree of the other workbook's name (``[1]!Name``, ``[1]Sheet!Name``), its
        references qualified with ``[n]``."""
        m = _BOOK.fullmatch(qualifier)
        link = self.links.get(int(m.group(1))) if m else None
        if link is None:
            raise Unanswered(f"external name: the file lists no such workbook: "
                             f"{qualifier}!{name}")
        scope = None
        if m.group(2):
            folded = [s.casefold() for s in link.sheet_names]
            scope = folded.index(m.group(2).casefold()) if m.group(2).casefold() in folded \
                else -1
        text = link.names.get((name.casefold(), scope))
        if text is None and scope is not None:
            text = link.names.get((name.casefold(), None))
        if text is None:
            raise Unanswered(f"external name: not in the file's cache of {self.book(link)}: "
                             f"{qualifier}!{name}")
        try:
            node = parse(text.lstrip("="))
        except FormulaSyntaxError as exc:
            raise Unanswered(f"external name: {exc}: {qualifier}!{name}") from None
        book = f"[{link.index}]"
        if isinstance(node, (ast.CellRef, ast.RangeRef)) and node.sheet is not None \
                and not node.sheet.startswith("["):
            return dataclasses.replace(node, sheet=book + node.sheet)
        raise Unanswered(f"external name: not a reference into one sheet: "
                         f"{qualifier}!{name} = {text!r}")
