"""What a mechanism template is: parameters, quantities as trees, checks, charts.

A template is data.  It knows nothing of xlsx: the workbook writer reads the
trees and prints them; ``pruning.py`` prunes them to what a scene asks for.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Mapping

from ..expr import Node, Param, Var, eq, if_
from ..expr.tree import children


@dataclass(frozen=True)
class ParamSpec:
    name: str
    default: float
    unit: str
    description: str
    positive: bool = False  # lengths: must be > 0


@dataclass(frozen=True)
class InputSpec:
    name: str
    unit: str
    description: str
    start: float = 0.0
    stop: float = 360.0
    step: float = 10.0
    positive: bool = False   # a length: the sweep must start above 0


@dataclass(frozen=True)
class Quantity:
    """One Table column: ``expr`` refers to parameters and to other quantities."""

    name: str
    unit: str
    expr: Node
    description: str
    output: bool = True  # False: an intermediate column, present only when needed

    @property
    def header(self) -> str:
        return f"{self.name} [{self.unit}]" if self.unit else self.name


@dataclass(frozen=True)
class Check:
    """A dimensionless closure residual over Table columns (0 when they agree)."""

    name: str
    level: str  # "position" | "velocity" | "acceleration"
    expr: Node
    description: str


@dataclass(frozen=True)
class Chart:
    title: str
    x: str
    ys: tuple[str, ...]
    y_title: str
    path: bool = False  # True: y against x of a point, equal axis scales


def slide_charts(what: str, x: str, names: tuple[str, str, str], unit: str = "mm"
                 ) -> tuple[Chart, ...]:
    """A sliding part's displacement, velocity and acceleration against ``x``; ``names``:
    its three quantities (s, v, a), in ``unit``, ``unit``/s and ``unit``/s^2."""
    s, v, a = names
    return (Chart(f"{what} displacement", x, (s,), f"{s} [{unit}]"),
            Chart(f"{what} velocity", x, (v,), f"{v} [{unit}/s]"),
            Chart(f"{what} acceleration", x, (a,), f"{a} [{unit}/s^2]"))


def turn_charts(what: str, x: str, names: tuple[str, str, str]) -> tuple[Chart, ...]:
    """A turning link's angle (deg), angular velocity and angular acceleration against
    ``x``; ``names``: its three quantities (theta, omega, alpha)."""
    theta, omega, alpha = names
    return (Chart(f"{what} angle", x, (theta,), f"{theta} [deg]"),
            Chart(f"{what} angular velocity", x, (omega,), f"{omega} [rad/s]"),
            Chart(f"{what} angular acceleration", x, (alpha,), f"{alpha} [rad/s^2]"))


@dataclass(frozen=True)
class Span:
    """A Summary row: max - min of a quantity over the sweep (stroke, swing)."""

    label: str
    quantity: str


@dataclass(frozen=True)
class Figure:
    """A Summary row computed from parameters alone (time ratio, exact stroke)."""

    label: str
    unit: str
    expr: Node
    description: str
    needs: tuple[str, ...] = ()  # if given: shown only when one of these columns is


NOT_APPLICABLE = "n/a"


def only_if(expr: Node, condition: Node, needs: str) -> Node:
    """A figure that holds only under ``condition``: its value where the condition holds,
    else the text ``n/a: needs <needs>`` (docs/workbook.md, Summary; never a number that does not
    apply)."""
    return if_(condition, expr, f"{NOT_APPLICABLE}: needs {needs}")


@dataclass(frozen=True)
class Condition:
    """A design condition over the parameters alone (a balancing condition): ``expr`` is
    its residual in ``unit``, 0 when it holds; ``scale`` (>= 0, same unit) the sum of the
    magnitudes of its terms.  It holds when |expr| <= check_tol * scale.  Unlike a Check
    it says nothing of the workbook's correctness: shown on the Checks sheet below the
    rows, kept only when one of the Table columns ``needs`` is (if given)."""

    name: str
    unit: str
    expr: Node
    scale: Node
    description: str
    needs: tuple[str, ...] = ()


@dataclass(frozen=True)
class Derived:
    """A value computed from the parameters, shown on the Parameters sheet as a live
    formula with a defined name (a counterweight's mass); trees may use it as Param."""

    name: str
    unit: str
    expr: Node
    description: str


@dataclass(frozen=True)
class OptionSpec:
    """A template option: ``choices`` for text options, else a bool or an int option."""

    name: str
    default: str | bool | int
    description: str
    choices: tuple[str, ...] = ()
    minimum: int | None = None   # int options
    maximum: int | None = None

    def problem(self, value: object) -> str | None:
        """Why ``value`` is not acceptable, or None."""
        if self.choices:
            return None if value in self.choices else f"must be one of {', '.join(self.choices)}"
        if isinstance(self.default, bool):
            return None if isinstance(value, bool) else "must be true or false"
        if isinstance(value, bool) or not isinstance(value, int):
            return "must be an integer"
        if self.minimum is not None and value < self.minimum:
            return f"must be >= {self.minimum}"
        if self.maximum is not None and value > self.maximum:
            return f"must be <= {self.maximum}"
        return None


@dataclass(frozen=True)
class Link:
    """A moving link, for centres of mass and the shaking force
    (docs/mechanisms.md, Shaking force and balance).

    Its frame: origin at its first joint, u along ``angle`` (rad), v to the left.
    All fields are trees over the template's quantities and parameters."""

    name: str
    joint: tuple[Node, Node]          # first joint, position
    joint_acc: tuple[Node, Node]      # first joint, acceleration
    angle: Node                       # direction of u, in radians
    omega: Node                       # angular velocity (0 for a translating link)
    alpha: Node                       # angular acceleration


@dataclass(frozen=True)
class Mass:
    """A link's mass (kg) and centre of mass: ``u`` along the link from its first joint,
    ``v`` to its left, in the template's length unit (docs/scene.md, masses)."""

    m: float
    u: float
    v: float


@dataclass(frozen=True)
class PointMass:
    """A mass carried by a link: ``m`` (kg) at (``u``, ``v``) in the link's frame, all trees."""

    label: str      # column suffix: the link's name, or cw_crank for a counterweight
    link: Link
    m: Node
    u: Node
    v: Node
    description: str


@dataclass(frozen=True)
class Template:
    id: str
    title: str
    description: str
    input: InputSpec
    parameters: tuple[ParamSpec, ...]
    quantities: tuple[Quantity, ...]
    status: Node  # a text per row: "ok", "cannot assemble", "dead centre"
    checks: tuple[Check, ...] = ()
    charts: tuple[Chart, ...] = ()
    spans: tuple[Span, ...] = ()
    figures: tuple[Figure, ...] = ()
    options: tuple[OptionSpec, ...] = ()
    derived: tuple[Derived, ...] = ()  # in order: each may use the parameters and earlier ones
    links: tuple[Link, ...] = ()
    conditions: tuple[Condition, ...] = ()
    length_unit_m: float = 1e-3  # metres per length unit of the template (mm)
    # Options -> the template for them (branch, method, iterations, balance ...).
    configure: Callable[["Template", Mapping[str, object]], "Template"] = (
        lambda template, options: template)
    # Cross-parameter rule: a message naming the offending parameter, or None.
    validate: Callable[[Mapping[str, float]], tuple[str, str] | None] = lambda p: None
    # The status over only the columns a scene keeps, for templates whose parts are
    # independent (the legs of a parallel mechanism); None: ``status`` whatever is kept.
    status_for: Callable[[frozenset[str]], Node] | None = None
    # Why nothing assembles, for the error message.
    assembly_failure: Callable[[Mapping[str, float]], str] = lambda p: "no row assembles"

    def __post_init__(self) -> None:
        params = {p.name for p in self.parameters} | {d.name for d in self.derived}
        earlier = {self.input.name}
        seen: set[int] = set()  # subtrees already checked (the known names only grow)
        for q in self.quantities:  # each refers only to earlier columns: a valid order
            _check_refs(self.id, q.name, q.expr, earlier, params, seen)
            earlier.add(q.name)
        known = earlier
        for c in self.checks:
            _check_refs(self.id, c.name, c.expr, known, params, seen)
        _check_refs(self.id, "status", self.status, known, params, seen)
        alone: set[int] = set()
        for c in self.conditions:
            _check_refs(self.id, c.name, c.expr + c.scale, set(), params, alone)

    def quantity(self, name: str) -> Quantity:
        for q in self.quantities:
            if q.name == name:
                return q
        raise KeyError(name)

    @property
    def outputs(self) -> tuple[str, ...]:
        return tuple(q.name for q in self.quantities if q.output)

    @property
    def defaults(self) -> dict[str, float]:
        return {p.name: p.default for p in self.parameters}

    @property
    def option_defaults(self) -> dict[str, object]:
        return {o.name: o.default for o in self.options}

    def with_options(self, options: Mapping[str, object]) -> "Template":
        """The template configured for ``options`` (missing ones take their defaults).

        Templates are immutable and configuring one is pure, so each (template, options)
        is configured once per process: loading a scene asks for the same configuration
        once per requested quantity."""
        chosen = {**self.option_defaults, **options}
        key = (id(self), tuple(sorted(chosen.items())))
        hit = _CONFIGURED.get(key)
        if hit is None or hit[0] is not self:
            if len(_CONFIGURED) >= _MAX_CONFIGURED:
                _CONFIGURED.clear()
            hit = _CONFIGURED[key] = (self, self.configure(self, chosen))
        return hit[1]


# (id of the template, its options) -> (the template, configured); the template is kept so
# that its id is not reused while the entry lives
_CONFIGURED: dict[tuple[int, tuple], tuple[Template, Template]] = {}
_MAX_CONFIGURED = 256


def _check_refs(template: str, what: str, expr: Node, known: set[str], params: set[str],
                seen: set[int]) -> None:
    """Every Var of ``expr`` is in ``known`` and every Param in ``params``; subtrees in
    ``seen`` (by identity: the trees share them) were checked against no more names."""
    unknown = set()
    stack = [expr]
    while stack:
        node = stack.pop()
        if id(node) in seen:
            continue
        seen.add(id(node))
        if isinstance(node, Var):
            if node.name not in known:
                unknown.add(node.name)
        elif isinstance(node, Param):
            if node.name not in params:
                unknown.add(node.name)
        else:
            stack.extend(children(node))
    if unknown:
        raise ValueError(f"template {template}: {what} refers to unknown {sorted(unknown)}")


def symbols(names: str, kind: type = Param) -> tuple[Node, ...]:
    """``l_AB, l_BC = symbols("l_AB l_BC")``: parameter (or Var) nodes by name."""
    return tuple(kind(n) for n in names.split())


def quantity_vars(names: str) -> tuple[Var, ...]:
    return symbols(names, Var)  # type: ignore[return-value]


def speed_scale(omega: Node) -> Node:
    """The input speed as the scale of a rate residual, 1 where it is 0: at zero speed
    every rate is 0 and the residual is measured per unit speed instead of as 0/0."""
    return if_(eq(omega, 0), 1, omega)
