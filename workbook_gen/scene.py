"""Scenes: the TOML file that says which mechanism, parameters, sweep and outputs.

``load_scene`` validates everything a user can get wrong and raises
SceneError with a one-line message naming the file, the key and the value.
"""

from __future__ import annotations

import math
import re
import tomllib
import unicodedata
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from .errors import SceneError
from .mechanisms import TEMPLATES, get_template
from .mechanisms.base import Mass, Template
from .names import check_name

MAX_ROWS = 1_048_576 - 1  # Excel's rows, less the header
_TOP_KEYS = {"name", "mechanism", "title", "parameters", "sweep", "outputs", "options", "masses"}
# letters and digits of any script (Nähmaschine_v2), '_', '-', '.'; NFC-normalised
_STEM = re.compile(r"^\w[\w.-]*$")
# A file stem that every file system takes: with "_tradeoff.xlsx" and the temporary
# file's prefix and suffix it stays far below the 255 bytes of a file name.
MAX_STEM = 100
# Windows refuses these as file names whatever the extension.
_RESERVED = re.compile(r"^(CON|PRN|AUX|NUL|COM[0-9]|LPT[0-9])(\..*)?$", re.IGNORECASE)
# A length that must be > 0 sets a scale the formulas divide by and multiply up to four of
# (a residual over omega^2 l_AB l_BC): it must neither underflow nor overflow (a subnormal
# 5e-324 has no relative precision at all).  Any parameter is at most 1e75 in magnitude;
# a tiny offset or angle is harmless (it only adds to larger terms).
MAGNITUDE = (1e-75, 1e75)
MIN_ROWS = 3  # rates and extremes need a neighbour on each side


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
    warnings: tuple[str, ...] = ()   # legal but probably unintended (a sweep short of its stop)
    cli: Mapping[str, Any] = field(default_factory=dict)  # the overrides, to re-apply (variants)

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
        if abs(number) > MAGNITUDE[1] or specs[key].positive and number < MAGNITUDE[0]:
            low = f"{MAGNITUDE[0]:g}.." if specs[key].positive else "at most "
            raise _fail(source, f"parameters.{key}", f"must be of magnitude {low}"
                        f"{MAGNITUDE[1]:g}", value)
        # as the Parameters sheet holds it (16 significant digits, XlsxWriter's %.16G):
        # the cached values are then what Excel recomputes from the file, also where a
        # limit amplifies the 17th digit (a rod 1e-12 longer than a toggle needs)
        values[key] = float(f"{number:.16G}")
    for name in values:
        check_name(name, f"{source}: parameters.{name}")
    return values


def _sweep(source: str, template: Template, given: dict,
           cli: Mapping[str, float | None]) -> tuple[Sweep, tuple[str, ...]]:
    """The sweep, and warnings about a legal but probably unintended one.

    ``cli`` holds the command line's --start/--stop/--step (None: not given); they win
    over the scene's keys and messages name them as given."""
    unknown = set(given) - {"start", "stop", "step"}
    if unknown:
        key = sorted(unknown)[0]
        raise _fail(source, f"sweep.{key}", "is not a sweep key (start, stop, step)",
                    given[key])
    spec = template.input
    values, where = {}, {}
    for key in ("start", "stop", "step"):
        if cli.get(key) is not None:
            where[key], raw = f"--{key}", cli[key]
        else:
            where[key], raw = f"sweep.{key}", given.get(key, getattr(spec, key))
        values[key] = _number(source, where[key], raw)
    start, stop, step = values["start"], values["stop"], values["step"]
    if step <= 0:
        raise _fail(source, where["step"], "must be > 0", step)
    if stop < start:
        raise _fail(source, where["stop"], f"must be >= {where['start']} = {start:g}", stop)
    if spec.positive and start <= 0:   # a length: C on B, or a negative cylinder
        raise _fail(source, where["start"], f"must be > 0 ({spec.name} is a length)", start)
    if (stop - start) / step + 1 > MAX_ROWS:
        raise _fail(source, where["step"], f"gives more rows than Excel allows ({MAX_ROWS:,} "
                    f"below the header) for {start:g}..{stop:g}", step)
    sweep = Sweep(start, stop, step)
    if sweep.rows < MIN_ROWS:
        key = where["step"] if stop > start else where["stop"]
        raise _fail(source, key, f"leaves {sweep.rows} row(s) for {start:g}..{stop:g} by "
                    f"{step:g}; at least {MIN_ROWS} are needed (rates and extremes)",
                    values[key.lstrip("-").removeprefix("sweep.")])
    warnings = ()
    last = start + (sweep.rows - 1) * step
    if abs(stop - last) > 1e-9 * max(abs(stop), abs(start), step):
        warnings = (f"{source}: {where['step']} = {step:g} does not reach {where['stop']} = "
                    f"{stop:g}: the last row is {sweep.values()[-1]:g}",)
    return sweep, warnings


