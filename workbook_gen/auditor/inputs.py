"""What the auditor reads off a workbook: formula texts, constants, names, cached values."""

from __future__ import annotations

from dataclasses import dataclass, field
import time
from itertools import compress, islice, repeat
from pathlib import Path


from ..cellref import a1, cell_name
from ..errors import FormulaSyntaxError, WorkbookReadError
from ..evaluator import expand_shared
from ..evaluator.grouping import Grouped
from ..xlsx import read_workbook
from ..xlsx.model import Workbook

Key = tuple[str, int, int]

DATA_TABLE = ("data table (What-If Analysis): its values are not recomputed; the cells "
              "that read it read its cached values")


@dataclass
class AuditInputs:
    book: Workbook
    formulas: dict[Key, str] = field(default_factory=dict)     # text without '='
    cached: dict[Key, object] = field(default_factory=dict)    # cached value of each formula
    constants: dict[Key, object] = field(default_factory=dict)
    array_cells: list[Key] = field(default_factory=list)       # array formulas: not recomputed
    broken: dict[Key, str] = field(default_factory=dict)       # shared formulas that do not expand
    # formula cells with no text to recompute (a data table's <f t="dataTable"/>, an empty
    # <f/>): not checked, their readers read their cached values -> why
    opaque: dict[Key, str] = field(default_factory=dict)
    # array formulas: master -> (text, (last row, last col)); cached holds every cell they fill
    arrays: dict[Key, tuple[str, tuple[int, int]]] = field(default_factory=dict)
    _names: dict[str, Key] | None = None
    array_master: dict[Key, Key] = field(default_factory=dict)  # array cell -> its master
    grouped: Grouped | None = None  # the formulas' runs, when read_inputs grouped them
    # data tables (evaluator.whatif.DataTable); cached holds every cell they fill
    data_tables: list = field(default_factory=list)
    table_of: dict[Key, object] = field(default_factory=dict)  # table cell -> its table
    grouping_seconds: float = 0.0

    def uncheckable(self) -> dict[Key, str]:
        """Formula cells not handed to the evaluator, with the reason (cells an array
        formula fills included: what reads them is not checked either)."""
        return {k: f"formula syntax: {msg}" for k, msg in self.broken.items()}

    def text_of(self, key: Key) -> str:
        """The formula of a cell; for a cell an array formula fills, the array's."""
        if key in self.formulas:
            return self.formulas[key]
        if key in self.table_of:  # as Excel shows a data table's cells
            return "{=" + self.table_of[key].text() + "}"
        master = self.array_master.get(key)
        return "{=" + self.arrays[master][0] + "}" if master in self.arrays else ""

    def book_info(self):
        """Sheet order, sheet-scoped names and tables, for the evaluator."""
        from ..evaluator.book import BookInfo, Table
        from ..formula.tokenizer import CELL_PARTS, column_number
        def corners(ref: str | None):
            ends = [CELL_PARTS.fullmatch(p) for p in (ref or "").replace("$", "").split(":")]
            if len(ends) != 2 or not all(ends):
                return None
            return tuple(x for m in ends for x in (int(m.group(4)), column_number(m.group(2))))

        tables = []
        filtered: dict[str, frozenset[int]] = {}
        for sheet in self.book.sheets:
            ranges = [sheet.filter_ref]
            for t in sheet.tables:
                ranges.append(t.filter_ref)
                if (area := corners(t.ref)) is None:
                    continue
                r1, c1, r2, c2 = area
                tables.append(Table(t.name, sheet.name, r1, c1, r2, c2, tuple(t.columns),
                                    t.header_rows, t.totals_rows))
            # rows a filter hid: the hidden rows below a filtering autoFilter's header
            rows = {r for area in map(corners, ranges) if area is not None
                    for r in sheet.hidden_rows if area[0] < r <= area[2]}
            if rows:
                filtered[sheet.name] = frozenset(rows)
        from ..xlsx.reader import MISSING_PART
        return BookInfo(self.book.sheet_names,
                        {s.name: dict(s.defined_names) for s in self.book.sheets
                         if s.defined_names}, tables,
                        [name for name, kind in self.book.other_sheets if kind == MISSING_PART],
                        {s.name: frozenset(s.hidden_rows) for s in self.book.sheets
                         if s.hidden_rows}, filtered,
                        all_sheets=self._all_sheets(),
                        charset="mac_roman" if "macintosh" in (self.book.application or
                                                               "").lower() else "cp1252",
                        date1904=self.book.date1904,
                        olap=self.book.olap, external=self.book.external_links,
                        topics=self.book.topics)

    def _all_sheets(self) -> list[str]:
        """Every sheet's name in the workbook's order: the worksheets at their positions
        (``Sheet.index``), the other sheets, listed in order, at the positions left."""
        book = self.book
        by_position = {s.index: s.name for s in book.sheets}
        left = (i for i in range(len(book.sheets) + len(book.other_sheets))
                if i not in by_position)
        by_position.update(zip(left, (name for name, _ in book.other_sheets)))
        return [by_position[i] for i in sorted(by_position)]

    @property
    def formula_count(self) -> int:
        """Formula cells as the file stores them: an array formula counts once."""
        # array masters, and the cells of an array's area that the file gives an empty <f/>
        masters = sum(1 for k in self.array_cells
                      if self.book.sheet(k[0]).cell(k[1], k[2]).has_formula)
        return (len(self.formulas) + len(self.broken) + len(self.opaque) + masters
                + len(self.data_tables))

    def is_formula(self, key: Key) -> bool:
        if key in self.formulas or key in self.broken or key in self.table_of:
            return True
        cell = self.book.sheet(key[0]).cell(key[1], key[2])
        return cell is not None and cell.has_formula

    @staticmethod
    def ref(key: Key) -> str:
        """The A1 reference of a cell key: (sheet, 2, 3) -> 'C2'."""
        return a1(key[1], key[2])

    def cell_keys(self) -> dict[str, Key]:
        """'Sheet!B2' -> key, for the formula cells (built on first use)."""
        if self._names is None:
            self._names = {cell_name(k): k for k in self.cached}
        return self._names


