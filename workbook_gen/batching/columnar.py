"""summary.parquet: the summary table as a columnar file (pandas, Dask, pyarrow and
DuckDB read it natively), written in row groups as the rows arrive, so a batch of a
million variants never holds its table in memory.

Columns, their names (with units) and order are summary.csv's.  Types: ``variant``
int64 (text where a design file names the variants), ``file``, ``status``, ``audit``
text, the varied parameters and every figure float64 (NaN: no number), a varied
option text (true/false too) or int64, ``rows_flagged``, ``rows_not_assembled`` int64 (null for a
refused variant).  A template figure that may be a text (``n/a: needs ...``, a
Grashof class) is float64 while every variant has a number or none, text when every
one is a text or none, and text for all when it is a mix (numbers as summary.csv
writes them).

While the batch runs, such a figure's texts go to a side file (its float column
holds null there), so the rows written keep every value exactly (``batches`` reads
them back, bounded, for the summaries' text when a column's kind changed); ``finish``
renames the main file when no text came, else writes the final file from both, a row
group at a time.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Iterable, Iterator, Mapping, Sequence

import numpy as np

from .blocktext import number_texts
from .rows import ROW_COUNTS

ROW_GROUP = 1 << 14      # rows per row group (a block of variants is ~1,000)
_TEXT = ("file", "status", "audit")


def _pa():
    import pyarrow
    import pyarrow.parquet  # noqa: F401  (the submodule)
    return pyarrow


class ParquetSink:
    """The rows of ``columns`` appended in order (``write``), then made summary.parquet
    at ``path`` (``finish``), or removed (``abort``)."""

    def __init__(self, path: Path, columns: Sequence[str], headers: Sequence[str],
                 texts: Iterable[str], numbered: bool, texts_always: Iterable[str] = (),
                 integers: Iterable[str] = ()):
        """``columns``: the summary's names (``headers``: as the files name them, with
        units); ``texts``: the figures that may hold texts; ``numbered``: every
        variant's label its number; ``texts_always``, ``integers``: varied options
        whose values are texts (true/false too), integers."""
        pa = _pa()
        self.path, self.columns = Path(path), list(columns)
        texts = set(texts)
        self.texts = [name for name in columns if name in texts]
        always, integers = set(texts_always) | set(_TEXT), set(integers) | set(ROW_COUNTS)
        fields = []
        for name, head in zip(self.columns, headers):
            if name == "variant":
                kind = pa.int64() if numbered else pa.string()
            elif name in always:
                kind = pa.string()
            elif name in integers:
                kind = pa.int64()
            else:
                kind = pa.float64()
            fields.append(pa.field(head, kind))
        self._head = dict(zip(columns, headers))
        self.schema = pa.schema(fields)
        self._numbered = numbered
        self._main = self._temp(".parquet.tmp")
        self._side = self._temp(".texts.parquet.tmp") if self.texts else None
        # dictionary encoding for the texts only: for the float columns (distinct
        # values) it would hold a dictionary and its hash table per column, ~4 MB each
        self._writer = pa.parquet.ParquetWriter(
            self._main, self.schema, use_dictionary=self._texts(self.schema))
        self._side_schema = pa.schema([pa.field(n, pa.string()) for n in self.texts])
        self._side_writer = (pa.parquet.ParquetWriter(self._side, self._side_schema)
                             if self.texts else None)
        self._buffer: list[tuple[object, object]] = []
        self._buffered = 0
        self.has_text = dict.fromkeys(self.texts, False)

    @staticmethod
    def _texts(schema) -> list[str]:
        pa = _pa()
        return [f.name for f in schema if f.type == pa.string()]

    def _temp(self, suffix: str) -> Path:
        fd, name = tempfile.mkstemp(prefix=f".{self.path.stem}.", suffix=suffix,
                                    dir=self.path.parent)
        os.close(fd)
        return Path(name)

    def write(self, data: Mapping[str, Sequence[object]], count: int) -> None:
        """``count`` rows: each column's values (floats, None or NaN for no number;
        texts; a text-capable figure's numbers and texts)."""
        pa = _pa()
        arrays, side = [], []
        for field, name in zip(self.schema, self.columns):
            values = data[name]
            if name == "variant" and self._numbered:
                arrays.append(pa.array(np.asarray(values, dtype=np.int64)))
            elif name in self.has_text:
                numbers = [v if not isinstance(v, str) else None for v in values]
                words = [v if isinstance(v, str) else None for v in values]
                if any(w is not None for w in words):
                    self.has_text[name] = True
                arrays.append(pa.array(numbers, pa.float64()))
                side.append(pa.array(words, pa.string()))
            elif isinstance(values, np.ndarray):
                arrays.append(pa.array(values, field.type))
            elif field.type == pa.string():
                arrays.append(pa.array(["" if v is None else str(v) for v in values],
                                       pa.string()))
            else:
                arrays.append(pa.array(list(values), field.type))
        self._buffer.append((pa.RecordBatch.from_arrays(arrays, schema=self.schema),
                             pa.RecordBatch.from_arrays(side, schema=self._side_schema)
                             if self.texts else None))
        self._buffered += count
        if self._buffered >= ROW_GROUP:
            self._flush()

    def _flush(self) -> None:
        if not self._buffer:
            return
        pa = _pa()
        main = pa.Table.from_batches([b for b, _ in self._buffer], self.schema)
        self._writer.write_table(main, row_group_size=max(1, self._buffered))
        if self.texts:
            side = pa.Table.from_batches([s for _, s in self._buffer], self._side_schema)
            self._side_writer.write_table(side, row_group_size=max(1, self._buffered))
        self._buffer, self._buffered = [], 0

    def close(self) -> None:
        """No more rows (``batches`` may read them)."""
        self._flush()
        for writer in (self._writer, self._side_writer):
            if writer is not None:
                writer.close()
        self._writer = self._side_writer = None

    def batches(self, names: Sequence[str] | None = None, start: int = 0
                ) -> Iterator[tuple[int, dict[str, list]]]:
        """The rows written (after ``close``) from row ``start`` (0-based) on, a row
        group at a time: (its first row, each column's values as written, a
        text-capable figure's texts back in place)."""
        pa = _pa()
        names = list(names or self.columns)
        main = pa.parquet.ParquetFile(self._main)
        side = pa.parquet.ParquetFile(self._side) if self.texts else None
        first = 0
        for group in range(main.num_row_groups):
            count = main.metadata.row_group(group).num_rows
            first, lo = first + count, first
            if first <= start:
                continue
            table = main.read_row_group(group, columns=[self._head[n] for n in names])
            words = side.read_row_group(group) if side is not None else None
            out = {}
            for name in names:
                values = table.column(self._head[name]).to_pylist()
                if name == "variant" and self._numbered:
                    values = [str(v) for v in values]
                if name in self.has_text and self.has_text[name]:
                    texts = words.column(name).to_pylist()
                    values = [t if t is not None else v for v, t in zip(values, texts)]
                out[name] = values[max(0, start - lo):]
            yield max(lo, start), out

    def column(self, name: str):
        """A whole column written (after ``close``): a float64 array for a column of
        numbers (8 bytes a value), else a list of the values as written."""
        pa = _pa()
        head = self._head[name]
        values = pa.parquet.read_table(self._main, columns=[head]).column(head)
        if name in self.has_text and self.has_text[name]:
            texts = pa.parquet.read_table(self._side, columns=[name]).column(name)
            return [t if t is not None else v for v, t in zip(values.to_pylist(),
                                                               texts.to_pylist())]
        if values.type == pa.float64():
            return values.to_numpy()      # null (None) as NaN: no number, as written
        return values.to_pylist() if name != "variant" or not self._numbered else [
            str(v) for v in values.to_pylist()]

    def finish(self, kinds: Mapping[str, str]) -> None:
        """summary.parquet at ``path`` (``kinds``: each column's kind in the whole
        table, as ``Table.kind`` gives it)."""
        self.close()
        texts = [n for n in self.texts if self.has_text[n] and kinds[n] != "number"]
        if not texts:
            os.chmod(self._main, 0o644)
            os.replace(self._main, self.path)
            self._remove(self._side)
            return
        pa = _pa()
        heads = {self._head[n] for n in texts}
        schema = pa.schema([pa.field(f.name, pa.string()) if f.name in heads else f
                            for f in self.schema])
        final = self._temp(".final.parquet.tmp")
        main = pa.parquet.ParquetFile(self._main)
        side = pa.parquet.ParquetFile(self._side)
        try:
            with pa.parquet.ParquetWriter(final, schema,
                                          use_dictionary=self._texts(schema)) as writer:
                for group in range(main.num_row_groups):
                    table = main.read_row_group(group)
                    words = side.read_row_group(group)
                    for name in texts:
                        head = self._head[name]
                        numbers = number_texts(table.column(head).to_numpy(
                            zero_copy_only=False))
                        column = [t if t is not None else (n or None) for n, t in zip(
                            numbers, words.column(name).to_pylist())]
                        table = table.set_column(table.schema.get_field_index(head),
                                                 pa.field(head, pa.string()),
                                                 pa.array(column, pa.string()))
                    writer.write_table(table, row_group_size=max(1, table.num_rows))
            os.chmod(final, 0o644)
            os.replace(final, self.path)
        finally:
            self._remove(final)
        self._remove(self._main)
        self._remove(self._side)

    @staticmethod
    def _remove(path: Path | None) -> None:
        if path is not None:
            path.unlink(missing_ok=True)

    def abort(self) -> None:
        for writer in (self._writer, self._side_writer):
            if writer is not None:
                try:
                    writer.close()
                except Exception:  # noqa: BLE001  (removing it anyway)
                    pass
        self._writer = self._side_writer = None
        self._remove(self._main)
        self._remove(self._side)
