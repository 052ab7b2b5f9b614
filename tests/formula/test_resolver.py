"""One Resolver protocol (formula/resolver.py, issue 23): every method the formula
evaluators ask of a workbook is declared there with its default, every resolver is one,
and no caller probes a resolver with getattr or hasattr."""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import pytest

from workbook_gen.formula import DictResolver, parse
from workbook_gen.formula import functions as fx
from workbook_gen.formula.resolver import NO_WORKBOOK, Resolver
from workbook_gen.formula.scalar import evaluate
from workbook_gen.formula.values import Ref
from workbook_gen.xlerror import ExcelError

ROOT = Path(__file__).resolve().parents[2] / "workbook_gen"
DECLARED = {n for n in dir(Resolver) if not n.startswith("_")}


def _trees():
    for path in sorted(ROOT.rglob("*.py")):
        yield path, ast.parse(path.read_text())


def test_callers_ask_only_what_the_protocol_declares():
    """``….resolver.m`` and ``ctx.workbook.m`` in the formula package name a declared
    method; nothing anywhere asks getattr/hasattr of a resolver or a context's workbook."""
    asked, probes = set(), []
    for path, tree in _trees():
        where = path.relative_to(ROOT.parent)
        for node in ast.walk(tree):
            if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Attribute)
                    and node.value.attr in ("resolver", "workbook")
                    and path.is_relative_to(ROOT / "formula")):
                asked.add((str(where), node.attr))
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
                    and node.func.id in ("getattr", "hasattr") and node.args
                    and any(w in ast.unparse(node.args[0]) for w in ("resolver", ".workbook"))):
                probes.append(f"{where}:{node.lineno}")
    assert probes == []
    assert {name for _, name in asked} - DECLARED == set()
    assert len(asked) >= 12  # (the finder sees the callers: SHEET, RTD, ISFORMULA, ...)


def _resolver_classes():
    """Every class of the package that defines ``cell``, ``range`` and ``name``."""
    for path, tree in _trees():
        module = ".".join(path.relative_to(ROOT.parent).with_suffix("").parts)
        for node in ast.walk(tree):
            if isinstance(node, ast.ClassDef):
                methods = {f.name for f in node.body if isinstance(f, ast.FunctionDef)}
                if {"cell", "range", "name"} <= methods:
                    yield module, node.name


def test_every_resolver_is_a_resolver():
    found = sorted(_resolver_classes())
    assert len(found) >= 3  # store.SheetResolver, scalar.DictResolver, the auditor's
    for module, name in found:
        cls = getattr(importlib.import_module(module), name)
        assert issubclass(cls, Resolver), f"{module}.{name}"


def test_no_attribute_is_set_on_a_resolver_from_outside():
    """``resolver.has_formula = lambda ...`` once stood in for a method."""
    bolted = []
    for path, tree in _trees():
        for node in ast.walk(tree):
            if isinstance(node, ast.Assign):
                for target in node.targets:
                    if (isinstance(target, ast.Attribute) and isinstance(target.value, ast.Name)
                            and target.value.id != "self"
                            and isinstance(node.value, ast.Lambda)):
                        bolted.append(f"{path.relative_to(ROOT.parent)}:{node.lineno}")
    assert bolted == []


@pytest.mark.parametrize("formula, expected", [
    ("SHEET()", ExcelError.NA),              # the sheets are not known
    ("SHEETS()", ExcelError.NA),
    ("ISFORMULA(A1)", False),                # a table of values holds no formula
    ("FORMULATEXT(A1)", ExcelError.NA),
    ("SUBTOTAL(109,A1:A3)", 6.0),            # no row hidden
    ("CODE(CHAR(200))", 200.0),              # Windows' character set
    ("SUM(Sheet1:Sheet2!A1)", ExcelError.REF),  # no sheet order: #REF!
    ('INDIRECT("Sheet9!A1")+1', 2.0),        # an unknown sheet is no #REF! then
])
def test_the_defaults_are_what_a_table_of_values_answers(formula, expected):
    """What Excel answers where the workbook holds only these values (A1:A3 = 1, 2, 3;
    Sheet9!A1 = 1): no formulas, no hidden rows, no sheet list known."""
    book = DictResolver({"A1": 1.0, "A2": 2.0, "A3": 3.0, "Sheet9!A1": 1.0})
    assert evaluate(parse(formula), book) == expected


class _Answering(DictResolver):
    """A workbook that overrides the defaults: its methods are asked, not probed for."""

    def has_formula(self, sheet, row, col):
        return (row, col) == (1, 1)

    def formula_text(self, sheet, row, col):
        return ("1+0", False) if (row, col) == (1, 1) else None

    def sheet_number(self, sheet):
        return {"sheet1": 1, "sheet2": 2}.get((sheet or self.sheet).casefold())

    def sheet_count(self):
        return 2

    def hidden_rows(self, sheet):
        return frozenset({2})

    def sheets_between(self, first, last):
        return ["Sheet1", "Sheet2"]


@pytest.mark.parametrize("formula, expected", [
    ("SHEET()", 1.0), ("SHEET(\"sheet2\")", 2.0), ("SHEETS()", 2.0),
    ("ISFORMULA(A1)", True), ("ISFORMULA(A2)", False), ("FORMULATEXT(A1)", "=1+0"),
    ("SUBTOTAL(109,A1:A3)", 4.0),            # row 2 hidden
    ("SUM(Sheet1:Sheet2!A1)", 2.0),          # Sheet1!A1 + Sheet2!A1
    ('INDIRECT("Sheet9!A1")+1', ExcelError.REF),  # no such sheet among the two
])
def test_a_resolver_answering_is_heard(formula, expected):
    book = _Answering({"A1": 1.0, "A2": 2.0, "A3": 3.0, "Sheet2!A1": 1.0, "Sheet9!A1": 1.0})
    assert evaluate(parse(formula), book) == expected


def test_a_call_without_a_workbook_sees_the_defaults():
    assert fx.Context().workbook is NO_WORKBOOK
    assert fx.Context(resolver=DictResolver()).workbook is not NO_WORKBOOK
    assert fx.Context().read(Ref(None, 1, 1, 1, 1)) == ExcelError.REF  # no cells to read