def _array(inputs: AuditInputs, sheet, cell, key: Key) -> None:
    from ..formula.tokenizer import CELL_PARTS, column_number
    corners = [CELL_PARTS.fullmatch(p) for p in (cell.array_ref or cell.ref).replace("$", "")
               .split(":")]
    if not all(corners):
        return
    last = corners[-1]
    area = (max(cell.row, int(last.group(4))), max(cell.col, column_number(last.group(2))))
    text = sheet.formula_source(cell)[0] if cell.formula is not None else ""
    inputs.arrays[key] = (text, area)
    for r in range(cell.row, area[0] + 1):
        for c in range(cell.col, area[1] + 1):
            inputs.array_master[(sheet.name, r, c)] = key


def _data_table(inputs: AuditInputs, cell, key: Key) -> None:
    from ..evaluator.whatif import DataTable
    from ..formula.tokenizer import CELL_PARTS, column_number
    last = CELL_PARTS.fullmatch((cell.array_ref or cell.ref).replace("$", "").split(":")[-1])
    if last is not None:
        area = (max(cell.row, int(last.group(4))), max(cell.col, column_number(last.group(2))))
        inputs.data_tables.append(DataTable.of(key[0], cell.row, cell.col, area,
                                               cell.data_table))


def read_inputs(path: str | Path, group: bool = False) -> AuditInputs:
    """The formulas, cached values and constants of the workbook at ``path``; with
    ``group``, also the formulas' runs (``inputs.grouped``), each sheet's grouped as soon
    as it is read (while the other core still reads a large workbook's other sheets)."""
    if not Path(path).is_file():
        raise WorkbookReadError(f"{path}: no such file")
    inputs = AuditInputs(None)  # type: ignore[arg-type]  (the book once read)
    taken: set[str] = set()
    if group:
        inputs.grouped = Grouped()

    def take(sheet) -> None:  # each sheet once, in order
        if sheet.name in taken:  # read again after a failed read on two cores
            return
        taken.add(sheet.name)
        _sheet_inputs(inputs, sheet)
        if group:
            part, seconds = sheet.prepared
            if isinstance(part, str):  # the cost refused, named by file
                raise WorkbookReadError(f"{path}: {part}")
            inputs.grouped.merge(part)
            inputs.grouping_seconds += seconds

    inputs.book = read_workbook(path, ready=take, prepare=_grouped if group else None)
    for table in inputs.data_tables:  # (every sheet read: the cells they fill are known)
        for key in table.cells():
            inputs.table_of[key] = table
            inputs.cached[key] = inputs.constants.get(key)
    return inputs


