"""Evaluate a scene's Table columns with numpy: the Table's cached values and ``compute()``."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .. import xlmath as xm
from ..errors import CannotAssembleError
from ..expr.numeric import compiled, compiled_set
from ..pruning import Model, select
from ..scene import Scene
from ..xlerror import ExcelError

if TYPE_CHECKING:
    import pandas as pd

STATUS = "status"  # the Table's last column: each row's status text
STATUS_OK = "ok"
CANNOT_ASSEMBLE = "cannot assemble"
_STATUS = "\x00status"  # the status tree's result among the columns' (no quantity's name)


@dataclass(frozen=True)
class Table:
    """The Table sheet's values: every column, the status texts, the parameters."""

    scene: Scene
    model: Model
    inputs: np.ndarray
    columns: dict[str, xm.XArray]   # every Table column by name, input included
    status: np.ndarray              # object array of status texts
    params: dict[str, float]        # the parameters and the template's derived values

    @property
    def rows(self) -> int:
        return len(self.inputs)

    @property
    def assembled(self) -> np.ndarray:
        return self.status != CANNOT_ASSEMBLE


def evaluate_table(scene: Scene, kind: type[Table] = Table) -> Table:
    """Every column of the scene's Table (a ``kind``, ``Table`` or a subclass); refuses a
    sweep where nothing assembles."""
    model = select(scene.template, scene.outputs)
    params = derived_values(scene)
    inputs = np.array(scene.sweep.values())
    n = len(inputs)
    columns = {scene.template.input.name: xm.array(inputs)}
    named = tuple((q.name, q.expr) for q in model.columns) + ((_STATUS, model.status),)
    columns.update(compiled_set(named)(columns, params, n))
    texts = status_texts(columns.pop(_STATUS))
    if not np.any(texts != CANNOT_ASSEMBLE):
        raise CannotAssembleError(
            f"{scene.source}: the mechanism cannot be assembled anywhere in the sweep "
            f"{scene.sweep.start:g}..{scene.sweep.stop:g}: "
            f"{scene.template.assembly_failure(scene.parameters)}")
    return kind(scene, model, inputs, columns, texts, params)


def status_texts(status: xm.XArray) -> np.ndarray:
    """The status tree's values as the Table's texts: "cannot assemble" where an error."""
    return np.where(status.err != 0, CANNOT_ASSEMBLE, status.val).astype(object)


def derived_values(scene: Scene) -> dict[str, float]:
    """The scene's parameters with the template's derived values (NaN where an error)."""
    params = dict(scene.parameters)
    for item in scene.template.derived:
        value = compiled(item.expr)({}, params, 1)
        params[item.name] = float(value.val[0])
    return params


def headers(model: Model) -> list[str]:
    """The Table's header row: ``name [unit]``, the input first, the status last."""
    spec = model.template.input
    return [f"{spec.name} [{spec.unit}]"] + [q.header for q in model.columns] + [STATUS]


def cached_values(column: xm.XArray) -> list:
    """A column's cells as a workbook caches them: numbers, booleans, texts or Excel
    error texts."""
    values = column.val.tolist()
    if column.boolean:
        values = [bool(v) if v == v else v for v in values]
    if np.count_nonzero(column.err):   # (a C call: .any() is Python-level in numpy)
        for i in np.flatnonzero(column.err):
            values[i] = ExcelError.from_code(int(column.err[i])).value
    return values


def derived_cells(table: Table) -> dict[str, object]:
    """Each derived value of the template as the Parameters sheet caches it (an error
    text where the formula gives an error)."""
    return {item.name: cached_values(xm.array(np.array([table.params[item.name]])))[0]
            for item in table.scene.template.derived}


def compute(scene: Scene) -> pd.DataFrame:
    """The Table as a DataFrame (columns exactly the Table headers; errors as NaN)."""
    import pandas as pd  # only here: writing a workbook does not need it (~0.35 s to import)
    table = evaluate_table(scene)
    data = {}
    for header, name in zip(headers(table.model), table.model.names):
        data[header] = table.columns[name].val.astype(float)
    data[STATUS] = table.status
    return pd.DataFrame(data)
