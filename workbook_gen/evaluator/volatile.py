"""Cells whose value changes at every recalculation (TODAY, NOW, RAND, RANDBETWEEN,
RANDARRAY): checked against the function's contract instead of recomputed.

A cell calling one of them cannot be recomputed: the cached value is from the moment
(or the draw) of the file's last recalculation. What can be checked is that some value
the function may return gives the cached value:

- ``TODAY()``: a whole date serial, at most a day after the file's last save
  (``dcterms:modified`` of docProps/core.xml, in UTC: a day either way for time zones);
  an earlier date is accepted (a file saved without recalculating keeps old values) and
  the message says how much earlier;
- ``NOW()``: a serial at most a day after the last save;
- ``RAND()``: a number in [0, 1);
- ``RANDBETWEEN(a, b)``: a whole number in [a, b], ``a`` and ``b`` recomputed;
- ``RANDARRAY(rows, cols, min, max, whole)`` as an array formula on its own
  (:func:`check_array`): each cell of its area a number in [min, max] (whole with
  ``whole``), #N/A beyond rows x cols.

A formula that is just the call is checked directly (a value outside the contract is a
disagreement). A formula around the call (``TODAY()+$A2``, ``(RANDBETWEEN(-50,250)+100)*10``,
``TEXT(TODAY(),"mm/dd/yyyy")``) is evaluated with the call replaced by candidate values:
the dates around the last save, the value another cell of the workbook settled on, the
value that solves an affine formula, and every value of a small whole-number range. A
candidate inside the contract that gives the cached value: agrees; a contract searched
completely with none: disagrees; otherwise not checked. A formula
with several independent draws (two RAND() calls) is not checked.

NOW and TODAY are not draws: one recalculation reads the clock once, so every NOW() of
the workbook returns the same moment t and every TODAY() the day INT(t). They are one
shared unknown, fixed by any cell that determines it: a cell that is just ``=NOW()`` or
``=TODAY()`` caches it (:func:`moments` collects those values before any cell is
checked). A formula with NOW/TODAY and at most one draw (``RAND()*NOW()``,
``NOW()-TODAY()``) is evaluated at each moment the workbook settled on, the draw (if
any) then checked as above: agrees if one moment gives the cached value. It never
disagrees: a cell entered after the last full recalculation (manual calculation) may
have read another moment.

Either way the cell's cached value is what its dependents read: they are recomputed from
it and compared as usual (the same as they would be from a constant input).
"""

from __future__ import annotations

import dataclasses
import datetime as dt
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from workbook_gen.formula import ast
from workbook_gen.formula.functions import coerce
from workbook_gen.formula.functions.serials import moment_of, moment_serial
from workbook_gen.xlerror import ExcelError

CHANGING = frozenset({"NOW", "TODAY", "RAND", "RANDBETWEEN", "RANDARRAY"})
SHARED = frozenset({"NOW", "TODAY"})  # one value per recalculation (the clock's moment)
MAX_MOMENTS = 8  # distinct moments tried for a formula mixing NOW/TODAY with others
SMALL_RANGE = 2000  # whole-number contracts searched value by value up to this size


@dataclass
class Clock:
    """What the audit knows of the file's last recalculation."""
    cached: Mapping  # (sheet, row, col) -> cached value of each formula cell
    saved: dt.datetime | None = None  # dcterms:modified (UTC), None if the file omits it
    agree: Callable[[object, object], bool] = lambda a, b: a == b
    date1904: bool = False
    settled: dict[str, float] = field(default_factory=dict)  # TODAY/NOW values found
    moments: dict[str, list[float]] = field(default_factory=dict)  # cached by =NOW()/=TODAY()

    def serial(self) -> float | None:
        if self.saved is None:
            return None
        return moment_serial(self.saved.replace(tzinfo=None), self.date1904)


@dataclass
class Outcome:
    status: str  # "agrees", "disagrees" or "unknown"
    message: str
    contract: str = ""  # the contract in a few words (shown as the "recomputed" side)


def calls(node: ast.Node) -> list[ast.Func]:
    return [n for n in ast.walk(node) if isinstance(n, ast.Func) and n.name in CHANGING]