def _grouped(sheet) -> tuple[Grouped | str, float]:
    """(the runs of one sheet's formulas, or why they were refused; seconds spent), in the
    process that read the sheet."""
    t = time.perf_counter()
    cells, chunks = sheet.parts()
    mine = AuditInputs(None)  # type: ignore[arg-type]
    _sheet_inputs(mine, sheet, cells, [])
    rows, cols = [k[1] for k in mine.formulas], [k[2] for k in mine.formulas]
    texts = list(mine.formulas.values())
    for chunk_rows, chunk_cols, _, formulas in chunks:
        is_formula = [t is not None for t in formulas]
        rows += compress(chunk_rows, is_formula)
        cols += compress(chunk_cols, is_formula)
        texts += compress(formulas, is_formula)
    grouped = Grouped()
    try:
        grouped.add_sheet(sheet.name, rows, cols, texts)
    except WorkbookReadError as exc:
        return str(exc), time.perf_counter() - t
    return grouped, time.perf_counter() - t


def _sheet_inputs(inputs: AuditInputs, sheet, cells=None, chunks=None) -> None:
    """Add one sheet's formulas, cached values and constants to ``inputs``."""
    formulas, cached, constants = inputs.formulas, inputs.cached, inputs.constants
    name = sheet.name
    if cells is None:
        cells, chunks = sheet.parts()
    for cell in cells:
        kind = cell.formula_type
        if kind is None and not cell.array_master:  # the common cases first, as below
            constants[(name, cell.row, cell.col)] = cell.value
            continue
        if kind == "normal" and cell.formula is not None and cell.array_master is None:
            key = (name, cell.row, cell.col)
            formulas[key] = cell.formula
            cached[key] = cell.value
            continue
        key = (name, cell.row, cell.col)
        if cell.is_array or (cell.array_master and cell.formula is None):
            inputs.array_cells.append(key)
            inputs.constants[key] = cell.value
            inputs.cached[key] = cell.value
            if cell.is_array:
                _array(inputs, sheet, cell, key)
            continue
        if kind == "dataTable" and cell.data_table is not None:  # recomputed (whatif)
            _data_table(inputs, cell, key)
            inputs.constants[key] = cell.value
            continue
        source = sheet.formula_source(cell) if cell.has_formula else None
        if source is None:
            inputs.constants[key] = cell.value
            if cell.has_formula:
                inputs.opaque[key] = (DATA_TABLE if kind == "dataTable" else
                                      "the file gives this cell a formula without text")
            continue
        text, origin = source
        if origin != cell.ref:
            master = sheet[origin]
            try:
                text = expand_shared(text, master.row, master.col, cell.row, cell.col)
            except FormulaSyntaxError as exc:
                inputs.broken[key] = str(exc)
                inputs.constants[key] = cell.value
                continue
        inputs.formulas[key] = text
        inputs.cached[key] = cell.value
    for rows, cols, values, texts in chunks:  # plain cells: whole columns at once
        _plain_cells(inputs, list(zip(repeat(name), rows, cols)), values, texts)


def _plain_cells(inputs: AuditInputs, keys: list[Key], values: list, texts: list) -> None:
    """Constants and formulas of the plain kind (text, no array or shared formula)."""
    is_formula = [t is not None for t in texts]
    if all(is_formula):
        inputs.formulas.update(zip(keys, texts))
        inputs.cached.update(zip(keys, values))
    elif not any(is_formula):
        inputs.constants.update(zip(keys, values))
    else:
        formula_keys = list(compress(keys, is_formula))
        inputs.formulas.update(zip(formula_keys, compress(texts, is_formula)))
        inputs.cached.update(zip(formula_keys, compress(values, is_formula)))
        is_constant = [not f for f in is_formula]
        inputs.constants.update(zip(compress(keys, is_constant), compress(values, is_constant)))
