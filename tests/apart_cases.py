"""The biggest sheets read in a forked child (xlsx/apart.py, workbook_gen/forked.py): the
Workbook is the one that reading every sheet in order gives, errors included.

Run by tests/xlsx/test_apart.py in a fresh pytest process: the audit forks only a process
without other threads, and the suite's own process has some (the Dask client's)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
import xlsxwriter

from workbook_gen import audit
from workbook_gen.auditor.inputs import read_inputs
from workbook_gen.errors import WorkbookReadError
from workbook_gen.forked import Forked, can_fork
from workbook_gen.xlsx import apart, read_workbook

CORPUS = Path("/work/shared/corpus/xlsx")
# several sheets with shared formulas, tables, strings, errors
CORPUS_FILES = ["formulas__test.xlsx", "xlcalculator__BASES.xlsx",
                "poi__StructuredRefs-lots-with-lookups.xlsx", "poi__stress024.xlsx"]


@pytest.fixture(scope="module")
def book(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("apart") / "three.xlsx"
    wb = xlsxwriter.Workbook(str(path))
    for n, name in enumerate(["First", "Second sheet", "Third"]):
        ws = wb.add_worksheet(name)
        for r in range(1, 300 + 100 * n):
            ws.write_number(r, 0, r * 0.1 + n)
            ws.write_formula(r, 1, f"=A{r + 1}*2", None, r * 0.2)
            ws.write_string(r, 2, f"text {r % 7}")  # shared strings
            ws.write_boolean(r, 3, r % 2 == 0)
            ws.write_formula(r, 4, "=1/0", None, "#DIV/0!")
        ws.write_array_formula("F2:F4", "{=A2:A4*2}", None, 0)
        ws.set_row(5, None, None, {"hidden": True})
    wb.close()
    return path


def _read(path: Path, serial: bool, monkeypatch, **limits):
    monkeypatch.setenv("WORKBOOK_GEN_SERIAL", "1" if serial else "0")
    try:
        wb = read_workbook(path, **limits)
    except WorkbookReadError as exc:
        return "error: " + str(exc)
    cells = [(s.name, ref, repr(c), type(c.value)) for s in wb.sheets
             for ref, c in s.cells.items()]
    return repr(wb), cells, [sorted(s.hidden_rows) for s in wb.sheets]


def test_forked_runs_in_a_child_and_hands_back_results_and_errors():
    assert can_fork(), "this machine should run the forked path (fork, one thread)"
    assert Forked(os.getpid).result() != os.getpid()
    with pytest.raises(ValueError, match="invalid literal"):
        Forked(int, "not a number").result()
    # a result that cannot be pickled is computed by the caller itself, same outcome
    pid, fn = Forked(lambda: (os.getpid(), lambda: 7)).result()
    assert pid == os.getpid() and fn() == 7


def _values(parent: int, fail_at: int | None = None, die_at: int | None = None):
    """A generator for Forked: (value, made in the child?) three times; an exception, or
    the child's death, at one of them."""
    for i in range(3):
        if i == fail_at:
            raise KeyError(f"at {i}")
        if i == die_at and os.getpid() != parent:
            os._exit(3)
        yield i, os.getpid() != parent


def test_forked_generator_sends_each_value_as_it_is_made():
    me = os.getpid()
    job = Forked(_values, me)
    assert [job.next() for _ in range(3)] == [(0, True), (1, True), (2, True)]
    job.close()
    job = Forked(_values, me, 1)  # its exception raised where the value would be
    assert job.next() == (0, True)
    with pytest.raises(KeyError, match="at 1"):
        job.next()
    # a child that dies: the values after the last it sent are made here
    job = Forked(_values, me, None, 1)
    assert [job.next() for _ in range(3)] == [(0, True), (1, False), (2, False)]
    job.close()
    # a value that cannot be pickled is made here, and those after it
    job = Forked(lambda: (yield from [(os.getpid(), 1), (os.getpid(), lambda: 2)]))
    assert job.next()[0] != me and job.next()[0] == me


@pytest.mark.parametrize("name", ["book", *CORPUS_FILES])
def test_two_processes_read_what_one_reads(name, book, monkeypatch):
    path = book if name == "book" else CORPUS / name
    assert path.is_file(), f"corpus file missing: {path}"
    monkeypatch.setattr(apart, "MIN_SHARE", 0)  # fork even for small sheets
    splits = []
    real = apart.split
    monkeypatch.setattr(apart, "split", lambda *a: splits.append(real(*a)) or splits[-1])
    forked = _read(path, False, monkeypatch)
    assert splits and splits[-1], "the child read no sheet"
    assert forked == _read(path, True, monkeypatch)


@pytest.mark.parametrize("max_cells", [500, 1500, 3000])
def test_cell_limit_names_the_same_sheet(max_cells, book, monkeypatch):
    monkeypatch.setattr(apart, "MIN_SHARE", 0)
    ours = _read(book, False, monkeypatch, max_cells=max_cells)
    assert ours == _read(book, True, monkeypatch, max_cells=max_cells)
    assert isinstance(ours, str) and "max_cells" in ours


@pytest.mark.parametrize("name", ["book", *CORPUS_FILES])
def test_audit_inputs_of_two_processes_are_those_of_one(name, book, monkeypatch):
    """The audit's inputs, read and grouped into runs by the process that read each
    sheet, are the same on two cores as on one."""
    path = book if name == "book" else CORPUS / name
    monkeypatch.setattr(apart, "MIN_SHARE", 0)

    def inputs(serial: bool):
        monkeypatch.setenv("WORKBOOK_GEN_SERIAL", "1" if serial else "0")
        got = read_inputs(path, group=True)
        return ([list(d.items()) for d in (got.formulas, got.cached, got.constants,
                                           got.broken)],
                got.grouped.runs, got.grouped.errors, got.grouped.parsed)

    assert inputs(False) == inputs(True)


@pytest.fixture(scope="module")
def sewing(tmp_path_factory) -> Path:
    """A workbook of ours: its report has the reference check."""
    from workbook_gen.scene import load_scene
    from workbook_gen.workbook import write_workbook
    scene = load_scene(Path(__file__).resolve().parent.parent / "templates"
                       / "sewing_machine.toml")
    return write_workbook(scene, tmp_path_factory.mktemp("sewing") / "sewing", force=True)


@pytest.mark.parametrize("name", ["book", "sewing", "xlcalculator__BASES.xlsx"])
def test_audit_report_of_two_processes_is_that_of_one(name, book, sewing, monkeypatch):
    """The whole report: the evaluation beside the local one, the comparison beside the
    reference check and the findings."""
    path = {"book": book, "sewing": sewing}.get(name) or CORPUS / name
    monkeypatch.setattr(apart, "MIN_SHARE", 0)

    def report(serial: bool):
        monkeypatch.setenv("WORKBOOK_GEN_SERIAL", "1" if serial else "0")
        out = audit(path).to_json()
        for key in ("seconds", "timings"):
            out.pop(key, None)
        return out

    forked = report(False)
    assert forked == report(True)
    assert name != "sewing" or forked["reference"], "the reference check did not run"
