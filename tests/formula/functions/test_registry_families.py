"""A function's family is where it is defined (issue 23 item 5): each family is a package of
workbook_gen/formula/functions/ named after Excel's category, the registry takes the family
from the package that registers the function, and nothing else registers."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from workbook_gen.formula import functions as fx
from workbook_gen.formula.functions.registry import FAMILIES, REGISTRY, family_of, register

FOLDER = Path(fx.__file__).parent
PREFIX = fx.__name__ + "."


def test_the_families_are_the_packages():
    packages = {p.parent.name for p in FOLDER.glob("*/__init__.py")} - {"numfmt"}
    assert packages == set(FAMILIES)


def test_every_family_registers_functions_and_every_function_has_its_package():
    assert {f.family for f in REGISTRY.values()} == set(FAMILIES)
    for name, f in REGISTRY.items():
        family, _, module = f.module.partition(".")
        assert family == f.family, name
        assert (FOLDER / family / f"{module}.py").is_file(), (name, f.module)


def test_a_function_is_defined_in_its_family_or_in_the_shared_machinery():
    """The callable itself (or the wrapper that made it: numeric, with_flag) comes from the
    family's package or from a module beside the packages (coerce, numeric, arrayargs...),
    never from another family."""
    for name, f in REGISTRY.items():
        where = f.fn.__module__
        assert where.startswith(PREFIX), (name, where)
        top = where[len(PREFIX):].split(".")[0]
        assert top == f.family or top not in FAMILIES, (name, f.family, where)


def test_only_the_family_packages_call_register():
    for path in FOLDER.rglob("*.py"):
        inner = path.relative_to(FOLDER).parts
        if len(inner) > 1 and inner[0] in FAMILIES and path.name != "__init__.py":
            continue
        calls = [n for n in ast.walk(ast.parse(path.read_text()))
                 if isinstance(n, ast.Call) and getattr(n.func, "id", None) == "register"]
        assert calls == [], path.relative_to(FOLDER)


def _register_from(module: str, name: str):
    namespace = {"__name__": module, "register": register}
    exec(f"register({name!r}, 1)(lambda ctx, x: x)", namespace)


def test_the_family_is_taken_from_the_registering_module():
    try:
        _register_from(PREFIX + "statistical.probe", "FAMILYPROBE")
        assert REGISTRY["FAMILYPROBE"].family == "statistical"
        assert REGISTRY["FAMILYPROBE"].module == "statistical.probe"
    finally:
        REGISTRY.pop("FAMILYPROBE", None)


@pytest.mark.parametrize("module", [PREFIX + "coerce", PREFIX + "statistical",
                                    PREFIX + "stats.core", "workbook_gen.evaluator.calls"])
def test_registering_from_outside_a_family_package_is_refused(module):
    with pytest.raises(ValueError, match="family package"):
        _register_from(module, "FAMILYPROBE")
    assert "FAMILYPROBE" not in REGISTRY
    with pytest.raises(ValueError):
        family_of(module)


def test_excel_categories_land_in_their_family():
    """A few functions of each family, by Microsoft's "Excel functions (by category)"."""
    expected = {
        "math": ["SUM", "SUMX2MY2", "ROMAN", "BASE", "COT", "ACOTH", "SEQUENCE", "SUBTOTAL",
                 "AGGREGATE", "MMULT", "RANDARRAY", "MULTINOMIAL", "SUMIF", "SUMIFS",
                 "SUMPRODUCT", "COMBIN"],
        "statistical": ["AVERAGE", "STDEV", "NORM.DIST", "FREQUENCY", "LINEST", "T.TEST",
                        "BINOM.DIST", "PERMUT", "PERMUTATIONA", "COUNTIFS", "MAXIFS"],
        "engineering": ["CONVERT", "DEC2BIN", "BITAND", "ERF", "DELTA", "BESSELJ", "IMSUM"],
        "financial": ["PMT", "PRICE", "ODDFPRICE", "VDB"],
        "date": ["DATE", "WEEKNUM", "WORKDAY.INTL"],
        "text": ["LEN", "LENB", "REGEXTEST", "TEXTSPLIT", "ARRAYTOTEXT", "T"],
        "logical": ["IF", "LAMBDA", "LET"],
        "lookup": ["VLOOKUP", "XLOOKUP", "OFFSET", "VSTACK", "FILTER", "RTD", "HYPERLINK"],
        "information": ["ISNUMBER", "SHEET", "SHEETS"],
        "database": ["DSUM", "DGET"],
        "cube": ["CUBEVALUE"],
    }
    wrong = {n: REGISTRY[n].family for fam, names in expected.items() for n in names
             if REGISTRY[n].family != fam}
    assert wrong == {}


def test_no_module_imports_a_private_name_from_another_package():
    """Helpers shared across families are public (arrayargs, criteria, numeric, round_digits);
    a family's private helpers stay inside its package."""
    found = []
    for path in FOLDER.rglob("*.py"):
        package = ".".join(path.relative_to(FOLDER.parent.parent.parent).with_suffix("").parts[:-1])
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module and not node.level:
                private = [a.name for a in node.names
                           if a.name.startswith("_") and not a.name.startswith("__")]
                if private and node.module.rpartition(".")[0] != package:
                    found.append((path.relative_to(FOLDER).as_posix(), node.module, private))
    assert found == []
