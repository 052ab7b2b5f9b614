"""The private names of XlsxWriter and zipfile the writer relies on (issue 23 item 4), all
in workbook_gen/workbook/xlsxwriter_internals.py and listed there (``PRIVATE``): a new
release that drops one, or changes its parameters, fails here naming it, before any
workbook comes out wrong.  No other module of workbook_gen uses one, and importing the
package leaves XlsxWriter's module as it is.  The tested range is pinned in
pyproject.toml."""

from __future__ import annotations

import ast
import importlib
import inspect
import io
import pkgutil
import re
import zipfile
from pathlib import Path

import pytest
import xlsxwriter
import xlsxwriter.chart
import xlsxwriter.drawing
import xlsxwriter.workbook

import workbook_gen
from workbook_gen.workbook import xlsxwriter_internals as internals
from workbook_gen.workbook.xlsxwriter_internals import PRIVATE, ZippedWorkbook

ROOT = Path(workbook_gen.__file__).parent
INTERNALS = Path(internals.__file__)


def _workbook():
    return xlsxwriter.Workbook(io.BytesIO(), {"constant_memory": True})


#: An instance of each class whose instance attributes PRIVATE names (``Owner().name``).
INSTANCES = {
    "xlsxwriter.workbook:Workbook": _workbook,
    "xlsxwriter.worksheet:Worksheet": lambda: _workbook().add_worksheet(),
    "xlsxwriter.chart:Chart": lambda: _workbook().add_chart({"type": "scatter"}),
    "xlsxwriter.drawing:Drawing": xlsxwriter.drawing.Drawing,
    "zipfile:ZipFile": lambda: zipfile.ZipFile(io.BytesIO(), "w"),
    "zipfile:ZipInfo": lambda: zipfile.ZipInfo("x"),
}


def _resolve(path: str):
    """The object ``module:Owner.name`` (``Owner().name``) names; AttributeError naming
    the missing part."""
    module, _, dotted = path.partition(":")
    obj = importlib.import_module(module)
    owner = module
    for part in dotted.split("."):
        if part.endswith("()"):
            owner = f"{owner}:{part[:-2]}" if owner == module else f"{owner}.{part[:-2]}"
            obj = INSTANCES[owner]()
            continue
        if not hasattr(obj, part):
            raise AttributeError(f"{path}: {part} is gone")
        obj = getattr(obj, part)
        owner = f"{owner}:{part}" if owner == module else f"{owner}.{part}"
    return obj


@pytest.mark.parametrize("private", PRIVATE, ids=[p.path for p in PRIVATE])
def test_private_name_is_there_with_its_parameters(private):
    try:
        obj = _resolve(private.path)
    except AttributeError as gone:
        pytest.fail(f"{gone} (relied on by workbook/xlsxwriter_internals.py: see its docstring)")
    if private.params is not None:
        have = tuple(inspect.signature(obj).parameters)
        assert have == private.params, (
            f"{private.path} now takes {have}, not {private.params}: see "
            f"workbook/xlsxwriter_internals.py")


def test_every_private_name_is_in_the_docstring():
    doc = internals.__doc__
    for private in PRIVATE:
        name = re.split(r"[.:]", private.path)[-1]
        assert re.search(rf"\b{re.escape(name)}\b", doc), f"{name} is not in the docstring"


def test_store_workbook_makes_its_zip_with_the_module_name_zipfile():
    """ZippedWorkbook runs ``_store_workbook``'s code with its global ZipFile rebound:
    that needs the zip made by that global name and no closure."""
    code = xlsxwriter.workbook.Workbook._store_workbook.__code__
    assert "ZipFile" in code.co_names and not code.co_freevars


def test_zipped_workbook_is_xlsxwriters_bytes_and_patches_nothing():
    """A ZippedWorkbook at zlib's default level writes what XlsxWriter writes, in both
    packaging paths; importing workbook_gen leaves xlsxwriter.workbook.ZipFile alone."""
    import workbook_gen.batching.summary  # noqa: F401 (both zipping writers imported)
    import workbook_gen.workbook  # noqa: F401

    assert xlsxwriter.workbook.ZipFile is zipfile.ZipFile
    for options in ({"in_memory": True}, {"constant_memory": True}):
        outputs = []
        for kind in (xlsxwriter.Workbook, ZippedWorkbook):
            stream = io.BytesIO()
            book = kind(stream, options)
            book.add_worksheet().write_column(0, 0, [f"row {i} " * 9 for i in range(200)])
            book.close()
            outputs.append(stream.getvalue())
        assert outputs[0] == outputs[1], options
    assert xlsxwriter.workbook.ZipFile is zipfile.ZipFile


