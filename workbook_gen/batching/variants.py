"""Which variants a batch makes: ``--vary`` specs, ``--design`` files, random samples.

Every spec is checked before anything is written; a bad one raises SceneError with a
one-line message naming the spec and what to fix (the command line exits 2).

- ``NAME=START:STOP:STEP``: a grid, start to stop inclusive (stop kept when it lies on
  the grid to 1e-9 relative);
- ``NAME=V1,V2,...``: a list;
- several of those: the full factorial in the order given, the last varying fastest;
- ``NAME=normal:MEAN:SD`` / ``NAME=uniform:LO:HI`` with ``samples`` and ``seed``: random
  variants from numpy's ``default_rng(seed)``, drawn spec by spec in the order given;
- a design file (CSV or xlsx, first sheet): one variant per row, the header names the
  parameters, an optional ``variant`` column names the rows, an empty cell keeps the
  scene's value.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple, Sequence
from collections.abc import Sequence as SequenceABC

import numpy as np

from ..errors import SceneError

# One row per variant on the summary's Variants sheet: Excel's rows less the header.
MAX_VARIANTS = 1_048_575


class Variant(NamedTuple):
    """One variant (a named tuple: 100,000 of them are made in a fraction of what frozen
    dataclasses cost)."""

    index: int                      # 1-based, the file number
    label: str                      # the summary's ``variant`` column
    values: tuple[tuple[str, float], ...]  # the overrides, in --vary / design column order


class ColumnVariants(SequenceABC):
    """Variants every one of which sets the same parameters, held as one float column
    per parameter and made when asked (a million ``Variant`` tuples held ~360 MB, the
    columns 8 bytes a value): ``[k]`` is a ``Variant``, a slice another
    ``ColumnVariants`` (what a worker is sent: its columns only)."""

    def __init__(self, names: tuple[str, ...], columns: Sequence[np.ndarray], first: int = 1):
        self.names, self.columns, self.first = names, tuple(columns), first

    def __len__(self) -> int:
        return len(self.columns[0]) if self.columns else 0

    def __getitem__(self, key):
        if isinstance(key, slice):
            lo, hi, step = key.indices(len(self))
            if step != 1:
                return tuple(self[k] for k in range(lo, hi, step))
            return ColumnVariants(self.names, [c[lo:max(lo, hi)] for c in self.columns],
                                  self.first + lo)
        size = len(self)
        k = key + size if key < 0 else key
        if not 0 <= k < size:
            raise IndexError(f"variant {key} of {size}")
        return Variant(self.first + k, str(self.first + k),
                       tuple(zip(self.names, [c.item(k) for c in self.columns])))

    def __iter__(self):
        rows = zip(*(c.tolist() for c in self.columns)) if self.columns else ()
        names = self.names
        for k, row in enumerate(rows, self.first):
            yield Variant(k, str(k), tuple(zip(names, row)))


def _factorial(names: tuple[str, ...], levels: tuple[tuple[float, ...], ...]
               ) -> ColumnVariants:
    """The full factorial of ``levels``, the last varying fastest."""
    sizes = [len(level) for level in levels]
    columns = []
    for j, level in enumerate(levels):
        before, after = math.prod(sizes[:j]), math.prod(sizes[j + 1:])
        columns.append(np.repeat(np.tile(np.array(level, dtype=float), before), after))
    return ColumnVariants(names, columns)


@dataclass(frozen=True)
class Design:
    """The variants of a batch and the parameters they vary, in order."""

    names: tuple[str, ...]
    variants: Sequence[Variant]    # a tuple, or ColumnVariants (grids, random samples)
    kind: str                       # "grid" (grids and lists), "random" or "design"
    levels: tuple[tuple[float, ...], ...] = ()   # grid: the values of each name, in order

    def __len__(self) -> int:
        return len(self.variants)


@dataclass(frozen=True)
class _Spec:
    name: str
    kind: str                       # "grid" | "list" | "normal" | "uniform"
    numbers: tuple[float, ...]
    text: str


def _number(spec: str, text: str, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise SceneError(f"--vary {spec!r}: {what} {text.strip()!r} is not a number") from None
    if not math.isfinite(value):
        raise SceneError(f"--vary {spec!r}: {what} must be finite, got {text.strip()!r}")
    return value


def parse_vary(text: str) -> _Spec:
    name, sep, body = text.partition("=")
    name, body = name.strip(), body.strip()
    if not sep or not name or not body:
        raise SceneError(f"--vary {text!r}: expected NAME=START:STOP:STEP, NAME=V1,V2,... "
                         f"or NAME=normal:MEAN:SD | uniform:LO:HI")
    head, _, rest = body.partition(":")
    if head.strip().lower() in ("normal", "uniform"):
        kind = head.strip().lower()
        parts = rest.split(":")
        labels = ("MEAN", "SD") if kind == "normal" else ("LO", "HI")
        if len(parts) != 2:
            raise SceneError(f"--vary {text!r}: expected {name}={kind}:{labels[0]}:{labels[1]}")
        a, b = (_number(text, p, label) for p, label in zip(parts, labels))
        if kind == "normal" and b <= 0:
            raise SceneError(f"--vary {text!r}: SD must be > 0, got {parts[1].strip()}")
        if kind == "uniform" and not a < b:
            raise SceneError(f"--vary {text!r}: LO must be < HI, got {parts[0].strip()} and "
                             f"{parts[1].strip()}")
        return _Spec(name, kind, (a, b), text)
    if ":" in body:
        parts = body.split(":")
        if len(parts) != 3:
            raise SceneError(f"--vary {text!r}: a grid is {name}=START:STOP:STEP")
        start, stop, step = (_number(text, p, w) for p, w in zip(parts, ("START", "STOP", "STEP")))
        if step == 0:
            raise SceneError(f"--vary {text!r}: STEP must not be 0")
        if (stop - start) * step < 0:
            raise SceneError(f"--vary {text!r}: STEP {parts[2].strip()} never reaches STOP "
                             f"{parts[1].strip()} from START {parts[0].strip()}")
        return _Spec(name, "grid", _grid(text, start, stop, step), text)
    values = tuple(_number(text, p, "value") for p in body.split(","))
    if len(set(values)) != len(values):
        raise SceneError(f"--vary {text!r}: a value is listed twice")
    return _Spec(name, "list", values, text)


def _grid(text: str, start: float, stop: float, step: float) -> tuple[float, ...]:
    span = (stop - start) / step
    count = int(math.floor(span + 1e-9)) + 1
    if count > MAX_VARIANTS:
        raise SceneError(f"--vary {text!r}: {count:,} values, more than {MAX_VARIANTS:,}")
    # Free of accumulated rounding (95.5, not 95.50000000000001): as many decimals as
    # the step needs, and ten more.
    decimals = 10 - int(math.floor(math.log10(abs(step))))
    values = [round(start + i * step, decimals) for i in range(count)]
    if abs(values[-1] - stop) <= 1e-9 * max(abs(stop), abs(step)):
        values[-1] = stop
    return tuple(values)


def _check_names(names: Sequence[str], parameters: Sequence[str], sets: Sequence[str],
                 where: str) -> None:
    seen = set()
    for name in names:
        if name not in parameters:
            raise SceneError(f"{where} {name!r}: not a parameter of this scene's template "
                             f"(known: {', '.join(parameters)})")
        if name in seen:
            raise SceneError(f"{where} {name!r}: varied twice")
        if name in sets:
            raise SceneError(f"{where} {name!r}: also given with --set; vary it or set it, "
                             f"not both")
        seen.add(name)


def from_specs(texts: Sequence[str], parameters: Sequence[str], sets: Sequence[str] = (),
               samples: int | None = None, seed: int | None = None) -> Design:
    """The variants of ``--vary`` specs (grid/list factorial, or random samples)."""
    specs = [parse_vary(t) for t in texts]
    _check_names([s.name for s in specs], parameters, sets, "--vary")
    random = [s for s in specs if s.kind in ("normal", "uniform")]
    names = tuple(s.name for s in specs)
    if random:
        if len(random) != len(specs):
            fixed = next(s for s in specs if s not in random)
            raise SceneError(f"--vary {fixed.text!r}: random specs (normal:, uniform:) cannot "
                             f"be mixed with grids or lists; give every varied parameter a "
                             f"distribution")
        if samples is None:
            raise SceneError(f"--vary {random[0].text!r}: a random spec needs --samples N "
                             f"(and --seed S to choose the draw)")
        if not 1 <= samples <= MAX_VARIANTS:
            raise SceneError(f"--samples must be 1..{MAX_VARIANTS:,}, got {samples}")
        rng = np.random.default_rng(0 if seed is None else seed)
        columns = []
        for s in specs:
            a, b = s.numbers
            draw = rng.normal(a, b, samples) if s.kind == "normal" else rng.uniform(a, b, samples)
            columns.append(draw)
        return Design(names, ColumnVariants(names, columns), "random")
    if samples is not None or seed is not None:
        raise SceneError("--samples and --seed go with a random spec "
                         "(--vary NAME=normal:MEAN:SD or NAME=uniform:LO:HI)")
    if not specs:
        raise SceneError("nothing to vary: give --vary NAME=SPEC (repeatable) or --design FILE")
    levels = tuple(s.numbers for s in specs)
    count = math.prod(len(v) for v in levels)
    if count > MAX_VARIANTS:
        raise SceneError(f"--vary: {count:,} variants in the full factorial, more than "
                         f"{MAX_VARIANTS:,}")
    return Design(names, _factorial(names, levels), "grid", levels)


def _design_rows(path: Path) -> list[list[object]]:
    suffix = path.suffix.lower()
    try:
        if suffix == ".csv":
            with path.open(newline="", encoding="utf-8-sig") as handle:
                return [row for row in csv.reader(handle)]
        if suffix in (".xlsx", ".xlsm"):
            import openpyxl
            book = openpyxl.load_workbook(path, read_only=True, data_only=True)
            try:
                sheet = book.worksheets[0]
                return [list(row) for row in sheet.iter_rows(values_only=True)]
            finally:
                book.close()
    except OSError as exc:
        raise SceneError(f"--design {path}: cannot read: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise SceneError(f"--design {path}: not UTF-8 text") from None
    except Exception as exc:  # openpyxl's many ways of refusing a file
        raise SceneError(f"--design {path}: not a readable xlsx file ({exc})") from None
    raise SceneError(f"--design {path}: expected a .csv or .xlsx file")


def _blank(value: object) -> bool:
    return value is None or (isinstance(value, str) and not value.strip())


def from_design(path: str | Path, parameters: Sequence[str], sets: Sequence[str] = ()) -> Design:
    """One variant per row of a CSV or xlsx design table."""
    path = Path(path)
    rows = [row for row in _design_rows(path) if not all(_blank(v) for v in row)]
    if not rows:
        raise SceneError(f"--design {path}: empty; the first row names the parameters")
    header = [str(h).strip() if not _blank(h) else "" for h in rows[0]]
    while header and not header[-1]:
        header.pop()
    if "" in header:
        raise SceneError(f"--design {path}: column {header.index('') + 1} of the header is empty")
    label_col = header.index("variant") if "variant" in header else None
    names = [h for h in header if h != "variant"]
    if header.count("variant") > 1:
        raise SceneError(f"--design {path}: two 'variant' columns")
    if not names:
        raise SceneError(f"--design {path}: the header names no parameter")
    _check_names(names, parameters, sets, f"--design {path}: column")
    if len(rows) - 1 > MAX_VARIANTS:
        raise SceneError(f"--design {path}: {len(rows) - 1:,} rows, more than {MAX_VARIANTS:,}")
    variants = []
    for r, row in enumerate(rows[1:], start=2):
        row = list(row) + [None] * (len(header) - len(row))
        if any(not _blank(v) for v in row[len(header):]):
            raise SceneError(f"--design {path}: row {r} has more cells than the header")
        values = []
        for c, name in enumerate(header):
            cell = row[c]
            if c == label_col or _blank(cell):
                continue
            if isinstance(cell, bool) or not isinstance(cell, (int, float, str)):
                raise SceneError(f"--design {path}: row {r}, {name}: not a number: {cell!r}")
            try:
                value = float(cell)
            except ValueError:
                raise SceneError(f"--design {path}: row {r}, {name}: not a number: "
                                 f"{cell!r}") from None
            if not math.isfinite(value):
                raise SceneError(f"--design {path}: row {r}, {name}: must be finite, "
                                 f"got {cell!r}")
            values.append((name, value))
        label = str(row[label_col]).strip() if label_col is not None and not _blank(
            row[label_col]) else str(r - 1)
        variants.append(Variant(r - 1, label, tuple(values)))
    return Design(tuple(names), tuple(variants), "design")
