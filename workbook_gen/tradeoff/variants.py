"""Variants of a scene for the tradeoff: another step, method, options or outputs.

A variant is parsed from the scene's own TOML text with some keys replaced, so it
goes through the same validation as the file (``parse_scene``).  The text is
written back by a minimal TOML writer: scenes hold only strings, numbers,
booleans, lists of strings and (for ``[masses]``) inline tables of numbers.
"""

from __future__ import annotations

import math
import tomllib
from typing import Mapping

from ..scene import Scene, parse_scene


def _value(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"not a finite number: {value!r}")
        return repr(value)
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, list):
        return "[" + ", ".join(_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {_value(v)}" for k, v in value.items()) + " }"
    raise TypeError(f"cannot write {value!r} as TOML")


def dumps(data: Mapping[str, object]) -> str:
    """TOML text for a scene's data (top-level keys first, then one table per section)."""
    lines = [f"{k} = {_value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    for key, table in data.items():
        if isinstance(table, dict):
            lines.append(f"\n[{key}]")
            lines += [f"{k} = {_value(v)}" for k, v in table.items()]
    return "\n".join(lines) + "\n"


def variant(scene: Scene, *, step: float | None = None,
            options: Mapping[str, object] | None = None,
            parameters: Mapping[str, float] | None = None,
            outputs: tuple[str, ...] | None = None) -> Scene:
    """``scene`` with another sweep step, options, parameters or requested outputs."""
    data = tomllib.loads(scene.text)
    if options:
        data["options"] = {**data.get("options", {}), **options}
    if parameters:
        data["parameters"] = {**data.get("parameters", {}), **parameters}
    if outputs is not None:
        data["outputs"] = {"quantities": list(outputs)}
    if step is not None:
        data["sweep"] = {**data.get("sweep", {}), "step": float(step)}
    cli = dict(scene.cli)  # the command line's --set, --start, --stop, --name, re-applied
    overrides = dict(cli.pop("overrides", {}))
    for name in (options or {}):  # the variant's own options win over --set ones
        overrides.pop(name, None)
    return parse_scene(dumps(data), scene.source, overrides or None, **cli)
