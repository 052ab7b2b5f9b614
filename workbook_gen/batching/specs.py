"""One varied name and its values: a ``--vary`` spec, or an entry of the Python API's
``vary`` mapping, checked before anything is written.

A parameter takes numbers (``95:105:0.5``, ``30,32,34``, ``normal:32:0.05``,
``uniform:31.9:32.1``; in Python also a list, tuple, range or numpy array of numbers);
a template option takes its own values (``branch=open,crossed``, ``balance=true,false``,
``iterations=4,8``; in Python a list of them), each checked against the option's
declared choices.  A bad value raises SceneError with one line naming where it was
given (``--vary 'branch=open,sideways'`` on the command line, ``vary['branch']`` in
Python) and what is allowed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

from ..errors import SceneError
from ..mechanisms.base import OptionSpec

# One row per variant on the summary's Variants sheet: Excel's rows less the header.
MAX_VARIANTS = 1_048_575
SPEC_FORMS = "NAME=START:STOP:STEP, NAME=V1,V2,... or NAME=normal:MEAN:SD | uniform:LO:HI"


@dataclass(frozen=True)
class Spec:
    name: str
    kind: str                       # "grid" | "list" | "normal" | "uniform"
    numbers: tuple[object, ...]     # grid/list: the values; random: the two numbers
    text: str                       # where it was given, for messages


def number(where: str, text: object, what: str = "value") -> float:
    """A finite float from a number or its text."""
    if isinstance(text, bool) or not isinstance(text, (int, float, str)):
        raise SceneError(f"{where}: {what} {text!r} is not a number")
    try:
        value = float(text)
    except (ValueError, OverflowError):
        shown = text.strip() if isinstance(text, str) else text
        raise SceneError(f"{where}: {what} {shown!r} is not a number") from None
    if not math.isfinite(value):
        shown = text.strip() if isinstance(text, str) else text
        raise SceneError(f"{where}: {what} must be finite, got {shown!r}")
    return value


def allowed(option: OptionSpec) -> str:
    """The values an option takes, for messages."""
    if option.choices:
        return ", ".join(option.choices)
    if isinstance(option.default, bool):
        return "true, false"
    low = "" if option.minimum is None else f"{option.minimum}"
    high = "" if option.maximum is None else f"{option.maximum}"
    return f"an integer {low}..{high}" if low or high else "an integer"


def option_value(where: str, option: OptionSpec, value: object) -> str | bool | int:
    """``value`` (a text from the command line or a CSV cell, or a Python/xlsx value) as
    the option's own type, or SceneError naming the values it takes."""
    given = value.strip() if isinstance(value, str) else value
    result: object = given
    if isinstance(option.default, bool) and isinstance(given, str):
        result = {"true": True, "false": False}.get(given.lower(), given)
    elif not option.choices and not isinstance(option.default, bool):
        if isinstance(given, str):
            try:
                result = int(given)
            except ValueError:
                result = given
        elif isinstance(given, float) and given.is_integer():
            result = int(given)
    if hasattr(result, "item") and not isinstance(result, (str, bool, int, float)):
        result = result.item()  # a numpy scalar
    if option.problem(result) is not None:
        raise SceneError(f"{where}: {option.name} must be {'one of ' if option.choices else ''}"
                         f"{allowed(option)}, got {given!r}")
    return result


def _grid(where: str, start: float, stop: float, step: float) -> tuple[float, ...]:
    span = (stop - start) / step
    count = int(math.floor(span + 1e-9)) + 1
    if count > MAX_VARIANTS:
        raise SceneError(f"{where}: {count:,} values, more than {MAX_VARIANTS:,}")
    # Free of accumulated rounding (95.5, not 95.50000000000001): as many decimals as
    # the step needs, and ten more.
    decimals = 10 - int(math.floor(math.log10(abs(step))))
    values = [round(start + i * step, decimals) for i in range(count)]
    if abs(values[-1] - stop) <= 1e-9 * max(abs(stop), abs(step)):
        values[-1] = stop
    return tuple(values)


def _distinct(where: str, name: str, kind: str, values: tuple, text: str) -> Spec:
    if not values:
        raise SceneError(f"{where}: no values")
    # 1 and True are equal keys: a value is the same only with the same type too
    if len({(type(v), v) for v in values}) != len(values):
        raise SceneError(f"{where}: a value is listed twice")
    return Spec(name, kind, values, text)