def _quantity_names(source: str, given: dict) -> list[str] | None:
    unknown = set(given) - {"quantities"}
    if unknown:
        key = sorted(unknown)[0]
        raise _fail(source, f"outputs.{key}", "is not an outputs key (quantities)", given[key])
    if "quantities" not in given:
        return None
    names = given["quantities"]
    if not isinstance(names, list) or not names or not all(isinstance(n, str) for n in names):
        raise _fail(source, "outputs.quantities", "must be a non-empty list of names", names)
    if len(set(names)) != len(names):
        raise _fail(source, "outputs.quantities", "lists a quantity twice", names)
    return names


def _implied_options(source: str, base: Template, names: list[str] | None,
                     options: dict[str, object]) -> dict[str, object]:
    """``options`` with what the requested quantities imply: asking for an iterative
    quantity (``phi_2_iter``) asks for the method that makes it.  An option given
    explicitly with another value is an error saying so."""
    if not names:
        return options
    implied = dict(options)
    for name in names:
        if name in _known(base.with_options(implied)):
            continue
        for spec in base.options:
            for choice in spec.choices:
                trial = {**implied, spec.name: choice}
                if name not in _known(base.with_options(trial)):
                    continue
                if spec.name in options:
                    raise _fail(source, "outputs.quantities",
                                f"asks for {name}, which needs options.{spec.name} = "
                                f"{choice!r}, but the scene sets options.{spec.name}",
                                options[spec.name])
                implied = trial
                break
            else:
                continue
            break
    return implied


def _known(template: Template) -> set[str]:
    return {q.name for q in template.quantities}


def _outputs(source: str, template: Template, names: list[str] | None) -> tuple[str, ...]:
    if names is None:
        return template.outputs
    known = _known(template)
    for name in names:
        if name not in known:
            raise _fail(source, "outputs.quantities",
                        f"names an unknown quantity of {template.id} (known: "
                        f"{', '.join(template.outputs)})", name)
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
        for part in ("m", "u", "v"):  # u, v: no silent default for a centre of mass
            if part not in entry:
                raise SceneError(f"{source}: {key}.{part} is missing (an entry is "
                                 f"{{ m = kg, u = along the link, v = to its left }})")
        m = _number(source, f"{key}.m", entry["m"])
        if m < 0:
            raise _fail(source, f"{key}.m", "must be >= 0", entry["m"])
        masses[name] = Mass(m, _number(source, f"{key}.u", entry["u"]),
                            _number(source, f"{key}.v", entry["v"]))
    return masses


def _split_overrides(source: str, base: Template, overrides: Mapping[str, Any]
                     ) -> tuple[dict[str, Any], dict[str, Any]]:
    """Overrides by name: an option of the template (``branch``) or a parameter."""
    option_names = {o.name for o in base.options}
    options, parameters = {}, {}
    for key, value in overrides.items():
        (options if key in option_names else parameters)[key] = value
    return parameters, options


def _stem(source: str, key: str, value: object) -> str:
    """A checked file stem from a scene's ``name`` or ``--name``: NFC-normalised, without
    the ``.xlsx`` a user may add (``--name fb.xlsx`` writes fb.xlsx, not fb.xlsx.xlsx)."""
    name = unicodedata.normalize("NFC", _string(source, key, value))
    if name.lower().endswith(".xlsx") and len(name) > 5:
        name = name[:-5]
    _check_stem(source, key, name)
    return name