def _library_private_names() -> set[str]:
    """Every underscore name (not dunder) of XlsxWriter's and zipfile's modules, classes
    and instances, and the non-underscore module names PRIVATE lists."""
    modules = [importlib.import_module(m.name) for m in
               pkgutil.walk_packages(xlsxwriter.__path__, "xlsxwriter.")] + [zipfile]
    names = set()
    for module in modules:
        for name, value in vars(module).items():
            names.add(name) if name.startswith("_") else None
            if inspect.isclass(value) and value.__module__ == module.__name__:
                names.update(vars(value))
    for make in INSTANCES.values():
        names.update(getattr(make(), "__dict__", {}))
    names = {n for n in names if n.startswith("_") and not n.endswith("__")}
    names.update(name for name in (p.path.partition(":")[2] for p in PRIVATE)
                 if "." not in name and name not in zipfile.__all__)   # not zipfile.ZipFile
    return names - {"_replace", "_asdict", "_fields", "_make", "_field_defaults"}  # namedtuples'


def _defined_here(tree: ast.AST) -> set[str]:
    """Names a module gives its own things: functions, classes, attributes it sets."""
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Store):
            names.add(node.attr)
        elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            names.add(node.id)
    return names


def test_no_other_module_uses_a_private_name():
    """Outside xlsxwriter_internals.py: no import from XlsxWriter's submodules (only
    ``import xlsxwriter`` for its documented Workbook), no zipfile name PRIVATE lists, no
    underscore name of either library read or called (unless the module defines a
    thing of that name itself)."""
    private = _library_private_names()
    found = []
    for path in sorted(ROOT.rglob("*.py")):
        if path == INTERNALS:
            continue
        tree = ast.parse(path.read_text())
        ours = _defined_here(tree)
        where = path.relative_to(ROOT.parent)
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.module and not node.level:
                if node.module.startswith("xlsxwriter"):
                    found.append(f"{where}:{node.lineno}: from {node.module} import")
                elif node.module == "zipfile":
                    found += [f"{where}:{node.lineno}: zipfile.{a.name}" for a in node.names
                              if a.name in private]
            elif isinstance(node, ast.Import):
                found += [f"{where}:{node.lineno}: import {a.name}" for a in node.names
                          if a.name.startswith("xlsxwriter.")]
            elif (isinstance(node, ast.Attribute) and node.attr in private
                  and node.attr not in ours):
                found.append(f"{where}:{node.lineno}: {ast.unparse(node)}")
    assert not found, "private names outside xlsxwriter_internals.py:\n" + "\n".join(found)


def test_no_subclass_overrides_a_private_method_outside_the_module():
    """Classes of workbook_gen derived from an XlsxWriter or zipfile class override
    underscore methods only in xlsxwriter_internals.py (the others override the public
    hooks it gives)."""
    bases = tuple({xlsxwriter.workbook.Workbook, xlsxwriter.worksheet.Worksheet,
                   xlsxwriter.chart.Chart, xlsxwriter.drawing.Drawing, zipfile.ZipFile,
                   zipfile.ZipInfo})
    private = _library_private_names()
    found = []
    for info in pkgutil.walk_packages(workbook_gen.__path__, "workbook_gen."):
        module = importlib.import_module(info.name)
        if module is internals:
            continue
        for name, cls in vars(module).items():
            if (inspect.isclass(cls) and cls.__module__ == module.__name__
                    and issubclass(cls, bases)):
                found += [f"{info.name}.{name}.{attr}" for attr in vars(cls) if attr in private]
    assert not found, found


def test_instance_attributes_the_charts_reset():
    """charts.py re-uses a chart object: it resets these attributes per workbook."""
    book = xlsxwriter.Workbook(None, {"in_memory": True})
    chart = book.add_chart({"type": "scatter"})
    chart.add_series({"categories": "=Table!$A$2:$A$3", "values": "=Table!$B$2:$B$3",
                      "categories_data": [0.0, 1.0], "values_data": [1.0, 2.0]})
    assert chart.formula_data == [[0.0, 1.0], [1.0, 2.0]]   # the series' cached points


def test_add_series_still_reads_the_cache_options():
    source = inspect.getsource(xlsxwriter.chart.Chart.add_series)
    for key in internals.SERIES_CACHE_OPTIONS:
        assert f'"{key}"' in source, f"add_series no longer reads {key}"


def test_the_pinned_range_is_the_installed_version():
    pinned = re.search(r'"XlsxWriter>=([\d.]+),<([\d.]+)"',
                       (Path(__file__).resolve().parents[2] / "pyproject.toml").read_text())
    assert pinned, "XlsxWriter is not pinned to a tested range in pyproject.toml"
    have = tuple(int(x) for x in xlsxwriter.__version__.split(".")[:2])
    low = tuple(int(x) for x in pinned.group(1).split(".")[:2])
    high = tuple(int(x) for x in pinned.group(2).split(".")[:2])
    assert low <= have < high, (xlsxwriter.__version__, pinned.group(0))
