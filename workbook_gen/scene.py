"""Scenes: the TOML file that says which mechanism, parameters, sweep and outputs.

``load_scene`` validates everything a user can get wrong and raises
SceneError with a one-line message naming the file, the key and the value.
"""

from __future__ import annotations

import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from .errors import SceneError
from .mechanisms import get_template
from .mechanisms.base import Mass, Template
from .names import check_name

MAX_ROWS = 1_048_576 - 1  # Excel's rows, less the header
_TOP_KEYS = {"name", "mechanism", "title", "parameters", "sweep", "outputs", "options", "masses"}
_STEM = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]*$")


@dataclass(frozen=True)
class Sweep:
    start: float
    stop: float
    step: float

    @property
    def rows(self) -> int:
        return int(math.floor((self.stop - self.start) / self.step + 1e-9)) + 1

    def values(self) -> list[float]:
        """The input values, free of accumulated rounding (0.3, not 0.30000000000000004)."""
        return [round(self.start + i * self.step, 10) for i in range(self.rows)]


@dataclass(frozen=True)
class Scene:
    source: str                 # the file it came from, for messages
    name: str
    template: Template
    title: str
    parameters: Mapping[str, float]
    sweep: Sweep
    outputs: tuple[str, ...]
    options: Mapping[str, object] = field(default_factory=dict)  # as given in the scene
    masses: Mapping[str, Mass] = field(default_factory=dict)
    text: str = ""              # the scene file as given
    overrides: tuple[str, ...] = ()  # the command-line overrides, as given

    @property
    def mechanism(self) -> str:
        return self.template.id


def _fail(source: str, key: str, problem: str, value: Any) -> SceneError:
    return SceneError(f"{source}: {key} {problem}, got {value!r}")