def _date(serial: float, date1904: bool = False) -> str:
    day = moment_of(serial, date1904)
    if day is None:
        return f"serial {serial:g}"
    return day.strftime("%Y-%m-%d %H:%M" if serial != int(serial) else "%Y-%m-%d")


def _number(value) -> float | None:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    return float(value) if math.isfinite(value) else None


def _replace(node: ast.Node, sites: list, value) -> ast.Node:
    """``node`` with every call in ``sites`` (by identity) replaced by ``value``."""
    if any(node is s for s in sites):
        if isinstance(value, ExcelError):
            return ast.ErrorLit(value)
        return ast.Number(float(value), repr(float(value)))
    if isinstance(node, ast.Func):
        return dataclasses.replace(node, args=tuple(_replace(a, sites, value) for a in node.args))
    if isinstance(node, (ast.Unary, ast.Percent)):
        return dataclasses.replace(node, operand=_replace(node.operand, sites, value))
    if isinstance(node, ast.Binary):
        return ast.Binary(node.op, _replace(node.left, sites, value),
                          _replace(node.right, sites, value))
    if isinstance(node, ast.Paren):
        return ast.Paren(_replace(node.inner, sites, value))
    return node


def _bare(node: ast.Node) -> ast.Node:
    while isinstance(node, ast.Paren):
        node = node.inner
    return node


class _Domain:
    """The values a call may return: whole numbers or reals in [lo, hi] (hi excluded for
    RAND), with preferred candidates and a text for messages."""

    def __init__(self, lo, hi, whole, text, preferred=(), hi_open=False):
        self.lo, self.hi, self.whole, self.text = lo, hi, whole, text
        self.preferred, self.hi_open = list(preferred), hi_open

    def holds(self, x: float) -> bool:
        if self.whole and x != int(x):
            return False
        return self.lo <= x and (x < self.hi if self.hi_open else x <= self.hi)

    def finite(self) -> list[float] | None:
        if self.whole and self.hi - self.lo < SMALL_RANGE:
            return [float(v) for v in range(int(self.lo), int(self.hi) + 1)]
        return None


def _domain(call: ast.Func, evaluate, clock: Clock):
    """The call's contract as a _Domain, or an ExcelError the call returns for sure,
    or a text saying why it cannot be checked."""
    saved = clock.serial()
    if call.name == "TODAY":
        hi = math.floor(saved) + 1 if saved is not None else math.inf
        near = [] if saved is None else [math.floor(saved) + k for k in (0, -1, 1)]
        where = ("" if saved is None else
                 f" up to {_date(hi, clock.date1904)} (a day after the file's last save)")
        return _Domain(1, hi, True, "a whole date serial" + where,
                       [clock.settled[k] for k in ("TODAY",) if k in clock.settled]
                       + clock.moments.get("TODAY", [])
                       + [math.floor(t) for t in clock.moments.get("NOW", [])] + near)
    if call.name == "NOW":
        hi = saved + 1 if saved is not None else math.inf
        near = [] if saved is None else [saved + h / 24 for h in range(-12, 15)]
        where = ("" if saved is None else
                 f" up to {_date(round(hi * 1440) / 1440, clock.date1904)} "
                 "(a day after the file's last save)")
        return _Domain(0, hi, False, "a date-time serial" + where,
                       [clock.settled[k] for k in ("NOW",) if k in clock.settled]
                       + clock.moments.get("NOW", []) + near)
    if call.name == "RAND":
        return _Domain(0.0, 1.0, False, "a number in [0, 1)", [0.0, 0.5], hi_open=True)
    if call.name == "RANDBETWEEN":
        if len(call.args) != 2:
            return "RANDBETWEEN takes two arguments"
        bounds = []
        for arg in call.args:  # a cell's text or boolean is #VALUE!; a direct one converts
            value = evaluate(arg)
            if (isinstance(_bare(arg), (ast.CellRef, ast.Name)) and isinstance(value, (str, bool))
                    and not isinstance(value, ExcelError)):
                return ExcelError.VALUE
            number = coerce.number(value)
            if isinstance(number, ExcelError):
                return number
            bounds.append(number)
        lo, hi = math.ceil(bounds[0]), math.floor(bounds[1])
        if lo > hi:
            return ExcelError.NUM
        return _Domain(lo, hi, True, f"a whole number in [{lo}, {hi}]")
    return f"{call.name} is not checked"


