"""Which variants a batch makes: ``--vary`` specs, ``--design`` files, random samples.

Every spec is checked before anything is written; a bad one raises SceneError with a
one-line message naming the spec and what to fix (the command line exits 2).

- ``NAME=START:STOP:STEP``: a grid, start to stop inclusive (stop kept when it lies on
  the grid to 1e-9 relative);
- ``NAME=V1,V2,...``: a list (numbers, or a template option's values:
  ``branch=open,crossed``);
- several of those: the full factorial in the order given, the last varying fastest;
- ``NAME=normal:MEAN:SD`` / ``NAME=uniform:LO:HI`` with ``samples`` and ``seed``: random
  variants from numpy's ``default_rng(seed)``, drawn spec by spec in the order given;
- a design file (CSV with ``,`` or ``;``, or xlsx, first sheet): one variant per row,
  the header names the parameters and options, an optional ``variant`` column names
  the rows, an empty cell keeps the scene's value.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Mapping, NamedTuple, Sequence

import numpy as np

from ..errors import SceneError
from ..mechanisms.base import OptionSpec
from .designfile import decimal_comma, design_rows
from .specs import MAX_VARIANTS, option_value, specs_of

MAX_CELL_TEXT = 32_767  # characters (UTF-16 code units) an Excel cell holds


class Variant(NamedTuple):
    """One variant (a named tuple: 100,000 of them are made in a fraction of what frozen
    dataclasses cost)."""

    index: int                      # 1-based, the file number
    label: str                      # the summary's ``variant`` column
    values: tuple[tuple[str, object], ...]  # the overrides, in --vary / design column order
    #                                         (a parameter's float, an option's value)


@dataclass(frozen=True)
class Design:
    """The variants of a batch and the parameters they vary, in order."""

    names: tuple[str, ...]
    variants: tuple[Variant, ...]
    kind: str                       # "grid" (grids and lists), "random" or "design"
    levels: tuple[tuple[object, ...], ...] = ()  # grid: the values of each name, in order
    options: tuple[str, ...] = ()   # which of ``names`` are template options

    def __len__(self) -> int:
        return len(self.variants)


def flag(name: str, cli: bool) -> str:
    """How a message names an input: ``--samples`` on the command line, ``samples`` in
    Python."""
    return f"--{name}" if cli else name


def _check_names(names: Sequence[str], parameters: Sequence[str], options: Sequence[str],
                 sets: Sequence[str], where, cli: bool) -> None:
    """``where(name)``: how a message names the column or spec."""
    seen = set()
    for name in names:
        if name not in parameters and name not in options:
            known = ", ".join(parameters) + (f"; options: {', '.join(options)}" if options
                                             else "")
            raise SceneError(f"{where(name)}: not a parameter{' or option' if options else ''}"
                             f" of this scene's template (known: {known})")
        if name in seen:
            raise SceneError(f"{where(name)}: varied twice")
        if name in sets:
            raise SceneError(f"{where(name)}: also given with {flag('set', cli)}; vary it or "
                             f"set it, not both")
        seen.add(name)


def from_specs(texts: Sequence[str] | Mapping[str, object], parameters: Sequence[str],
               sets: Sequence[str] = (), samples: int | None = None, seed: int | None = None,
               options: Sequence[OptionSpec] = (), cli: bool = True) -> Design:
    """The variants of ``--vary`` specs (grid/list factorial, or random samples);
    ``texts`` as ``batch()``'s ``vary`` takes it (``specs.specs_of``); ``options`` the
    template's, which may be varied too; ``cli``: messages name the command line's
    flags, else ``batch()``'s arguments."""
    by_name = {o.name: o for o in options}
    specs = specs_of(texts, by_name, cli)
    listed = (lambda name: f"--vary {name!r}") if cli else (lambda name: f"vary[{name!r}]")
    _check_names([s.name for s in specs], parameters, list(by_name), sets, listed, cli)
    random = [s for s in specs if s.kind in ("normal", "uniform")]
    names = tuple(s.name for s in specs)
    varied_options = tuple(n for n in names if n in by_name)
    samples_flag = flag("samples", cli) + (" N" if cli else "")
    if random:
        if len(random) != len(specs):
            fixed = next(s for s in specs if s not in random)
            if fixed.name in by_name:
                raise SceneError(f"{fixed.text}: an option cannot be varied in a random study "
                                 f"(normal:, uniform:); run one batch per value with "
                                 f"{flag('set', cli)} {fixed.name}=VALUE")
            raise SceneError(f"{fixed.text}: random specs (normal:, uniform:) cannot "
                             f"be mixed with grids or lists; give every varied parameter a "
                             f"distribution")
        if samples is None:
            raise SceneError(f"{random[0].text}: a random spec needs {samples_flag} "
                             f"(and {flag('seed', cli)}{' S' if cli else ''} to choose the draw)")
        if isinstance(samples, bool) or not isinstance(samples, int) or not (
                1 <= samples <= MAX_VARIANTS):
            raise SceneError(f"{flag('samples', cli)} must be 1..{MAX_VARIANTS:,}, got {samples}")
        rng = np.random.default_rng(0 if seed is None else seed)
        columns = []
        for s in specs:
            a, b = s.numbers
            draw = rng.normal(a, b, samples) if s.kind == "normal" else rng.uniform(a, b, samples)
            columns.append([float(v) for v in draw])
        variants = tuple(Variant(i + 1, str(i + 1), tuple(zip(names, row)))
                         for i, row in enumerate(zip(*columns)))
        return Design(names, variants, "random")
    if samples is not None or seed is not None:
        raise SceneError(f"{flag('samples', cli)} and {flag('seed', cli)} go with a random spec "
                         + ("(--vary NAME=normal:MEAN:SD or NAME=uniform:LO:HI)" if cli else
                            "(vary={NAME: 'normal:MEAN:SD'} or 'uniform:LO:HI')"))
    if not specs:
        raise SceneError("nothing to vary: give --vary NAME=SPEC (repeatable) or --design FILE"
                         if cli else "nothing to vary: give vary={NAME: values} or design=FILE")
    levels = tuple(s.numbers for s in specs)
    count = math.prod(len(v) for v in levels)
    if count > MAX_VARIANTS:
        raise SceneError(f"{flag('vary', cli)}: {count:,} variants in the full factorial, more "
                         f"than {MAX_VARIANTS:,}")
    variants = tuple(Variant(i + 1, str(i + 1), tuple(zip(names, row)))
                     for i, row in enumerate(itertools.product(*levels)))
    return Design(names, variants, "grid", levels, varied_options)