def _number(source: str, key: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise _fail(source, key, "must be a number", value)
    if not math.isfinite(value):
        raise _fail(source, key, "must be finite", value)
    return float(value)


def _table(source: str, key: str, value: Any) -> dict:
    if not isinstance(value, dict):
        raise _fail(source, key, "must be a table", value)
    return value


def _string(source: str, key: str, value: Any) -> str:
    if not isinstance(value, str):
        raise _fail(source, key, "must be a string", value)
    return value


def _parameters(source: str, template: Template, given: dict) -> dict[str, float]:
    specs = {p.name: p for p in template.parameters}
    values = template.defaults
    for key, value in given.items():
        if key not in specs:
            raise _fail(source, f"parameters.{key}",
                        f"is not a parameter of {template.id} (known: {', '.join(specs)})",
                        value)
        number = _number(source, f"parameters.{key}", value)
        if specs[key].positive and number <= 0:
            raise _fail(source, f"parameters.{key}", "must be > 0", value)
        values[key] = number
    for name in values:
        check_name(name, f"{source}: parameters.{name}")
    return values


def _sweep(source: str, template: Template, given: dict, step: float | None) -> Sweep:
    unknown = set(given) - {"start", "stop", "step"}
    if unknown:
        key = sorted(unknown)[0]
        raise _fail(source, f"sweep.{key}", "is not a sweep key (start, stop, step)",
                    given[key])
    spec = template.input
    start = _number(source, "sweep.start", given.get("start", spec.start))
    stop = _number(source, "sweep.stop", given.get("stop", spec.stop))
    where = "--step" if step is not None else "sweep.step"
    step = _number(source, where, step if step is not None else given.get("step", spec.step))
    if step <= 0:
        raise _fail(source, where, "must be > 0", step)
    if stop < start:
        raise _fail(source, "sweep.stop", f"must be >= sweep.start = {start:g}", stop)
    if (stop - start) / step + 1 > MAX_ROWS:
        raise _fail(source, where, f"gives more rows than Excel allows ({MAX_ROWS:,} below "
                    f"the header) for {start:g}..{stop:g}", step)
    return Sweep(start, stop, step)


def _outputs(source: str, template: Template, given: dict) -> tuple[str, ...]:
    unknown = set(given) - {"quantities"}
    if unknown:
        key = sorted(unknown)[0]
        raise _fail(source, f"outputs.{key}", "is not an outputs key (quantities)", given[key])
    if "quantities" not in given:
        return template.outputs
    names = given["quantities"]
    if not isinstance(names, list) or not names or not all(isinstance(n, str) for n in names):
        raise _fail(source, "outputs.quantities", "must be a non-empty list of names", names)
    known = [q.name for q in template.quantities]
    for name in names:
        if name not in known:
            raise _fail(source, "outputs.quantities",
                        f"names an unknown quantity of {template.id} (known: "
                        f"{', '.join(template.outputs)})", name)
    if len(set(names)) != len(names):
        raise _fail(source, "outputs.quantities", "lists a quantity twice", names)
    return tuple(names)


def _options(source: str, template: Template, given: dict) -> dict[str, object]:
    specs = {o.name: o for o in template.options}
    options = {}
    for key, value in given.items():
        if key not in specs:
            known = ", ".join(specs) or "none"
            raise _fail(source, f"options.{key}", f"is not an option of {template.id} "
                                                  f"(known: {known})", value)
        problem = specs[key].problem(value)
        if problem:
            raise _fail(source, f"options.{key}", problem, value)
        options[key] = value
    return options


def _masses(source: str, template: Template, given: dict) -> dict[str, Mass]:
    links = [link.name for link in template.links]
    masses = {}
    for name, entry in given.items():
        key = f"masses.{name}"
        if name not in links:
            known = ", ".join(links) or f"none: {template.id} declares no links"
            raise _fail(source, key, f"is not a moving link of {template.id} (known: {known})",
                        entry)
        entry = _table(source, key, entry)
        unknown = set(entry) - {"m", "u", "v"}
        if unknown:
            extra = sorted(unknown)[0]
            raise _fail(source, f"{key}.{extra}", "is not a mass key (m, u, v)", entry[extra])
        if "m" not in entry:
            raise SceneError(f"{source}: {key}.m is missing")
        m = _number(source, f"{key}.m", entry["m"])
        if m < 0:
            raise _fail(source, f"{key}.m", "must be >= 0", entry["m"])
        masses[name] = Mass(m, _number(source, f"{key}.u", entry.get("u", 0.0)),
                            _number(source, f"{key}.v", entry.get("v", 0.0)))
    return masses


def parse_scene(text: str, source: str, overrides: Mapping[str, Any] | None = None,
                step: float | None = None) -> Scene:
    """A validated Scene from TOML text; ``overrides`` replace parameters."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"{source}: not valid TOML: {exc}") from None
    unknown = set(data) - _TOP_KEYS
    if unknown:
        key = sorted(unknown)[0]
        raise _fail(source, key, f"is not a scene key ({', '.join(sorted(_TOP_KEYS))})",
                    data[key])
    for key in ("name", "mechanism"):
        if key not in data:
            raise SceneError(f"{source}: {key} is missing")
    name = _string(source, "name", data["name"])
    if not _STEM.match(name):
        raise _fail(source, "name", "must be a file stem of letters, digits, '_', '-', '.'",
                    name)
    base = get_template(_string(source, "mechanism", data["mechanism"]))
    options = _options(source, base, _table(source, "options", data.get("options", {})))
    template = base.with_options(options)
    masses = _masses(source, template, _table(source, "masses", data.get("masses", {})))
    if options.get("balance") and template.links and not masses:
        raise _fail(source, "options.balance", "needs a [masses] table (the counterweights "
                    "balance the links' masses)", True)
    if masses:
        from .mechanisms.dynamics import add_dynamics
        template = add_dynamics(template, masses, options)
    title = _string(source, "title", data.get("title", template.title))
    given = dict(_table(source, "parameters", data.get("parameters", {})))
    given.update(overrides or {})
    parameters = _parameters(source, template, given)
    problem = template.validate(parameters)
    if problem:
        key, message = problem
        raise _fail(source, f"parameters.{key}", message, parameters[key])
    return Scene(
        source=source, name=name, template=template, title=title, parameters=parameters,
        sweep=_sweep(source, template, _table(source, "sweep", data.get("sweep", {})), step),
        outputs=_outputs(source, template, _table(source, "outputs", data.get("outputs", {}))),
        options=options,
        masses=masses,
        text=text,
        overrides=tuple(f"{k}={v}" for k, v in (overrides or {}).items()),
    )


def load_scene(path: str | Path, overrides: Mapping[str, Any] | None = None,
               step: float | None = None) -> Scene:
    """Read and validate a scene file (see SPEC section 3)."""
    source = str(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except OSError as exc:
        raise SceneError(f"{source}: cannot read: {exc.strerror}") from None
    except UnicodeDecodeError:
        raise SceneError(f"{source}: not UTF-8 text") from None
    return parse_scene(text, source, overrides, step)