def moments(cells, cached: Mapping, clock: Clock) -> None:
    """Record in ``clock.moments`` the values that cells which are just ``=NOW()`` or
    ``=TODAY()`` cache (numbers within the function's contract): ``cells`` yields
    (cell, tree) pairs."""
    for cell, node in cells:
        node = _bare(node)
        if not (isinstance(node, ast.Func) and node.name in SHARED and not node.args):
            continue
        x = _number(cached.get(cell))
        found = clock.moments.setdefault(node.name, [])
        if (x is not None and x not in found and len(found) < MAX_MOMENTS
                and _domain(node, None, clock).holds(x)):
            found.append(x)


def _at_moments(node, sites, cached, evaluate, clock: Clock) -> Outcome | None:
    """A formula with NOW/TODAY and at most one draw, at each moment the workbook settled
    on (see the module doc): the agreeing outcome, or None."""
    now = [s for s in sites if s.name == "NOW"]
    today = [s for s in sites if s.name == "TODAY"]
    times = clock.moments.get("NOW", [])
    if now:
        candidates = [(t, float(math.floor(t))) for t in times]
    else:
        days = clock.moments.get("TODAY", []) + [float(math.floor(t)) for t in times]
        candidates = [(None, d) for d in dict.fromkeys(days)]
    for t, day in candidates:
        tree = _replace(_replace(node, now, t), today, day) if now else _replace(node, today, day)
        when = (f"NOW() = {_value_text('NOW', t, clock)}" if now
                else f"TODAY() = {_value_text('TODAY', day, clock)}")
        if not calls(tree):
            if clock.agree(cached, evaluate(tree)):
                return Outcome("agrees", f"volatile {when} (the moment of the workbook's "
                                         "recalculation) gives the cached value")
            continue
        outcome = check(tree, cached, evaluate, clock)
        if outcome.status == "agrees":
            return Outcome("agrees", f"at {when} (the moment of the workbook's "
                                     f"recalculation), {outcome.message}")
    return None


def check(node: ast.Node, cached, evaluate, clock: Clock) -> Outcome:
    """Does some value within the contract of the formula's volatile call give ``cached``?
    ``evaluate(tree)`` evaluates a tree at the cell."""
    sites = calls(node)
    kinds = {s.name for s in sites}
    independent = sum(1 for s in sites if s.name in ("RAND", "RANDBETWEEN", "RANDARRAY"))
    if not sites:
        return Outcome("unknown", "no volatile call")
    if "RANDARRAY" in kinds:
        return Outcome("unknown", "volatile function RANDARRAY: not checked (an array of draws)")
    if len(kinds) > 1 or independent > 1:
        if kinds & SHARED and independent <= 1:
            outcome = _at_moments(node, sites, cached, evaluate, clock)
            if outcome is not None:
                return outcome
        return Outcome("unknown", "volatile functions " + ", ".join(sorted(kinds))
                       + ": several values that change at every recalculation: not checked")
    name = sites[0].name
    domain = _domain(sites[0], evaluate, clock)
    if isinstance(domain, str):
        return Outcome("unknown", f"volatile function {name}: {domain}")
    if isinstance(domain, ExcelError):  # the call's value is certain: recompute as usual
        value = evaluate(_replace(node, sites, domain))
        if clock.agree(cached, value):
            return Outcome("agrees", f"volatile {name}: returns {domain.value} for its "
                                     "arguments; recomputed")
        return Outcome("disagrees", f"volatile {name} returns {domain.value} for its arguments",
                       domain.value)
    label = f"{name}()" if name in ("TODAY", "NOW", "RAND") else name
    if _bare(node) is sites[0]:
        x = _number(cached)
        if x is not None and domain.holds(x):
            return Outcome("agrees", f"volatile {label}: checked against its contract "
                                     f"({_value_text(name, x, clock)} is {domain.text})")
        return Outcome("disagrees", f"volatile {label}: the cached value is not "
                                    f"{domain.text}", domain.text)
    f = lambda x: evaluate(_replace(node, sites, x))  # noqa: E731
    tried: set[float] = set()
    candidates = list(domain.preferred)
    solved = _solve(f, cached, domain)
    if solved is not None and math.isfinite(solved):
        candidates.insert(0, solved)
    complete = domain.finite()
    for x in candidates + (complete or []):
        if x in tried or not domain.holds(x):
            continue
        tried.add(x)
        if clock.agree(cached, f(x)):
            if name in ("TODAY", "NOW"):
                clock.settled.setdefault(name, x)
            return Outcome("agrees", f"volatile {label}: checked against its contract "
                                     f"({label} = {_value_text(name, x, clock)}, "
                                     f"{domain.text}, gives the cached value)")
    if complete is not None:
        return Outcome("disagrees", f"volatile {label}: no value of {label} that is "
                                    f"{domain.text} gives the cached value",
                       f"{label} = {domain.text}")
    return Outcome("unknown", f"volatile {label}: no value tried within its contract "
                              f"({domain.text}) gives the cached value")