def _body(where: str, name: str, body: str, option: OptionSpec | None) -> Spec:
    """The part after ``NAME=``."""
    head, _, rest = body.partition(":")
    if head.strip().lower() in ("normal", "uniform"):
        kind = head.strip().lower()
        if option is not None:
            raise SceneError(f"{where}: {name} is an option; it takes a list of its values "
                             f"({allowed(option)}), not a distribution")
        parts = rest.split(":")
        labels = ("MEAN", "SD") if kind == "normal" else ("LO", "HI")
        if len(parts) != 2:
            raise SceneError(f"{where}: expected {name}={kind}:{labels[0]}:{labels[1]}")
        a, b = (number(where, p, label) for p, label in zip(parts, labels))
        if kind == "normal" and b <= 0:
            raise SceneError(f"{where}: SD must be > 0, got {parts[1].strip()}")
        if kind == "uniform" and not a < b:
            raise SceneError(f"{where}: LO must be < HI, got {parts[0].strip()} and "
                             f"{parts[1].strip()}")
        return Spec(name, kind, (a, b), where)
    if ":" in body:
        if option is not None and (option.choices or isinstance(option.default, bool)):
            raise SceneError(f"{where}: {name} is an option; give its values as a list "
                             f"({name}={','.join(allowed(option).split(', '))})")
        parts = body.split(":")
        if len(parts) != 3:
            raise SceneError(f"{where}: a grid is {name}=START:STOP:STEP")
        start, stop, step = (number(where, p, w) for p, w in zip(parts, ("START", "STOP", "STEP")))
        if step == 0:
            raise SceneError(f"{where}: STEP must not be 0")
        if (stop - start) * step < 0:
            raise SceneError(f"{where}: STEP {parts[2].strip()} never reaches STOP "
                             f"{parts[1].strip()} from START {parts[0].strip()}")
        values = _grid(where, start, stop, step)
        if option is not None:
            values = tuple(option_value(where, option, v) for v in values)
        return _distinct(where, name, "grid", values, where)
    if option is not None:
        values = tuple(option_value(where, option, p) for p in body.split(","))
    else:
        values = tuple(number(where, p) for p in body.split(","))
    return _distinct(where, name, "list", values, where)


def parse_vary(text: str, options: Mapping[str, OptionSpec] | None = None,
               cli: bool = True) -> Spec:
    """A command-line ``--vary NAME=SPEC`` (in Python: an item of a ``vary`` list)."""
    where = f"--vary {text!r}" if cli else f"vary item {text!r}"
    name, sep, body = text.partition("=")
    name, body = name.strip(), body.strip()
    if not sep or not name or not body:
        raise SceneError(f"{where}: expected {SPEC_FORMS}")
    return _body(where, name, body, (options or {}).get(name))


def vary_entry(name: object, value: object, options: Mapping[str, OptionSpec] | None = None
               ) -> Spec:
    """An entry of the Python API's ``vary`` mapping: ``"l_BC": "95:105:1"`` (the
    command line's SPEC), ``"l_AB": [30, 32]`` (a list, tuple, range or numpy array of
    numbers, or of an option's values), or a single value."""
    if not isinstance(name, str) or not name.strip():
        raise SceneError(f"vary: a key must be a parameter or option name, got {name!r}")
    where = f"vary[{name!r}]"
    option = (options or {}).get(name)
    if isinstance(value, str):
        if not value.strip():
            raise SceneError(f"{where}: empty; give START:STOP:STEP, V1,V2,..., "
                             f"normal:MEAN:SD or uniform:LO:HI, or a list of values")
        return _body(where, name, value.strip(), option)
    if isinstance(value, (bytes, Mapping)) or value is None:
        raise SceneError(f"{where}: expected a list of values or a text such as "
                         f"'95:105:1', got {type(value).__name__}")
    if hasattr(value, "tolist"):  # a numpy array or scalar
        value = value.tolist()
    items = list(value) if isinstance(value, (list, tuple, range)) else [value]
    items = [v.item() if hasattr(v, "item") and not isinstance(v, (str, bytes)) else v
             for v in items]  # numpy scalars in a list
    if option is not None:
        values = tuple(option_value(where, option, v) for v in items)
    else:
        values = tuple(number(where, v) for v in items)
    return _distinct(where, name, "list", values, where)


def specs_of(vary: object, options: Mapping[str, OptionSpec] | None = None,
             cli: bool = True) -> list[Spec]:
    """The specs of ``vary`` as ``batch()`` takes it: a mapping (Python), or a sequence
    of the command line's ``NAME=SPEC`` texts."""
    if vary is None:
        return []
    if isinstance(vary, Mapping):
        return [vary_entry(k, v, options) for k, v in vary.items()]
    if isinstance(vary, str):
        raise SceneError(f"vary: a mapping {{name: values}} or a list of 'NAME=SPEC' texts, "
                         f"got the text {vary!r}")
    specs = []
    for item in vary:
        if not isinstance(item, str):
            raise SceneError(f"vary: a list item must be a text 'NAME=SPEC', got {item!r} "
                             f"(or give a mapping {{name: values}})")
        specs.append(parse_vary(item, options, cli))
    return specs


def shown(value: object) -> object:
    """A varied value as the summary shows it: an option's true/false as TOML spells
    them, anything else as it is."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return value
