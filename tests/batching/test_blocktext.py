"""The summary's rows formatted a block at a time (batching/blocktext.py): the texts
are Python's own ``repr`` of each number, and a block formatted by a worker gives the
bytes the command gives when it formats the whole table itself."""

from __future__ import annotations

import csv
import io
import re
import zipfile
from pathlib import Path
from xml.etree import ElementTree

import numpy as np
import openpyxl
import pytest
import xlsxwriter

from workbook_gen import batch, cli
from workbook_gen.batching import api, blocktext, summary_only
from workbook_gen.batching.table import Table

ROOT = Path(__file__).resolve().parents[2]
SEWING = str(ROOT / "templates" / "sewing_machine.toml")
TRICKY = [0.0, -0.0, 0.1, 1e-05, 0.0001, 1e16, 1e15, 123456789012345.6, 5e-324,
          -1.7976931348623157e308, 2.0 ** -1074 * 3, 95.01, 1 / 3, -197.16118968844148,
          float("nan"), float("inf"), None]


def test_number_texts_are_repr_of_each_number_and_empty_for_none_and_nan():
    rng = np.random.default_rng(5)
    values = TRICKY + rng.normal(0, 1e3, 500).tolist() + (10.0 ** rng.uniform(
        -30, 30, 500)).tolist() + [0.25] * 50
    expected = ["" if v is None or v != v else repr(v) for v in values]
    assert blocktext.number_texts(values) == expected  # floats and None: numpy path
    floats = np.array([np.nan if v is None else v for v in values])
    assert blocktext.number_texts(floats) == expected
    assert blocktext.number_texts([3, None, 0, 2.5]) == ["3", "", "0", "2.5"]


def test_fast_float_texts_are_repr_on_every_kind_of_float():
    """orjson's text where it spells a float as repr does, repr elsewhere: equal to repr
    on random bit patterns (every exponent, subnormals, NaN payloads, infinities), the
    neighbours of each band edge and of powers of ten, integers and short decimals."""
    rng = np.random.default_rng(11)
    edges = np.array([1e-4, 1e-3, 1e15, 1e16] + [10.0 ** k for k in range(-20, 21)])
    near = [np.nextafter(edges, s) for s in (0, np.inf)]
    for _ in range(3):
        near += [np.nextafter(near[-2], 0), np.nextafter(near[-1], np.inf)]
    values = np.concatenate([
        rng.integers(0, 2 ** 64, 200_000, dtype=np.uint64).view(np.float64),
        rng.normal(0, 1e3, 50_000), rng.uniform(-1, 1, 50_000) * 10.0 ** rng.integers(
            -8, 20, 50_000), np.round(rng.normal(0, 1e6, 20_000)),
        np.round(rng.normal(0, 100, 20_000), 3), edges, -edges, *near, [0.0, -0.0]])
    floats = values.tolist()
    expected = ["" if x != x else repr(x) for x in floats]
    assert blocktext._repr_texts(floats) == expected


RANDOM = ["l_AB=normal:32:16", "l_BC=uniform:20:110"]  # refused (l_AB <= 0) and partial rows


def _summaries(folder: Path) -> tuple[bytes, bytes]:
    out = folder / "sewing_machine-batch"
    return (out / "summary.csv").read_bytes(), (out / "summary.xlsx").read_bytes()


def _run(folder: Path, jobs: int) -> tuple[bytes, bytes]:
    frame = batch(SEWING, vary=RANDOM, samples=60, seed=3, out=folder, jobs=jobs, step=30.0,
                  summary_only=True, progress=False)
    statuses = {s.split(":")[0] for s in frame["status"]}
    assert statuses == {"ok", "partial", "refused"}
    return _summaries(folder)


