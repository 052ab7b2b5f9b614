"""Evaluate a scene's columns with numpy: the cached values and ``compute()``."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from . import xlmath as xm
from .errors import CannotAssembleError
from .expr.numeric import compiled, compiled_set
from .pruning import Model, select
from .scene import Scene

if TYPE_CHECKING:
    import pandas as pd

STATUS_OK = "ok"
_STATUS = "\x00status"  # the status tree's result among the columns' (no quantity's name)


@dataclass(frozen=True)
class Evaluated:
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
        return self.status != "cannot assemble"


def evaluate(scene: Scene) -> Evaluated:
    """Every column of the scene's Table; refuses a sweep where nothing assembles."""
    model = select(scene.template, scene.outputs)
    params = derived_values(scene)
    inputs = np.array(scene.sweep.values())
    n = len(inputs)
    columns = {scene.template.input.name: xm.array(inputs)}
    named = tuple((q.name, q.expr) for q in model.columns) + ((_STATUS, model.status),)
    columns.update(compiled_set(named)(columns, params, n))
    status = columns.pop(_STATUS)
    texts = np.where(status.err != 0, "cannot assemble", status.val).astype(object)
    if not np.any(texts != "cannot assemble"):
        raise CannotAssembleError(
            f"{scene.source}: the mechanism cannot be assembled anywhere in the sweep "
            f"{scene.sweep.start:g}..{scene.sweep.stop:g}: "
            f"{scene.template.assembly_failure(scene.parameters)}")
    return Evaluated(scene, model, inputs, columns, texts, params)


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
    return [f"{spec.name} [{spec.unit}]"] + [q.header for q in model.columns] + ["status"]


def compute(scene: Scene) -> pd.DataFrame:
    """The Table as a DataFrame (columns exactly the Table headers; errors as NaN)."""
    import pandas as pd  # only here: writing a workbook does not need it (~0.35 s to import)
    result = evaluate(scene)
    data = {}
    for header, name in zip(headers(result.model), result.model.names):
        data[header] = result.columns[name].val.astype(float)
    data["status"] = result.status
    return pd.DataFrame(data)