def _blank(value: object) -> bool:
    return value is None or (isinstance(value, str) and not value.strip())


def _cell_value(where: str, cell: object, option: OptionSpec | None, comma: bool) -> object:
    """A design cell as a parameter's float or an option's value."""
    if option is not None:
        return option_value(where, option, cell)
    if isinstance(cell, bool) or not isinstance(cell, (int, float, str)):
        raise SceneError(f"{where}: not a number: {cell!r}")
    text = decimal_comma(cell) if comma else cell
    try:
        value = float(text)
    except ValueError:
        raise SceneError(f"{where}: not a number: {cell!r}") from None
    if not math.isfinite(value):
        raise SceneError(f"{where}: must be finite, got {cell!r}")
    return value


def from_design(path: str | Path, parameters: Sequence[str], sets: Sequence[str] = (),
                options: Sequence[OptionSpec] = (), cli: bool = True) -> Design:
    """One variant per row of a CSV (``,`` or ``;``) or xlsx design table."""
    path = Path(path)
    by_name = {o.name: o for o in options}
    where = f"{flag('design', cli)} {path}"
    rows, comma = design_rows(path, where)
    rows = [row for row in rows if not all(_blank(v) for v in row)]
    if not rows:
        raise SceneError(f"{where}: empty; the first row names the parameters")
    header = [str(h).strip() if not _blank(h) else "" for h in rows[0]]
    while header and not header[-1]:
        header.pop()
    if "" in header:
        raise SceneError(f"{where}: column {header.index('') + 1} of the header is empty")
    label_col = header.index("variant") if "variant" in header else None
    names = [h for h in header if h != "variant"]
    if header.count("variant") > 1:
        raise SceneError(f"{where}: two 'variant' columns")
    if not names:
        raise SceneError(f"{where}: the header names no parameter")
    _check_names(names, parameters, list(by_name), sets,
                 lambda name: f"{where}: column {name!r}", cli)
    if len(rows) - 1 > MAX_VARIANTS:
        raise SceneError(f"{where}: {len(rows) - 1:,} rows, more than {MAX_VARIANTS:,}")
    variants = []
    for r, row in enumerate(rows[1:], start=2):
        row = list(row) + [None] * (len(header) - len(row))
        if any(not _blank(v) for v in row[len(header):]):
            raise SceneError(f"{where}: row {r} has more cells than the header")
        values = []
        for c, name in enumerate(header):
            cell = row[c]
            if c == label_col or _blank(cell):
                continue
            values.append((name, _cell_value(f"{where}: row {r}, {name}", cell,
                                             by_name.get(name), comma)))
        label = str(row[label_col]).strip() if label_col is not None and not _blank(
            row[label_col]) else str(r - 1)
        if len(label.encode("utf-16-le")) // 2 > MAX_CELL_TEXT:
            raise SceneError(f"{where}: row {r}, variant: a name of {len(label):,} "
                             f"characters, more than the {MAX_CELL_TEXT:,} an Excel cell holds")
        variants.append(Variant(r - 1, label, tuple(values)))
    return Design(tuple(names), tuple(variants), "design",
                  options=tuple(n for n in names if n in by_name))
