"""A batch of any accepted size finishes (issue 22, item 8): summary.xlsx in ZIP64 form
where its Variants sheet needs it (in the form Excel reads: checked here by zipfile,
openpyxl and LibreOffice on small sheets with the threshold forced low), summary.parquet
beside summary.csv, rows streamed (no table of a million rows held) and variants held
as columns."""

from __future__ import annotations

import csv
import io
import itertools
import math
import pickle
import struct
import zipfile
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import openpyxl
import pandas as pd
import pyarrow.parquet as pq
import pytest

from workbook_gen import batch
from workbook_gen.batching import columnar, sheetzip, summary_only
from workbook_gen.batching.api import variants_digest, variants_json
from workbook_gen.batching.folder import digest
from workbook_gen.batching.summary import VARIANTS
from workbook_gen.batching.variants import ColumnVariants, from_specs

ROOT = Path(__file__).resolve().parents[2]
SEWING = str(ROOT / "templates" / "sewing_machine.toml")
# refused (l_AB <= 0), partial, and "n/a: needs l_BC >= l_AB" in the exact needle
# stroke where the rod is shorter than the crank: a figure column of numbers and texts
RANDOM = ["l_AB=normal:32:16", "l_BC=uniform:20:110"]
GRID = ["l_BC=95:105:1", "l_AB=30,32"]


def _csv(folder: Path) -> list[list[str]]:
    with (folder / "summary.csv").open(newline="") as handle:
        return list(csv.reader(handle))


def _cell_text(value) -> str:
    """A cell read back, as summary.csv writes it."""
    if value is None:
        return ""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return str(value)
    return repr(float(value))


def _same_as_csv(rows, expected: list[list[str]], digits: int = 17) -> None:
    """Sheet rows (values) against summary.csv: numbers to the bit (to ``digits``
    significant digits: LibreOffice saves 15), texts exactly."""
    rows = list(rows)
    assert len(rows) == len(expected)
    for got, want in zip(rows, expected):
        got = list(got) + [None] * (len(want) - len(got))
        for g, w in zip(got, want):
            if isinstance(g, (int, float)) and not isinstance(g, bool):
                assert math.isclose(float(g), float(w), rel_tol=10.0 ** (1 - digits),
                                    abs_tol=0.0) if digits < 17 else float(g) == float(w), (
                    got, want)
            else:
                assert _cell_text(g) == w, (got, want)


def _run(out: Path, vary=GRID, **options) -> Path:
    batch(SEWING, vary=vary, out=out, jobs=1, step=30.0, summary_only=True, progress=False,
          **options)
    return out / "sewing_machine-batch"


