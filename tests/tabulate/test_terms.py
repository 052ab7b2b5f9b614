"""The terms the Checks residuals share (tabulate/terms.py): the factored residuals are
the inline ones to the bit, the formulas are short, and no term is dead."""

from __future__ import annotations

import numpy as np
import openpyxl
import pytest

from workbook_gen import xlmath as xm
from workbook_gen.tabulate import evaluate
from workbook_gen.expr import Var, walk
from workbook_gen.expr.numeric import compile_numpy
from workbook_gen.scene import load_scene
from workbook_gen.workbook import write_workbook
from workbook_gen.tabulate.checks import guarded, plan, residuals
from workbook_gen.tabulate.terms import MIN_SAVING, common_terms

SCENES = ["sewing_machine", "slider_crank", "four_bar", "walking_beam", "sewing_machine_masses"]


@pytest.mark.parametrize("name", SCENES)
def test_factored_residuals_equal_the_inline_trees_to_the_bit(name):
    result = evaluate(load_scene(f"templates/{name}.toml", step=5.0))
    factored, _ = residuals(result)
    columns = dict(result.columns)
    columns["status"] = xm.XArray(result.status, np.zeros(result.rows, np.uint8))
    for check in result.model.checks:
        inline = compile_numpy(guarded(check.expr))(columns, result.params, result.rows)
        ours = factored[check.name]
        assert list(ours.err) == list(inline.err), check.name
        assert [repr(v) for v in ours.val] == [repr(v) for v in inline.val], check.name


def test_sewing_machine_residual_formulas_are_short(tmp_path):
    path = write_workbook(load_scene("templates/sewing_machine.toml"), tmp_path)
    sheet = openpyxl.load_workbook(path)["Checks"]
    headers = [c.value for c in sheet[7]]
    checks = headers[1:headers.index("cannot assemble")]
    lengths = [len(sheet.cell(8, col).value) for col in range(2, 2 + len(checks))]
    terms = [h for h in headers if str(h).startswith("term ")]
    assert len(terms) >= 5
    # inline, these averaged 381 characters and the longest was 1,666
    assert sum(lengths) / len(lengths) < 150 and max(lengths) < 300


@pytest.mark.parametrize("name", SCENES)
def test_every_term_is_shared_and_comes_after_the_terms_it_uses(name):
    model = evaluate(load_scene(f"templates/{name}.toml")).model
    terms, trees = plan(model)
    uses = {t.name: 0 for t in terms}
    seen = set()
    for term in terms:
        for node in walk(term.expr):
            if isinstance(node, Var) and node.name in uses:
                assert node.name in seen, f"{term.name} uses {node.name} before it"
                uses[node.name] += 1
        seen.add(term.name)
    for tree in trees:
        for node in walk(tree):
            if isinstance(node, Var) and node.name in uses:
                uses[node.name] += 1
    assert all(n >= 2 for n in uses.values()), uses


def test_nothing_to_share_gives_no_terms():
    tree = Var("x") * 2 + 1
    assert common_terms((tree,)) == ((), (tree,))
    assert MIN_SAVING > 0


def test_cells_of_a_guarded_column_are_those_of_the_guard_tree():
    """checks.guarded_cells: the cached values (and error codes) of IF(status="ok", r, "n/a")
    without object arrays, equal to xm.where's, errors and -0 included."""
    import numpy as np
    from workbook_gen import xlmath as xm
    from workbook_gen.tabulate.checks import SKIPPED, guarded_cells, max_abs
    from workbook_gen.tabulate.table import cached_values
    status = xm.XArray(np.array(["ok", "toggle", "ok", "ok", "cannot assemble", "ok"],
                                dtype=object), np.zeros(6, np.uint8))
    ok = xm.compare("=", status, xm.const("ok", 6))
    val = np.array([1e-12, np.nan, -0.0, np.nan, 3.0, -2e-9])
    from workbook_gen.xlerror import ExcelError
    num = ExcelError.NUM.code
    err = np.array([0, num, 0, num, 0, 0], np.uint8)   # #NUM! in a skipped row and an ok one
    for e in (err, np.zeros(6, np.uint8)):
        column = xm.XArray(np.where(e != 0, np.nan, np.nan_to_num(val)), e)
        guarded = xm.where(ok, column, xm.const(SKIPPED, 6))
        cells, codes = guarded_cells(column, ok)
        assert cells == cached_values(guarded) and np.array_equal(codes, guarded.err)
        assert [repr(v) for v in cells] == [repr(v) for v in cached_values(guarded)]
        assert max_abs(cells, codes) == ("#NUM!" if e.any() else 2e-9)  # 3.0 is skipped