def _check_stem(source: str, key: str, name: str) -> None:
    if len(name) > MAX_STEM:
        raise _fail(source, key, f"is {len(name)} characters long; a file stem may have at "
                    f"most {MAX_STEM}", name if len(name) <= 40 else name[:37] + "...")
    if not _STEM.match(name) or name.endswith(".") or _RESERVED.match(name):
        raise _fail(source, key, "must be a file stem of letters (any script), digits, '_', "
                    "'-', '.' "
                    "(not starting with '.' or '-', not ending with '.', not a reserved "
                    "device name)", name)


def parse_scene(text: str, source: str, overrides: Mapping[str, Any] | None = None,
                step: float | None = None, *, start: float | None = None,
                stop: float | None = None, name: str | None = None) -> Scene:
    """A validated Scene from TOML text.

    ``overrides`` replace parameters or options (by name: ``{"l_BC": 105.0,
    "branch": "crossed"}``); ``start``/``stop``/``step`` the sweep's; ``name`` the
    file stem (a variant beside its baseline)."""
    text = text.removeprefix("\ufeff")  # a byte-order mark, as Windows editors save
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
    stem = _stem(source, "name", data["name"])
    if name is not None:
        stem = _stem(source, "--name", name)
    mechanism = _string(source, "mechanism", data["mechanism"])
    if mechanism not in TEMPLATES:
        raise _fail(source, "mechanism", f"is not a template (known: "
                    f"{', '.join(sorted(TEMPLATES))})", mechanism)
    base = get_template(mechanism)
    set_parameters, set_options = _split_overrides(source, base, overrides or {})
    given_options = {**_table(source, "options", data.get("options", {})), **set_options}
    options = _options(source, base, given_options)
    names = _quantity_names(source, _table(source, "outputs", data.get("outputs", {})))
    options = _implied_options(source, base, names, options)
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
    given.update(set_parameters)
    parameters = _parameters(source, template, given)
    problem = template.validate(parameters)
    if problem:
        key, message = problem
        raise _fail(source, f"parameters.{key}", message, parameters[key])
    sweep, warnings = _sweep(source, template, _table(source, "sweep", data.get("sweep", {})),
                             {"start": start, "stop": stop, "step": step})
    shown = [f"--set {k}={v}" for k, v in (overrides or {}).items()]
    shown += [f"--{k} {v:g}" for k, v in (("start", start), ("stop", stop)) if v is not None]
    shown += [f"--name {name}"] if name is not None else []
    return Scene(
        source=source, name=stem, template=template, title=title, parameters=parameters,
        sweep=sweep,
        outputs=_outputs(source, template, names),
        options=options,
        masses=masses,
        text=text,
        overrides=tuple(shown),
        warnings=warnings,
        cli={"overrides": dict(overrides or {}), "start": start, "stop": stop, "name": name},
    )


def load_scene(path: str | Path, overrides: Mapping[str, Any] | None = None,
               step: float | None = None, *, start: float | None = None,
               stop: float | None = None, name: str | None = None) -> Scene:
    """Read and validate a scene file (docs/scene.md).

    ``overrides`` replace parameters or options by name, ``start``/``stop``/``step``
    the sweep, ``name`` the output file stem; the command line's --set, --start,
    --stop, --step and --name are these.  ``scene.warnings`` lists what is legal but
    probably unintended (a step that does not reach the sweep's stop)."""
    return parse_scene(read_scene_text(path), str(path), overrides, step,
                       start=start, stop=stop, name=name)


def read_scene_text(path: str | Path) -> str:
    """The text of a scene file; a SceneError naming the file when it cannot be read."""
    try:
        return Path(path).read_text(encoding="utf-8")
    except OSError as exc:
        raise SceneError(f"{path}: cannot read: {exc.strerror}") from None
    except UnicodeDecodeError:
        raise SceneError(f"{path}: not UTF-8 text") from None
