"""The 50-digit reference: the scene's own trees evaluated with mpmath.

``Precise(scene)`` evaluates any Table column at any input value, at 50
significant digits (``mp.dps``), through only the columns that column needs.
``true_extremes`` finds an output's maximum and minimum over the sweep: the
dense float64 grid gives the candidates, and each is refined in 50 digits by a
safeguarded Newton iteration on the derivative (central differences at 50
digits, step 1e-15 of the sweep: truncation ~1e-30, rounding ~1e-35), falling
back to golden-section search where the shape is not a clean peak.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Iterable

import mpmath
import numpy as np

from ..expr.precise import compile_mpmath
from ..pruning import needed, select
from ..scene import Scene

DPS = 50
_GOLDEN = (mpmath.sqrt(5) - 1) / 2


class Precise:
    """Columns of a scene at ``dps`` digits, as functions of the input."""

    def __init__(self, scene: Scene, dps: int = DPS):
        self.scene, self.dps = scene, dps
        self.model = select(scene.template, scene.outputs)
        self.input = scene.template.input.name
        self._compiled = [(q.name, compile_mpmath(q.expr)) for q in self.model.columns]
        self._plans: dict[frozenset, list] = {}
        with mpmath.workdps(dps):  # the parameters, then the template's derived values (the
            # four-bar's length gaps...) in their order, each over those before it: once
            self._params = {k: mpmath.mpf(v) for k, v in scene.parameters.items()}
            for d in scene.template.derived:
                value = compile_mpmath(d.expr)({}, self._params)
                self._params[d.name] = value if isinstance(value, mpmath.mpf) else mpmath.nan

    def _plan(self, names: Iterable[str] | None) -> list:
        if names is None:
            return self._compiled
        key = frozenset(names)
        if key not in self._plans:
            keep = needed(self.scene.template, set(key))
            self._plans[key] = [(n, f) for n, f in self._compiled if n in keep]
        return self._plans[key]

    def row(self, x, names: Iterable[str] | None = None) -> dict[str, object]:
        """The columns ``names`` (and what they need; all if None) at input ``x``:
        mpf values or ExcelError."""
        with mpmath.workdps(self.dps):
            values: dict[str, object] = {self.input: mpmath.mpf(x)}
            for name, fn in self._plan(names):
                values[name] = fn(values, self._params)
        return values

    def column(self, name: str) -> Callable[[object], object]:
        """x -> the column's value at x (mpf, or None where it is an error or text)."""
        def f(x):
            value = self.row(x, (name,))[name]
            return value if isinstance(value, mpmath.mpf) else None
        return f

    def table(self, xs: Iterable[float], names: Iterable[str] | None = None) -> list[dict]:
        return [self.row(x, names) for x in xs]


@dataclass(frozen=True)
class Extremes:
    maximum: float
    minimum: float
    at_max: float
    at_min: float

    @property
    def magnitude(self) -> float:
        return max(abs(self.maximum), abs(self.minimum))


def _peak(g, a, m, b, lo, hi, dps: int):
    """The largest value of ``g`` near the grid peak m in [a, b] (a <= m <= b, inside
    [lo, hi]); returns (x, g(x)).  ``g`` returns None where undefined."""
    with mpmath.workdps(dps):
        seen: dict = {}

        def val(x):
            if x not in seen:
                v = g(x)
                seen[x] = mpmath.mpf("-inf") if v is None else v
            return seen[x]

        delta = (hi - lo) * mpmath.mpf("1e-15")

        def slope(x):
            xa, xb = max(lo, x - delta), min(hi, x + delta)
            return (val(xb) - val(xa)) / (xb - xa)

        a, m, b = mpmath.mpf(a), mpmath.mpf(m), mpmath.mpf(b)
        for x in (a, m, b):
            val(x)
        da, db = slope(a), slope(b)
        at_lo, at_hi = a == lo and da <= 0, b == hi and db >= 0
        if not (at_lo or at_hi) and da > 0 > db:
            x = m
            for _ in range(60):  # Newton on the slope, kept inside the bracket
                d = slope(x)
                if d == 0:
                    break
                if d > 0:
                    a = x
                else:
                    b = x
                curv = (val(min(hi, x + delta)) - 2 * val(x) + val(max(lo, x - delta))) / delta ** 2
                step = -d / curv if curv < 0 else None
                nxt = x + step if step is not None and a < x + step < b else (a + b) / 2
                if abs(nxt - x) <= delta:
                    x = nxt
                    val(x)
                    break
                x = nxt
        elif not (at_lo or at_hi):
            for _ in range(80):  # golden section on [a, b]
                c, d = b - _GOLDEN * (b - a), a + _GOLDEN * (b - a)
                if val(c) >= val(d):
                    b = d
                else:
                    a = c
                if b - a <= delta:
                    break
        x = max(seen, key=lambda k: seen[k])
        return x, seen[x]


def true_extremes(precise: Precise, name: str, xs: np.ndarray, ys: np.ndarray,
                  candidates: int = 3) -> Extremes | None:
    """The true maximum and minimum of column ``name`` over [xs[0], xs[-1]], refined
    from the float64 grid values ``ys`` (NaN where undefined).  None if ``ys`` is
    all NaN."""
    ok = np.isfinite(ys)
    if not ok.any():
        return None
    f = precise.column(name)
    lo, hi = mpmath.mpf(float(xs[0])), mpmath.mpf(float(xs[-1]))
    found = []
    for sign in (1.0, -1.0):
        y = np.where(ok, sign * ys, -np.inf)
        top = np.max(y)
        spread = max(np.max(y[ok]) - np.min(y[ok]), abs(top)) * 1e-4
        n = len(y)
        peaks = [i for i in range(n) if y[i] >= top - spread
                 and (i == 0 or y[i] >= y[i - 1]) and (i == n - 1 or y[i] >= y[i + 1])]
        peaks = sorted(peaks, key=lambda i: -y[i])[:candidates]

        def g(x, s=sign):
            v = f(x)
            return None if v is None else s * v
        best = None
        for i in peaks:
            a, b = xs[max(i - 1, 0)], xs[min(i + 1, n - 1)]
            x, v = _peak(g, float(a), float(xs[i]), float(b), lo, hi, precise.dps)
            if best is None or v > best[1]:
                best = (x, v)
        found.append((float(best[0]), float(sign * best[1])))
    (x_max, y_max), (x_min, y_min) = found
    return Extremes(y_max, y_min, x_max, x_min)