@pytest.fixture(scope="module")
def zip64_local(tmp_path_factory):
    """A summary whose Variants sheet is written in the ZIP64 local form (threshold 1
    byte), its central directory entry as below 4 GiB."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(sheetzip, "ZIP64_THRESHOLD", 1)
        return _run(tmp_path_factory.mktemp("zip64"))


def _local_header(data: bytes, name: str) -> tuple[int, ...]:
    info = zipfile.ZipFile(io.BytesIO(data)).getinfo(name)
    at = info.header_offset
    fields = struct.unpack("<4sHHHHHIIIHH", data[at:at + 30])
    end = at + 30 + fields[9] + fields[10] + info.compress_size
    descriptor = struct.unpack("<4sIQQ", data[end:end + 24])
    return fields, descriptor, info


def test_a_variants_sheet_past_the_threshold_has_the_zip64_local_form(zip64_local):
    data = (zip64_local / "summary.xlsx").read_bytes()
    fields, descriptor, info = _local_header(data, VARIANTS)
    sig, version, flags, method, _, _, crc, csize, size, _, extra = fields
    assert (sig, version, flags & 0x08, method) == (b"PK\x03\x04", 45, 0x08, 8)
    assert (crc, csize, size, extra) == (0, 0, 0, 0)   # all in the data descriptor
    assert descriptor == (b"PK\x07\x08", info.CRC, info.compress_size, info.file_size)
    assert info.extract_version == 45 and info.flag_bits & 0x08
    assert zipfile.ZipFile(io.BytesIO(data)).testzip() is None   # every CRC checked
    # every other member as XlsxWriter's zip has it: version 2.0, no descriptor
    for other in zipfile.ZipFile(io.BytesIO(data)).infolist():
        if other.filename != VARIANTS:
            assert (other.extract_version, other.flag_bits & 0x08) == (20, 0)


def test_openpyxl_and_libreoffice_read_the_zip64_summary(zip64_local, tmp_path):
    from workbook_gen.engines.libreoffice import recalculate
    expected = _csv(zip64_local)
    ours = openpyxl.load_workbook(zip64_local / "summary.xlsx")["Variants"]
    _same_as_csv(ours.iter_rows(values_only=True), expected)
    saved = recalculate(zip64_local / "summary.xlsx", tmp_path)   # refuses a file it cannot load
    theirs = openpyxl.load_workbook(saved)["Variants"]
    _same_as_csv(theirs.iter_rows(values_only=True), expected, digits=15)


def test_a_sheet_of_4_gib_has_its_size_in_a_zip64_extra_field(tmp_path, monkeypatch):
    monkeypatch.setattr(sheetzip, "ZIP64_THRESHOLD", 1)
    monkeypatch.setattr(sheetzip, "ZIP64_EXTRA_THRESHOLD", 1)
    folder = _run(tmp_path)
    data = (folder / "summary.xlsx").read_bytes()
    entries = []
    at = data.index(b"PK\x01\x02")
    while data[at:at + 4] == b"PK\x01\x02":
        head = struct.unpack(zipfile.structCentralDir, data[at:at + 46])
        name = data[at + 46:at + 46 + head[12]].decode()
        extra = data[at + 46 + head[12]:at + 46 + head[12] + head[13]]
        entries.append((name, head, extra))
        at += 46 + head[12] + head[13] + head[14]
    info = zipfile.ZipFile(io.BytesIO(data)).getinfo(VARIANTS)
    (_, head, extra), = [e for e in entries if e[0] == VARIANTS]
    assert (head[1], head[3], head[11]) == (45, 45, 0xFFFFFFFF)   # versions, size
    assert extra == struct.pack("<HHQ", 1, 8, info.file_size)
    assert info.file_size == len(zipfile.ZipFile(io.BytesIO(data)).read(VARIANTS))
    rows = openpyxl.load_workbook(folder / "summary.xlsx")["Variants"].iter_rows(
        values_only=True)
    _same_as_csv(rows, _csv(folder))


def test_a_million_variant_sheet_takes_the_zip64_branch(zip64_local):
    """At the default thresholds: the sheet's XML per variant (from the small batch)
    times a million (~2.3 GB) is past the local form's threshold (the command writes
    the form above), not yet the extra field's (4 GiB)."""
    with zipfile.ZipFile(zip64_local / "summary.xlsx") as archive:
        sheet = archive.read(VARIANTS)
    rows = sheet.count(b"<row ") - 1
    per_row = (sheet.rindex(b"</row>") - sheet.index(b"</row>")) / rows
    million = SimpleNamespace(size=int(per_row * 1_000_000))
    assert sheetzip.ZIP64_THRESHOLD < million.size < sheetzip.ZIP64_EXTRA_THRESHOLD
    assert sheetzip.needs_zip64(million)
    assert not sheetzip.needs_zip64(SimpleNamespace(size=len(sheet)))


# -- summary.parquet ----------------------------------------------------------------------

