"""What the xlsx reader returns: workbook, sheets, cells, names and external links."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

import numpy as np

from workbook_gen.cellref import column_letters  # noqa: F401  (part of this module's face)
from workbook_gen.xlerror import ExcelError

MAX_COL = 16_384

Value = float | str | bool | ExcelError | None
# plain cells as columns: rows, columns, cached values, formula texts (None: constant)
Chunk = tuple[list[int], list[int], list[Value], list["str | None"]]


@dataclass(slots=True)
class Cell:
    """One non-empty cell: cached value and, for a formula cell, its text."""

    ref: str
    row: int
    col: int
    value: Value = None
    formula: str | None = None
    formula_type: str | None = None  # "normal", "shared", "array", "dataTable"
    shared_index: int | None = None
    shared_master: str | None = None  # ref of the master (itself on the master)
    array_ref: str | None = None  # range of an array formula, on its master cell
    array_master: str | None = None  # on the other cells an array formula fills
    data_table: dict | None = None  # a data table's <f> attributes (r1, r2, dt2D, dtr, del1, del2)

    @property
    def has_formula(self) -> bool:
        """True for any formula cell, shared followers and data tables included."""
        return self.formula_type is not None

    @property
    def is_array(self) -> bool:
        return self.formula_type == "array"


@dataclass(slots=True)
class SharedFormula:
    index: int
    master: str  # cell ref holding the text
    ref: str  # range the formula was filled over
    text: str


@dataclass(slots=True)
class TableDef:
    """A table (ListObject) of a sheet, from its xl/tables part."""

    name: str        # displayName, the name formulas use
    ref: str         # "A1:D10", headers and totals included
    columns: list[str]
    header_rows: int = 1
    totals_rows: int = 0
    filter_ref: str | None = None  # its autoFilter's range, when that filters rows


@dataclass
class Sheet:
    """A worksheet: cells in document (row-major) order, keyed by A1 ref."""

    name: str
    index: int  # position in xl/workbook.xml <sheets>, the localSheetId of its names
    state: str = "visible"
    cells: dict[str, Cell] = field(default_factory=dict)
    defined_names: dict[str, str] = field(default_factory=dict)  # sheet-local names
    shared_formulas: dict[int, SharedFormula] = field(default_factory=dict)
    dimension: str | None = None
    tables: list[TableDef] = field(default_factory=list)
    hidden_rows: set[int] = field(default_factory=set)  # <row hidden="1">: hidden or filtered
    filter_ref: str | None = None  # the sheet's autoFilter range, when that filters rows
    _rows: dict[int, list[Cell]] | None = field(default=None, repr=False)
    _cells: dict[str, Cell] = field(default_factory=dict, repr=False)
    # Cells of the plain kind (a constant, or a formula with its text), as the scanner read
    # them: columns ``(rows, cols, values, formulas)`` that follow ``_cells`` in
    # document order. The audit takes them as they are (``parts``); ``cells`` turns them
    # into Cell objects on first use.
    chunks: list[Chunk] = field(default_factory=list, repr=False)
    _prepared: object = field(default=None, repr=False)
    _pending: Callable[[], None] | None = field(default=None, repr=False)  # fetches _prepared
    _unique: bool = field(default=False, repr=False)  # chunks checked to repeat no cell

    @property
    def cells(self) -> dict[str, Cell]:
        if self.chunks:
            self._materialize()
        return self._cells

    @cells.setter
    def cells(self, value: dict[str, Cell]) -> None:
        self._cells, self.chunks, self._rows = value, [], None

    @property
    def prepared(self) -> object:
        """What read_workbook's ``prepare(sheet)`` made of the sheet, in the process that
        read it (waiting for the other process, if it is still at it)."""
        if self._pending is not None:
            self._pending()
        return self._prepared

    @prepared.setter
    def prepared(self, value: object) -> None:
        self._prepared, self._pending = value, None

    def _materialize(self) -> None:
        cells = self._cells
        for rows, cols, values, formulas in self.chunks:
            letters = {c: column_letters(c) for c in set(cols)}
            refs = list(map(str.__add__, map(letters.__getitem__, cols), map(str, rows)))
            kinds = [None if f is None else "normal" for f in formulas]
            cells.update(zip(refs, map(Cell, refs, rows, cols, values, formulas, kinds)))
        self.chunks = []

    def adopt(self, cells: dict[str, Cell], chunks: list[Chunk]) -> None:
        """The cells and chunks of this sheet as another process read them (its ``parts``
        checked the chunks)."""
        self.cells = cells
        self.chunks, self._unique = chunks, True

    def chunk(self) -> Chunk:
        """The open chunk the scanner appends plain cells to."""
        if not self.chunks:
            self.chunks.append(([], [], [], []))
        self._unique = False
        return self.chunks[-1]

    def parts(self) -> tuple[list[Cell], list[Chunk]]:
        """``(cells, chunks)``: the sheet's cells as Cell objects, then, after them in
        document order, the plain ones as columns; every ref once (a sheet that repeats a
        ref is made all Cell objects, the last one kept, as ``cells`` does)."""
        if self.chunks and not self._unique:
            rows = [c.row for c in self._cells.values()]
            cols = [c.col for c in self._cells.values()]
            for chunk in self.chunks:
                rows += chunk[0]
                cols += chunk[1]
            at = np.array(rows, np.int64) * (MAX_COL + 1) + np.array(cols, np.int64)
            if not (np.diff(at) > 0).all() and len(np.unique(at)) != len(at):
                self._materialize()  # (in document order, each cell after the one before)
            self._unique = True
        return list(self._cells.values()), self.chunks

    def row_cells(self, row: int) -> list[Cell]:
        """The cells of one row by column, without making Cell objects of the others."""
        out = [c for c in self._cells.values() if c.row == row]
        for rows, cols, values, formulas in self.chunks:
            at, left = -1, rows.count(row)
            while left:  # (rows.index and count are C loops)
                at = rows.index(row, at + 1)
                left -= 1
                out.append(Cell(f"{column_letters(cols[at])}{row}", row, cols[at], values[at],
                                formulas[at], None if formulas[at] is None else "normal"))
        return sorted(out, key=lambda c: c.col)

    def __getitem__(self, ref: str) -> Cell:
        return self.cells[ref.replace("$", "").upper()]

    def cell(self, row: int, col: int) -> Cell | None:
        return self.cells.get(f"{column_letters(col)}{row}")

    def row(self, row: int) -> list[Cell]:
        if self._rows is None:
            rows: dict[int, list[Cell]] = {}
            for cell in self.cells.values():
                rows.setdefault(cell.row, []).append(cell)
            self._rows = {r: sorted(cs, key=lambda c: c.col) for r, cs in rows.items()}
        return self._rows.get(row, [])

    def column(self, col: int) -> list[Cell]:
        return sorted((c for c in self.cells.values() if c.col == col), key=lambda c: c.row)

    @property
    def max_row(self) -> int:
        return max([max((c.row for c in self._cells.values()), default=0),
                    *(max(c[0], default=0) for c in self.chunks)])

    @property
    def max_col(self) -> int:
        return max([max((c.col for c in self._cells.values()), default=0),
                    *(max(c[1], default=0) for c in self.chunks)])

    def formula_cells(self) -> Iterator[Cell]:
        return (c for c in self.cells.values() if c.has_formula)

    def formula_source(self, cell: Cell | str) -> tuple[str, str] | None:
        """``(text, origin_ref)`` of the formula of ``cell``, None if it has none.

        For a shared follower the text is the master's, written for ``origin_ref``:
        shift its relative references by the offset from origin_ref to the cell.
        """
        cell = self[cell] if isinstance(cell, str) else cell
        if cell.formula is not None:
            return cell.formula, cell.ref
        if cell.shared_index is not None and cell.shared_index in self.shared_formulas:
            shared = self.shared_formulas[cell.shared_index]
            return shared.text, shared.master
        return None


@dataclass(slots=True)
class ExternalLink:
    """A link to another workbook, never followed: what the file caches of it (the values
    of the cells its formulas read, as Excel last read them: ``<sheetDataSet>``)."""

    index: int  # the n of [n]Sheet!A1 in formula text
    part: str
    target: str | None  # the other workbook's path or URL as stored
    sheet_names: list[str] = field(default_factory=list)
    # sheet position (sheetId) -> {(row, col): value} of the cells cached
    cells: dict[int, dict[tuple[int, int], Value]] = field(default_factory=dict)
    # the other workbook's defined names: (name, sheet position or None) -> refersTo text
    names: dict[tuple[str, int | None], str] = field(default_factory=dict)


@dataclass
class Workbook:
    path: str
    sheets: list[Sheet]
    defined_names: dict[str, str]  # workbook-level names; sheet-local ones are on Sheet
    external_links: list[ExternalLink]
    other_sheets: list[tuple[str, str]]  # (name, kind) of chartsheets, dialog sheets, ...
    date1904: bool = False
    iterate: bool = False  # calcPr iterate="1": iterative calculation of circular references
    vba_project: str | None = None  # the part holding macros (xl/vbaProject.bin), never run
    application: str | None = None  # docProps/app.xml's Application: the program that saved it
    # the cube functions' cache of each connection (xlsx.olap), by case-folded name
    olap: dict = field(default_factory=dict)
    # the RTD calls' last values (xlsx.topics): ProgID -> (server, topics...) -> value
    topics: dict = field(default_factory=dict)

    @property
    def sheet_names(self) -> list[str]:
        return [s.name for s in self.sheets]

    def sheet(self, name: str) -> Sheet:
        """The worksheet called ``name`` (case-insensitive, as Excel compares them)."""
        folded = name.casefold()
        for sheet in self.sheets:
            if sheet.name.casefold() == folded:
                return sheet
        raise KeyError(name)

    __getitem__ = sheet

    def resolve_name(self, name: str, sheet: str | None = None) -> str | None:
        """Text of defined name ``name`` seen from ``sheet``: local first, then global."""
        scopes = [self.sheet(sheet).defined_names] if sheet is not None else []
        for scope in [*scopes, self.defined_names]:
            for key, text in scope.items():
                if key.casefold() == name.casefold():
                    return text
        return None

    @property
    def n_cells(self) -> int:
        """Cells read (without making Cell objects of the plain ones)."""
        return sum(len(cells) + sum(len(c[0]) for c in chunks)
                   for cells, chunks in (s.parts() for s in self.sheets))


