"""What the formula evaluators may ask of a workbook: :class:`Resolver`.

Coordinates are 1-based; ``sheet`` None is the calling cell's sheet. A resolver
subclasses :class:`Resolver` and overrides what it knows; every method has a default
that is the answer for a workbook that does not know it (no hidden rows, no array
formulas, no sheet list...), and the functions asking take that default as "not known
here" (SHEET gives #N/A, RTD is "not checked", ISFORMULA is FALSE). ``NO_WORKBOOK`` is a
resolver of nothing but defaults: what a function sees when it is evaluated without a
workbook (the vectorised evaluator's element-wise calls).

The values are ``float | str | bool | None | ExcelError`` (formula/values.py's
``Value``); a range is a 2-D list of them or a ``Range``.
"""

from __future__ import annotations

from workbook_gen.xlerror import ExcelError


class Resolver:
    """A workbook as the evaluator reads it. By default: no cells, no names, and none
    of the workbook-wide facts below."""

    #: Are the formulas as a file stores them (``_xlfn.`` prefixes and all)? Then a
    #: future function written without its prefix is an unknown name.
    stored: bool = False

    # -- the cells and the names ------------------------------------------------------------

    def cell(self, sheet: str | None, row: int, col: int):
        """The value of a cell; by default None (an empty cell)."""
        return None

    def range(self, sheet: str | None, row1: int, col1: int, row2: int, col2: int):
        """The values of a rectangle, row by row (a 2-D list or a ``Range``); by default
        each cell's :meth:`cell`."""
        return [[self.cell(sheet, r, c) for c in range(col1, col2 + 1)]
                for r in range(row1, row2 + 1)]

    def name(self, name: str, sheet: str | None):
        """A defined name's value (a 2-D list or a ``Range`` for a range; ``sheet`` is
        the qualifier of ``Sheet2!Name``); by default #NAME? (no such name)."""
        return ExcelError.NAME

    def name_node(self, name: str):
        """The tree of a defined name seen from the calling sheet (a LAMBDA called by
        name), or None; by default None (no name holds a LAMBDA)."""
        return None

    # -- what the layout says (SUBTOTAL, AGGREGATE, ANCHORARRAY, ISFORMULA, FORMULATEXT) -------

    def hidden_rows(self, sheet: str | None) -> frozenset[int]:
        """The hidden rows of a sheet (SUBTOTAL 101-111, AGGREGATE); by default none."""
        return frozenset()

    def filtered_rows(self, sheet: str | None) -> frozenset[int]:
        """The rows of a sheet a filter hid (SUBTOTAL 1-11 leave them out too); by
        default none."""
        return frozenset()

    def subtotal_cells(self, sheet: str | None) -> list[tuple[int, int]]:
        """(row, col) of a sheet's cells holding SUBTOTAL or AGGREGATE (which leave them
        out); by default none."""
        return []

    def spill_area(self, sheet: str | None, row: int, col: int) -> tuple[int, int] | None:
        """(last row, last column) of the array formula anchored at the cell, or None
        (ANCHORARRAY: #REF!); by default None."""
        return None

    def has_formula(self, sheet: str | None, row: int, col: int) -> bool:
        """Does the cell hold a formula? By default no (a table of values)."""
        return False

    def formula_text(self, sheet: str | None, row: int, col: int) -> tuple[str, bool] | None:
        """The cell's formula as stored (without '=') and whether it is an array
        formula's, or None (FORMULATEXT: #N/A); by default None."""
        return None

    # -- the workbook's sheets ----------------------------------------------------------------

    def sheet_number(self, sheet: str | None) -> int | None:
        """The 1-based place of a sheet (None: the calling cell's) among all the
        workbook's sheets, any case; None if there is no such sheet or the sheets are not
        known (SHEET: #N/A); by default None."""
        return None

    def sheet_count(self) -> int | None:
        """How many sheets the workbook has, or None when not known (SHEETS: #N/A; a
        reference to an unknown sheet is then not #REF!); by default None."""
        return None

    def sheets_between(self, first: str, last: str) -> list[str] | None:
        """The sheets of a 3-D reference ``first:last`` in workbook order, or None (the
        reference is #REF!); by default None."""
        return None

    # -- what the file caches of the world outside --------------------------------------------

    def charset(self) -> str:
        """The workbook's character set for CHAR and CODE ("cp1252" or "mac_roman");
        by default Windows' "cp1252"."""
        return "cp1252"

    def olap(self, connection: str):
        """The cube functions' cache of a connection (xlsx.olap.OlapCache), or None (the
        cell is not checked); by default None."""
        return None

    def topics(self, progid: str):
        """{(server, topics...): last value} of an RTD server's calls, or None (the cell
        is not checked); by default None."""
        return None


#: The resolver of a call evaluated without a workbook: every default.
NO_WORKBOOK = Resolver()