@pytest.fixture(scope="module")
def mixed(tmp_path_factory):
    """A random study with refused, partial and n/a rows, in blocks of 5 variants and
    Parquet row groups of 16 rows."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(summary_only, "BLOCK_ELEMENTS", 70)
        patch.setattr(columnar, "ROW_GROUP", 16)
        return _run(tmp_path_factory.mktemp("mixed"), RANDOM, samples=60, seed=3)


def _named(frame: pd.DataFrame, name: str) -> str:
    """The header of summary column ``name`` (``y_C_max [mm]``)."""
    found, = [c for c in frame.columns if c == name or c.startswith(name + " [")]
    return found


def _check_parquet(folder: Path) -> pd.DataFrame:
    """summary.parquet read by pandas against summary.csv: same columns, same values,
    numbers as float64, variant as int64, texts as texts."""
    expected = pd.read_csv(folder / "summary.csv", dtype=str, keep_default_na=False)
    frame = pd.read_parquet(folder / "summary.parquet")
    assert list(frame.columns) == list(expected.columns)
    assert len(frame) == len(expected)
    for name in expected.columns:
        column, want = frame[name], expected[name].tolist()
        if name == "variant":
            assert column.dtype == np.int64 and column.tolist() == [int(w) for w in want]
        elif name in ("rows_not_assembled", "rows_flagged"):
            assert [("" if pd.isna(v) else str(int(v))) for v in column] == want
        elif column.dtype == np.float64:
            assert [("" if math.isnan(v) else repr(v)) for v in column] == want, name
        else:
            assert [("" if v is None or v != v else v) for v in column] == want, name  # null
    return frame


def test_parquet_has_the_csv_columns_and_values(mixed):
    frame = _check_parquet(mixed)
    statuses = {s.split(":")[0] for s in frame["status"]}
    assert statuses == {"ok", "partial", "refused"}
    texts = frame[_named(frame, "needle_stroke_exact")].dropna()   # a mix of numbers and texts: texts
    assert len(texts) > 30 and texts.map(type).isin([str]).all()
    assert any(v.startswith("n/a") for v in texts)
    assert frame[_named(frame, "y_C_max")].dtype == np.float64
    assert frame[_named(frame, "l_AB")].dtype == np.float64
    # blocks of 5 variants, a row group from 16 rows on: 3 of 20
    assert pq.ParquetFile(mixed / "summary.parquet").num_row_groups == 3
    assert not list(mixed.glob(".summary.*"))   # no temporary file left


def test_parquet_of_a_file_batch_and_of_a_grid(tmp_path, monkeypatch):
    monkeypatch.setattr(columnar, "ROW_GROUP", 7)
    folder = tmp_path / "files" / "sewing_machine-batch"
    batch(SEWING, vary=["l_BC=20,95,105", "l_AB=-1,30,32"], out=tmp_path / "files", jobs=1,
          step=30.0, progress=False)
    frame = _check_parquet(folder)
    assert frame["file"].iloc[4] == "sewing_machine-0005.xlsx"
    grid = _check_parquet(_run(tmp_path / "grid"))
    assert grid[_named(grid, "needle_stroke_exact")].dtype == np.float64   # numbers: numbers


# -- rows streamed, variants as columns ----------------------------------------------------

def test_summary_only_keeps_no_row_in_memory(tmp_path, monkeypatch):
    """The table of a --summary-only batch holds no rows: its summaries are written
    as the blocks arrive (Parquet row groups before the last block comes)."""
    from workbook_gen.batching import api, summary
    monkeypatch.setattr(summary_only, "BLOCK_ELEMENTS", 70)
    monkeypatch.setattr(columnar, "ROW_GROUP", 10)
    seen = {"groups": 0, "sizes": []}
    flush, finish = columnar.ParquetSink._flush, summary.SummaryWriter.finish

    def flushed(self):
        seen["groups"] += bool(self._buffer)
        seen["sizes"].append(self._main.stat().st_size)
        flush(self)

    def finished(self, about, **options):
        seen["held"] = (self.table.keep, dict(self.table.data))   # after the last block
        finish(self, about, **options)

    monkeypatch.setattr(columnar.ParquetSink, "_flush", flushed)
    monkeypatch.setattr(summary.SummaryWriter, "finish", finished)
    done = api.run_batch(SEWING, GRID, out=tmp_path, jobs=1, step=30.0, summary_only=True,
                         progress=False)
    assert seen["held"] == (False, {})
    assert done.count == 22 and seen["groups"] >= 3
    assert seen["sizes"][1] > seen["sizes"][0]   # rows on disk while the batch ran
    frame = done.frame()
    assert len(frame) == 22 and frame.attrs["failed"] == done.failed == 0
    assert frame.attrs["units"]["y_C_max"] == "mm" and "y_C_max" in frame


def test_a_million_grid_variants_are_columns_and_equal_the_factorial():
    specs = ["l_BC=90:109.98:0.02", "l_AB=25:34.99:0.01"]
    design = from_specs(specs, ["l_AB", "l_BC"])
    variants = design.variants
    assert isinstance(variants, ColumnVariants) and len(design) == 1_000_000
    assert sum(c.nbytes for c in variants.columns) == 16_000_000
    levels = design.levels
    for k in (0, 1, 999, 1000, 123_456, 999_999):
        a, b = divmod(k, 1000)
        assert variants[k] == (k + 1, str(k + 1), (("l_BC", levels[0][a]), ("l_AB", levels[1][b])))
    part = variants[500_000:501_000]   # what a worker is sent
    assert len(pickle.dumps(part)) < 20_000
    assert list(part) == [variants[k] for k in range(500_000, 501_000)]
    small = from_specs(["l_BC=95:105:5", "l_AB=30,32", "l_BE=40:41:0.5"], ["l_AB", "l_BC", "l_BE"])
    assert [v.values for v in small.variants] == [
        (("l_BC", a), ("l_AB", b), ("l_BE", c)) for a, b, c in itertools.product(
            (95.0, 100.0, 105.0), (30.0, 32.0), (40.0, 40.5, 41.0))]


def test_the_folder_key_is_hashed_as_its_json_is_made():
    for variants in (from_specs(GRID, ["l_AB", "l_BC"]).variants,
                     from_specs(RANDOM, ["l_AB", "l_BC"], [], 5000, 1).variants, ()):
        assert variants_digest(variants) == digest(variants_json(variants).encode())