@pytest.fixture(scope="module")
def formatted_here(tmp_path_factory):
    """The summaries with every row formatted in the command (the workers' texts
    ignored): the reference the workers' blocks must give byte for byte."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(summary_only, "BLOCK_ELEMENTS", 70)  # 5 variants of 13 rows a block
        patch.setattr(api.SummaryWriter, "add", lambda self, *block: None)
        patch.setattr(api, "Table", lambda *args, keep, **kw: Table(*args, **kw))  # the rows held by
        # the table, as a file batch's (--summary-only streams them)
        return _run(tmp_path_factory.mktemp("here"), jobs=1)


@pytest.mark.parametrize("jobs", [1, 2])
def test_blocks_formatted_by_workers_give_the_bytes_of_the_command(formatted_here, tmp_path,
                                                                   monkeypatch, jobs):
    monkeypatch.setattr(summary_only, "BLOCK_ELEMENTS", 70)
    assert _run(tmp_path, jobs) == formatted_here


def test_a_block_formatted_with_another_kind_is_formatted_again(formatted_here, tmp_path,
                                                                monkeypatch):
    # Workers that take a figure column for another kind than the whole table's (here
    # numbers only, where the exact needle stroke is "n/a: needs l_BC >= l_AB" on the
    # partial variants, a mixed column): the command notices and formats every row itself.
    monkeypatch.setattr(summary_only, "BLOCK_ELEMENTS", 70)
    monkeypatch.setattr(summary_only, "value_kind", lambda values: "number")
    assert _run(tmp_path, 1) == formatted_here


def test_summary_xlsx_is_the_zip_zipfile_writes_for_its_members(formatted_here, tmp_path):
    """The Variants sheet is deflated as its rows arrive (ISA-L) and spliced into
    XlsxWriter's zip: every other member is byte for byte what zipfile writes (as
    XlsxWriter calls it: each member from a temporary file dated 1980-01-31, zlib
    level 1), and the Variants member has zipfile's header with its own deflate data,
    which inflates to the sheet (CRC checked)."""
    import io
    import os
    import tempfile
    import time
    import zipfile
    from workbook_gen.batching.summary import VARIANTS
    data = formatted_here[1]
    target = io.BytesIO()
    stamp = time.mktime((1980, 1, 31, 0, 0, 0, 0, 0, -1))
    with zipfile.ZipFile(io.BytesIO(data)) as ours, zipfile.ZipFile(
            target, "w", zipfile.ZIP_DEFLATED, compresslevel=1) as theirs:
        for info in ours.infolist():
            fd, temp = tempfile.mkstemp(dir=tmp_path)
            with os.fdopen(fd, "wb") as handle:
                handle.write(ours.read(info))
            os.utime(temp, (stamp, stamp))
            theirs.write(temp, info.filename)

    def members(book: bytes):
        with zipfile.ZipFile(io.BytesIO(book)) as z:
            for i in z.infolist():
                start = i.header_offset + 30 + len(i.filename.encode()) + len(i.extra)
                yield (i.filename, i.date_time, i.CRC, i.file_size, i.compress_type,
                       i.external_attr, z.read(i)), book[start:start + i.compress_size]

    ours, theirs = list(members(data)), list(members(target.getvalue()))
    assert [m for m, _ in ours] == [m for m, _ in theirs]
    for (meta, raw), (_, raw_zipfile) in zip(ours, theirs):
        assert raw == raw_zipfile or meta[0] == VARIANTS
    assert any(meta[0] == VARIANTS and raw != raw_zipfile
               for (meta, raw), (_, raw_zipfile) in zip(ours, theirs))


def test_a_sheet_start_not_foreseen_is_corrected(formatted_here, tmp_path, monkeypatch):
    from workbook_gen.batching import summary
    monkeypatch.setattr(summary_only, "BLOCK_ELEMENTS", 70)
    monkeypatch.setattr(summary, "_variants_xml", lambda table: (b"<worksheet>", b""))
    assert _run(tmp_path, 1) == formatted_here


def test_the_folder_key_of_the_variants_is_their_json(tmp_path):
    import json
    from workbook_gen.batching.api import variants_json
    from workbook_gen.batching.variants import Variant, from_specs
    plans = [from_specs(["l_AB=normal:32:8", "l_BC=uniform:20:110"], ["l_AB", "l_BC"], [],
                        50, 1).variants,
             (Variant(1, 'a "quoted", label', (("l_AB", 1e-05),)), Variant(2, "é\n", ()),
              Variant(3, "x1", (("l_AB", -0.0), ("l_BC", 1e16))),
              Variant(4, "x2", (("l_AB", 0.0), ("l_BC", 1e16))),
              Variant(5, "x3", (("l_AB", -0.0), ("l_BC", float("nan"))))),
             from_specs(["l_AB=-1:1:0.5", "l_BC=1,2"], ["l_AB", "l_BC"]).variants, ()]
    for variants in plans:
        assert variants_json(variants) == json.dumps(
            [[v.label, [[k, repr(x)] for k, x in v.values]] for v in variants])


# -- text from a design file: legal XML whatever it holds (issue 22 item 4) -----------------

HOSTILE = ["bell\x07", "_x0041_", "_x005F_", "nul\x00byte", "cr\rlf\nline", "tab\tin",
           "form\x0cfeed\x1fsep", "non-char\ufffe\uffff", 'a<b>&"c"', "_X00e9_ _x12_", "ünï ☃ 𝄞"]


def _xstring_decoded(text: str) -> str:
    """ECMA-376 Part 1, 22.9.2.19 ST_Xstring: each ``_xHHHH_`` is the character U+HHHH
    (``_x005F_`` the underscore that starts a literal ``_xHHHH_``)."""
    return re.sub(r"_x([0-9A-Fa-f]{4})_", lambda m: chr(int(m.group(1), 16)), text)


def test_design_names_with_control_characters_are_legal_xml_and_read_back(tmp_path):
    design = tmp_path / "hostile.csv"
    with design.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(["variant", "l_AB"])
        writer.writerows([name, 30 + i / 10] for i, name in enumerate(HOSTILE))
    batch(SEWING, design=design, out=tmp_path, summary_only=True, step=30.0, progress=False)
    path = tmp_path / "sewing_machine-batch" / "summary.xlsx"
    with zipfile.ZipFile(path) as z:  # every part parses as XML 1.0 (expat)
        for name in z.namelist():
            if name.endswith((".xml", ".rels")):
                ElementTree.fromstring(z.read(name))
        sheet_xml = z.read("xl/worksheets/sheet1.xml").decode()
    for read_only in (True, False):  # openpyxl opens it; its raw text decodes to the name
        book = openpyxl.load_workbook(path, read_only=read_only)
        names = [r[0] for r in book["Variants"].iter_rows(min_row=2, values_only=True)]
        assert [_xstring_decoded(n) for n in names] == HOSTILE
    # the escapes are XlsxWriter's own for the same texts
    reference = io.BytesIO()
    with xlsxwriter.Workbook(reference, {"constant_memory": True}) as book:
        sheet = book.add_worksheet()
        for row, name in enumerate(HOSTILE, start=1):
            sheet.write_string(row, 0, name)
    with zipfile.ZipFile(reference) as z:
        expected = re.findall(r"<is>(.*?)</is>", z.read("xl/worksheets/sheet1.xml").decode())
    assert re.findall(r'<c r="A\d+" t="inlineStr"><is>(.*?)</is>', sheet_xml) == expected
    # summary.csv holds the names as they are
    with (tmp_path / "sewing_machine-batch" / "summary.csv").open(newline="",
                                                                  encoding="utf-8") as handle:
        assert [r[0] for r in csv.reader(handle)][1:] == HOSTILE


def test_a_design_name_longer_than_a_cell_is_refused_in_one_line(tmp_path, capsys):
    design = tmp_path / "long.csv"
    design.write_text("variant,l_AB\nfine,30\n" + "x" * 32_768 + ",31\n")
    code = cli.main(["batch", SEWING, "--design", str(design), "--out", str(tmp_path / "out"),
                     "--summary-only", "--quiet"])
    err = capsys.readouterr().err
    assert code == 2 and not (tmp_path / "out").exists()
    assert err.count("\n") == 1 and "row 3, variant: a name of 32,768 characters, more " \
        "than the 32,767 an Excel cell holds" in err
    design.write_text("variant,l_AB\n" + "x" * 32_767 + ",31\n")  # the limit itself is fine
    assert cli.main(["batch", SEWING, "--design", str(design), "--out", str(tmp_path / "out"),
                     "--summary-only", "--quiet", "--step", "30"]) == 0
    sheet = openpyxl.load_workbook(tmp_path / "out" / "sewing_machine-batch" / "summary.xlsx",
                                   read_only=True)["Variants"]
    assert next(sheet.iter_rows(min_row=2, values_only=True))[0] == "x" * 32_767


def test_a_command_longer_than_a_cell_is_kept_whole_on_the_about_sheet(tmp_path):
    values = ",".join(f"{30 + i / 1000:.3f}" for i in range(6000))
    batch(SEWING, vary=[f"l_AB={values}"], out=tmp_path, summary_only=True, step=90.0,
          progress=False)
    rows = list(openpyxl.load_workbook(
        tmp_path / "sewing_machine-batch" / "summary.xlsx", read_only=True)["About"]
        .iter_rows(values_only=True))
    command = [rows[0][1]] + [r[1] for r in rows[1:] if r[0] is None and rows.index(r) < 3]
    assert all(len(piece) <= 32_767 for piece in command) and len(command) == 2
    assert "".join(command) == (f"workbook-gen batch {SEWING} --vary l_AB={values} "
                                f"--step 90 --summary-only")