def _value_text(name: str, x: float, clock: Clock) -> str:
    if name in ("TODAY", "NOW"):
        text = _date(x, clock.date1904)
        saved = clock.serial()
        if saved is not None and name == "TODAY" and x < math.floor(saved) - 1:
            text += f", {int(math.floor(saved) - x)} days before the file's last save"
        return text
    return f"{x:.15g}"


def _solve(f, cached, domain: _Domain):
    """The x where the formula, taken as affine between two points, gives ``cached``
    (rounded to a whole number where the contract is whole), or None: a candidate only,
    tried like the others."""
    y = _number(cached)
    if y is None:
        return None
    lo = domain.lo if math.isfinite(domain.lo) else 0.0
    x0 = float(domain.preferred[0]) if domain.preferred else float(lo)
    x1 = x0 + 1.0 if domain.whole or domain.hi - lo > 1 else x0 + 0.25
    y0, y1 = (_number(f(x)) for x in (x0, x1))
    if y0 is None or y1 is None or y1 == y0:
        return None
    slope = (y1 - y0) / (x1 - x0)
    x = x0 + (y - y0) / slope
    return float(round(x)) if domain.whole else x


def draws_array(node: ast.Node) -> bool:
    """Is the formula just a RANDARRAY call (an area of draws, checked cell by cell)?"""
    node = _bare(node)
    return isinstance(node, ast.Func) and node.name == "RANDARRAY" and not any(
        calls(a) for a in node.args)


def check_array(node: ast.Node, cached: list[list], evaluate) -> list[list[Outcome]]:
    """The outcome of each cell of the area a formula that is just ``RANDARRAY(...)``
    fills (``cached``: the area's cached values, row by row): within the call's rows and
    columns a draw within its contract (between min and max, whole with whole_number
    TRUE), #N/A beyond them; an error the arguments make certain is recomputed."""
    from workbook_gen.formula.functions.math.randarray import contract
    call = _bare(node)
    args = [None if isinstance(a, ast.Missing) else evaluate(a) for a in call.args]
    found = contract(*args)
    out = []
    for i, row in enumerate(cached):
        outcomes = []
        for j, value in enumerate(row):
            if isinstance(found, ExcelError):
                expect = found if i == 0 and j == 0 else ExcelError.NA
                outcomes.append(Outcome("agrees" if value is expect else "disagrees",
                                        f"volatile RANDARRAY returns {found.value} for its "
                                        "arguments", expect.value))
                continue
            n_rows, n_cols, lo, hi, whole = found
            if i >= n_rows or j >= n_cols:  # beyond the array: #N/A
                outcomes.append(Outcome("agrees" if value is ExcelError.NA else "disagrees",
                                        f"beyond RANDARRAY's {n_rows} x {n_cols} array",
                                        "#N/A"))
                continue
            text = (f"a whole number in [{lo:g}, {hi:g}]" if whole
                    else f"a number in [{lo:.15g}, {hi:.15g}]")
            x = _number(value)
            if x is not None and _Domain(lo, hi, whole, text).holds(x):
                outcomes.append(Outcome("agrees", "volatile RANDARRAY: checked against its "
                                                  f"contract ({x:.15g} is {text})"))
            else:
                outcomes.append(Outcome("disagrees", "volatile RANDARRAY: the cached value "
                                                     f"is not {text}", text))
        out.append(outcomes)
    return out
