"""The table of worksheet functions: one :class:`Function` entry per name, with its family:
the package of :mod:`workbook_gen.formula.functions` whose module registers it
(:data:`FAMILIES`, after Excel's categories; :func:`family_of`).

An entry says how many arguments the function takes, what kind each is, and gives the
scalar form (and, where the column evaluator has one, the vectorised form):

* ``scalar``: the argument arrives as one value (a 1x1 reference is its cell; a larger
  reference is implicitly intersected with the formula's row or column, else #VALUE!);
* ``range``: a :class:`~workbook_gen.formula.values.Range` (with ``.ref`` when it is a
  reference) or a single value: SUM, COUNTIF, VLOOKUP tables;
* ``ref``: as ``range``, but the function reads the reference itself (ROW, OFFSET),
  not only its values;
* ``lazy``: a thunk, called only if needed (IF, IFERROR, CHOOSE).

``kinds`` gives one kind per position; the last repeats for further arguments. A call
with too few or too many arguments is #VALUE! (Excel refuses to enter it).

``fn(ctx, *args)`` receives a :class:`Context`: the dialect, the calling cell and a way
to read other references (OFFSET, INDIRECT). The vectorised form ``vector(xs, n)``
takes ``[(val, err), ...]`` float/uint8 arrays and returns ``(val, err, boolean)`` or
None where it cannot be exact (the caller then goes cell by cell).
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from typing import Callable

from workbook_gen.formula.resolver import NO_WORKBOOK, Resolver
from workbook_gen.formula.values import Range, Ref, Value, scalar_of
from workbook_gen.xlerror import ExcelError

KINDS = frozenset({"scalar", "range", "ref", "lazy"})
#: the families, each a package of this one, after Excel's own categories (Microsoft's
#: "Excel functions (by category)"; its Compatibility functions sit with their successors)
FAMILIES = ("math", "statistical", "engineering", "financial", "date", "text", "logical",
            "lookup", "information", "database", "cube")
DIALECTS = ("excel", "libreoffice")


class RowDependent(Exception):
    """Raised (only when ``Context.intersect`` is False) where a value would need implicit
    intersection with the calling cell: a column evaluator computing a part of a formula
    once for all rows learns that the part depends on the row after all."""


class Unanswered(Exception):
    """Raised where a value is read from a cache the file keeps of something outside it
    (an OLAP cube, another workbook) and the file does not hold it: the cell, and what
    reads it, is "not checked" with ``str(exc)`` as the reason (never a guessed value)."""


@dataclass
class Context:
    """What a function may know about its call.

    ``cell`` is ``(sheet, row, col)`` of the formula (None when unknown); ``resolver``
    reads cells and ranges (a formula.resolver.Resolver; None without a workbook, where a
    reference is #REF!); ``dialect`` is "excel" or "libreoffice"; ``parse_ref`` turns text
    into a Ref or None (INDIRECT).
    """

    dialect: str = "excel"
    cell: tuple[str, int, int] | None = None
    resolver: Resolver | None = None
    parse_ref: Callable[[str], Ref | None] | None = None
    intersect: bool = True

    @property
    def workbook(self) -> Resolver:
        """What the workbook says of itself (hidden rows, sheets, caches...): the
        resolver, or every Resolver default when there is none."""
        return NO_WORKBOOK if self.resolver is None else self.resolver

    def read(self, ref: Ref) -> Range | ExcelError:
        """The values of ``ref`` (a Range carrying ``ref``), or #REF! if unreadable."""
        if self.resolver is None:
            return ExcelError.REF
        if not (1 <= ref.row1 <= ref.row2 <= 1_048_576 and 1 <= ref.col1 <= ref.col2 <= 16_384):
            return ExcelError.REF
        rows = self.resolver.range(ref.sheet, ref.row1, ref.col1, ref.row2, ref.col2)
        rng = rows if isinstance(rows, Range) else Range.of(rows)
        return rng.with_ref(ref)

    def scalar(self, v) -> Value:
        """One value for a scalar argument: implicit intersection of a reference with the
        calling cell's row (a one-column range) or column (a one-row range)."""
        if isinstance(v, Range) and v.shape != (1, 1) and v.ref is not None and self.cell:
            if not self.intersect:
                raise RowDependent(v.ref)
            ref, (_, row, col) = v.ref, self.cell
            same_sheet = True  # Excel intersects with the row/column on any sheet
            # (koala__basic.xlsx: Sheet2!B2 =Liste2, a range of Sheet1, cached 20 = B2's)
            if same_sheet and ref.col1 == ref.col2 and ref.row1 <= row <= ref.row2:
                return v.rows[row - ref.row1][0]
            if same_sheet and ref.row1 == ref.row2 and ref.col1 <= col <= ref.col2:
                return v.rows[0][col - ref.col1]
            return ExcelError.VALUE
        return scalar_of(v)


@dataclass(frozen=True)
class Function:
    name: str
    family: str                   # the family package that registers it (see :func:`register`)
    fn: Callable
    min_args: int
    max_args: int | None          # None: any number (Excel's limit is 255)
    kinds: tuple[str, ...]
    volatile: bool = False
    vector: Callable | None = None
    position: bool = False        # reads the calling cell's position (ROW(), COLUMN())
    range_numbers: bool = False   # its ranges keep only numbers (SUM): booleans skipped
    omitted: bool = False         # an omitted argument (LINEST(y,,FALSE)) arrives as None, not 0
    accepts: Callable | None = None  # accepts(arg nodes): False where it cannot compute the call
    module: str = ""              # the module that registers it ("statistical.fit")

    def kind(self, i: int) -> str:
        return self.kinds[min(i, len(self.kinds) - 1)] if self.kinds else "scalar"

    @property
    def lazy(self) -> bool:
        return "lazy" in self.kinds


REGISTRY: dict[str, Function] = {}
# arguments that an array formula maps over although the function reads them as a whole
# (the criteria of SUMIF, COUNTIFS...): name -> which argument positions
ARRAY_LIFTED: dict[str, Callable[[int], bool]] = {}


def family_of(module: str) -> tuple[str, str]:
    """``(family, module)`` of a registering module's dotted name: the family is the package
    directly under this one (``...functions.statistical.fit`` -> ``("statistical",
    "statistical.fit")``). Only family packages register; anything else is refused."""
    prefix = __name__.rpartition(".")[0] + "."
    inner = module[len(prefix):] if module.startswith(prefix) else ""
    family, dot, rest = inner.partition(".")
    if not dot or not rest or family not in FAMILIES:
        raise ValueError(f"functions are registered from a family package of {prefix[:-1]}, "
                         f"not from {module}")
    return family, inner


def register(name: str, min_args: int, max_args: int | None = None,
             kinds: tuple[str, ...] | str = "scalar", *, volatile: bool = False,
             vector: Callable | None = None, position: bool = False,
             range_numbers: bool = False, aliases=(), omitted: bool = False,
             accepts: Callable | None = None):
    """Decorator: add ``fn`` to the registry under ``name`` (and ``aliases``).

    The family is not written by hand: it is the family package of the module calling
    ``register`` (:func:`family_of`), so a function's family is where it is defined."""
    family, module = family_of(sys._getframe(1).f_globals["__name__"])
    if isinstance(kinds, str):
        kinds = (kinds,)
    assert set(kinds) <= KINDS, kinds
    max_args = min_args if max_args is None else max_args
    if max_args == -1:
        max_args = None

    def deco(fn):
        for n in (name, *aliases):
            REGISTRY[n] = Function(n, family, fn, min_args, max_args, kinds, volatile,
                                   vector, position, range_numbers, omitted, accepts, module)
        return fn
    return deco


def arity_ok(entry: Function, n: int) -> bool:
    return n >= entry.min_args and (entry.max_args is None or n <= entry.max_args)


def call(name: str, args: list, ctx: Context | None = None) -> Value | Range:
    """Apply the function ``name`` (registered; upper-case, no prefix) to its arguments:
    values or Ranges, or thunks for lazy kinds. Scalar-kind arguments are reduced to one
    value here (implicit intersection)."""
    entry = REGISTRY[name]
    ctx = ctx or Context()
    if not arity_ok(entry, len(args)):
        if ctx.dialect == "libreoffice":  # an argument's error first (LibreOffice 7.4:
            # FLOOR(undefined_name,1,2) is #NAME?, FLOOR(1.2,1,2) #VALUE!)
            first = next((a for a in args if isinstance(a, ExcelError)), None)
            if first is not None:
                return first
        return ExcelError.VALUE
    if not entry.lazy:
        args = [ctx.scalar(a) if entry.kind(i) == "scalar" else a for i, a in enumerate(args)]
        if ctx.dialect == "libreoffice":  # no boolean type there: TRUE is the number 1
            args = [float(a) if isinstance(a, bool) else a for a in args]
    try:
        return entry.fn(ctx, *args)
    except ZeroDivisionError:
        return ExcelError.DIV0
    except (ValueError, ArithmeticError):  # a math domain or range error, decimal's too
        return ExcelError.NUM
